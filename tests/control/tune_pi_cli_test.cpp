// `sysid tune-pi` and `sysid track --plant M.json` through the program: the tuner's margins
// are those `sysid margins` prints for the same gains; the model plant is named in the table
// and the JSON; feedforward from another model shows the model error; wrong flag mixes are
// usage errors.
#include <catch2/catch.hpp>
#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>

#include "support/plot_index_check.hpp"
#include "support/test_support.hpp"

using Catch::Contains;
using sysid::test::RunCli;
using sysid::test::TempDir;
using sysid::test::TestData;
using sysid::test::WriteText;

TEST_CASE("tune-pi: the margins it reports are those of sysid margins", "[control][cli]") {
  const std::string model = TestData("control/twin_model.json");
  const auto tuned = RunCli({"tune-pi", "--model", model, "--loop-rate", "10000", "--json"});
  REQUIRE(tuned.exit_code == 0);
  const auto t = nlohmann::json::parse(tuned.out);
  CHECK(t["plant"] == model);
  const double kp = t["tuning"]["kp_v_per_m"], ki = t["tuning"]["ki_v_per_m_s"];
  const auto margins = RunCli({"margins", "--model", model, "--rate", "10000", "--kp",
                               nlohmann::json(kp).dump(), "--ki", nlohmann::json(ki).dump(),
                               "--json"});
  REQUIRE(margins.exit_code == 0);
  const auto m = nlohmann::json::parse(margins.out);
  for (int d = 0; d < 2; ++d) {
    const auto& a = t["tuning"]["margins"]["directions"][d];
    const auto& b = m["directions"][d];
    CHECK(a["direction"] == b["direction"]);
    for (const char* key : {"crossover_rad_s", "phase_margin_deg", "gain_margin_db"})
      CHECK(a[key].get<double>() == Approx(b[key].get<double>()).epsilon(1e-9));
  }
  // The weaker direction meets the target with equality (the highest crossover).
  const double pm0 = t["tuning"]["margins"]["directions"][0]["phase_margin_deg"],
               pm1 = t["tuning"]["margins"]["directions"][1]["phase_margin_deg"];
  CHECK(std::min(pm0, pm1) >= 45 - 1e-6);
  CHECK(t["behaviour"]["step"]["saturated_samples"] == 0);
  CHECK(t["behaviour"]["sine"]["limit_cycle"]["limit_cycle"] == false);

  const auto text = RunCli({"tune-pi", "--model", model});
  REQUIRE(text.exit_code == 0);
  CHECK_THAT(text.out, Contains("plant: " + model));
  CHECK_THAT(text.out, Contains("phase margin [deg]"));
  CHECK(RunCli({"tune-pi", "--model", model, "--phase-margin", "95"}).exit_code == 1);
}

TEST_CASE("track --plant M.json: the model as plant, named, with feedforward from another model",
          "[control][cli]") {
  TempDir dir;
  const std::string model = TestData("control/twin_model.json");
  const auto own = RunCli({"track", "--plant", model, "--ff", "none,analytic", "--freq", "1",
                           "--cycles", "1", "--kp", "1900", "--ki", "39000", "--json"});
  REQUIRE(own.exit_code == 0);
  const auto j = nlohmann::json::parse(own.out);
  CHECK(j["plant"] == model);
  CHECK_THAT(j["schemes"][0]["stage_limits"].get<std::string>(), Contains("model plant"));
  const double pi_alone = j["schemes"][0]["rms_error_m"], with_own = j["schemes"][1]["rms_error_m"];
  // The plant's own inverse: only the loop's sampling is left.
  CHECK(with_own < 0.01 * pi_alone);
  // The paper's model as feedforward on this plant: a model error the loop must absorb.
  WriteText(dir / "other.json",
            R"({"a1p": 80, "a1n": 140, "a2p": 2.5, "a2n": 8, "a3": 6, "tau": 0.002})");
  const auto other = RunCli({"track", "--plant", model, "--ff", "analytic", "--model",
                             dir / "other.json", "--freq", "1", "--cycles", "1", "--kp", "1900",
                             "--ki", "39000", "--json"});
  REQUIRE(other.exit_code == 0);
  const double with_other = nlohmann::json::parse(other.out)["rms_error_m"];
  INFO("RMS e: PI alone " << pi_alone << ", own model " << with_own << ", other " << with_other);
  CHECK(with_other > 5 * with_own);
  CHECK(with_other < pi_alone);

  const auto text = RunCli({"track", "--plant", model, "--freq", "1", "--cycles", "1"});
  REQUIRE(text.exit_code == 0);
  // -o: the plots' index passes the house's plot rules (one colour per scheme across them).
  const auto folder = RunCli({"track", "--plant", model, "--ff", "none,analytic", "--freq", "1",
                              "--cycles", "1", "-o", dir / "out"});
  REQUIRE(folder.exit_code == 0);
  CHECK(sysid::test::CheckPlotIndex(dir / "out") == 2);
  CHECK_THAT(text.out, Contains("plant: " + model + " (identified friction model"));
  const auto stage = RunCli({"track", "--plant", "virtual-1khz", "--freq", "1", "--cycles", "1"});
  REQUIRE(stage.exit_code == 0);
  CHECK_THAT(stage.out, Contains("plant: virtual"));
  CHECK(RunCli({"track", "--plant", "virtual", "--loop-rate", "1000"}).exit_code == 1);
  CHECK(RunCli({"track", "--plant", model, "--ff", "hysteresis"}).exit_code == 1);
}
