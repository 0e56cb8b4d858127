// Issue #12's acceptance: the default stage meets the paper's facts F1-F3 and F6, F4, and F5's
// controller ordering against PI, as computed by `sysid stage facts --json` (never stored); the
// actuator-delay preset does not. Issue #28's: the default meets F8 too (its drive hysteresis).
// The default is the loop-rate candidate C (10 kHz loop, 1 kHz records, 0.1 ms driver lag) with
// the ceramic's play operators and creep (P2): issue #26's F4 in motion does not ring at the
// 1 kHz loop's ~80 Hz (docs/virtual_stage.md, "Loop rate"); the error's jump at each stroke's
// onset is F5's, not F4's. F5's NN-vs-analytic order is not asserted: it depends on the trained
// network (docs/virtual_stage.md, "Measured").
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.hpp"

namespace {

const nlohmann::json* FindFact(const nlohmann::json& j, const std::string& id) {
  for (const auto& f : j["facts"])
    if (f["id"] == id) return &f;
  return nullptr;
}

}  // namespace

TEST_CASE("the default stage meets F1-F4, F6, F8 and F5's ordering against PI",
          "[stage][facts][cli]") {
  // --reduced shortens delay tuning and trains a small network (8 hidden units, 15 epochs) so
  // that this runs in seconds under the sanitizers; F1-F4 and F6 are the full experiments, F5's
  // PI and analytic rows too, its NN row uses the reduced network (the full 24-unit run is
  // `sysid stage facts`, docs/virtual_stage.md). F7 is reported only, so not asked here. One
  // thread: the training's result is then reproducible (measured: identical over repeated runs).
  const auto r = sysid::test::RunCli({"stage", "facts", "--json", "--reduced", "--threads", "1",
                                      "--facts", "F1,F2,F3,F4,F5,F6,F8"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["facts"].size() == 7);
  for (const char* id : {"F1", "F2", "F3", "F6", "F8"}) {
    const auto* f = FindFact(j, id);
    REQUIRE(f != nullptr);
    INFO(id << ": " << (*f)["virtual"].get<std::string>() << " (tolerance "
            << (*f)["tolerance"].get<std::string>() << ")");
    CHECK((*f)["required"] == true);
    CHECK((*f)["met"] == true);
  }
  // F5: PI alone is the worst at both frequencies; PI and analytic are within a factor 3 of the
  // paper's table (0.10651 / 0.03609 / 0.01779 mm at 0.5 Hz, 0.17156 / 0.10579 / 0.07292 at 1 Hz)
  // and the reduced network's row is at most 3x the paper's. Not its lower bound: on the 10 kHz
  // loop the reduced network's 1 Hz row can be better than a third of the paper's 0.07292 mm
  // (measured on C, the default before the drive hysteresis: 0.0235 mm).
  const auto& f5 = (*FindFact(j, "F5"))["values"];
  const double paper[2][3] = {{0.10651e-3, 0.03609e-3, 0.01779e-3},
                              {0.17156e-3, 0.10579e-3, 0.07292e-3}};
  const char* freq[2] = {"0.5 Hz", "1 Hz"};
  const char* scheme[3] = {"none", "analytic", "nn"};
  for (int i = 0; i < 2; ++i) {
    double e[3];
    for (int k = 0; k < 3; ++k) {
      const std::string key = std::string("max_error_m at ") + freq[i] + " " + scheme[k];
      REQUIRE(f5.contains(key));
      e[k] = f5[key].get<double>();
      INFO(key << " = " << e[k] << " m, paper " << paper[i][k] << " m");
      CHECK(e[k] <= 3 * paper[i][k]);
      if (k < 2) CHECK(e[k] >= paper[i][k] / 3);
    }
    CHECK(e[0] > e[1]);
    CHECK(e[0] > e[2]);
  }
  // F4: quiet at rest (dwell ripple <= 1 um, nothing clipped) and in motion (RMS ripple with
  // each stroke's breakaway transient left out <= 5 um, measured 4.0 / 2.05 um at 0.5 / 1 Hz;
  // the 1 kHz loop rings at ~80 Hz with 18.6 / 27.1 um by the same metric).
  const auto& f4 = *FindFact(j, "F4");
  for (const char* hz : {"0.5 Hz", "1 Hz"}) {
    const auto& v = f4["values"];
    INFO(hz << ": " << f4["virtual"].get<std::string>());
    CHECK(v[std::string("ripple_m at ") + hz].get<double>() <= 1e-6);
    CHECK(v[std::string("clipped_samples at ") + hz].get<double>() == 0);
    CHECK(v[std::string("motion_ripple_m at ") + hz].get<double>() <= 5e-6);
  }
  CHECK(f4["met"] == true);
  // F3's numbers themselves: tau in 2.5-4.5 ms.
  const auto& f3 = (*FindFact(j, "F3"))["values"];
  REQUIRE(f3.contains("tau_s"));
  CHECK(f3["tau_s"].get<double>() >= 0.0025);
  CHECK(f3["tau_s"].get<double>() <= 0.0045);
}

TEST_CASE("the actuator-delay preset runs and fails the delay and gain facts",
          "[stage][facts][cli]") {
  // The preset by name.
  const auto r = sysid::test::RunCli({"stage", "facts", "--json", "--reduced", "--threads", "2",
                                      "--stage", "actuator-delay", "--facts", "F3,F4"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  // On the actuator-delay stage tau-hat = 0 (its delay is in the actuator path) and the
  // paper's gains limit-cycle at +-10 V.
  CHECK((*FindFact(j, "F3"))["met"] == false);
  CHECK((*FindFact(j, "F4"))["met"] == false);
  CHECK(j["required_met"] == false);
}
