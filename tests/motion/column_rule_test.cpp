// One rule for a recording's v and a columns (issue 29), in the library and every command: the
// columns as they are when present; --derivative (prefer_velocity_column = false) derives them
// from x. The reference for "derived" is Differentiate on x, for "columns" the columns.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "support/test_support.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/motion.hpp"
#include "sysid/signal.hpp"

using sysid::test::RunCli;

namespace {

// x = c t^2 with v, a columns that are NOT its derivatives (3 v_true, 5 a_true), so a result
// tells at once which source was used.
sysid::Recording Marked(int n, double dt) {
  sysid::Recording r;
  r.source = "marked";
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(n, 0.0, (n - 1) * dt);
  r.SetColumn("t", t);
  r.SetColumn("u", Eigen::VectorXd::Zero(n));
  r.SetColumn("x", (0.5 * t.array().square()).matrix());
  r.SetColumn("v", (3.0 * t).eval());
  r.SetColumn("a", Eigen::VectorXd::Constant(n, 5.0));
  return r;
}

}  // namespace

TEST_CASE("ExtractMotion uses the v, a columns unless told to derive from x", "[motion]") {
  const sysid::Recording r = Marked(200, 1e-3);
  const sysid::MotionSignals cols = sysid::ExtractMotion(r);  // the default
  CHECK(cols.velocity_from == "columns v, a");
  CHECK(cols.v_mps == r.column("v"));  // the columns exactly, no filter
  CHECK(cols.a_mps2 == r.column("a"));

  sysid::MotionOptions derive;
  derive.prefer_velocity_column = false;
  const sysid::MotionSignals fromx = sysid::ExtractMotion(r, derive);
  CHECK(fromx.velocity_from == "x (central)");
  const sysid::Derivatives ref = sysid::Differentiate(r.column("x"), 1e-3, derive.derivative);
  CHECK(fromx.v_mps.isApprox(ref.v_mps, 1e-14));  // the same computation
  CHECK(fromx.a_mps2.isApprox(ref.a_mps2, 1e-14));
  CHECK(fromx.a_mps2[100] == Approx(1.0).epsilon(1e-6));  // x'' = 1 for x = t^2 / 2

  // Only v: a is v's derivative by the filter (3 for v = 3 t).
  sysid::Recording only_v = r;
  only_v.names.pop_back();
  only_v.data.conservativeResize(Eigen::NoChange, only_v.data.cols() - 1);
  const sysid::MotionSignals v_only = sysid::ExtractMotion(only_v);
  CHECK(v_only.velocity_from == "column v (a: central)");
  CHECK(v_only.a_mps2[100] == Approx(3.0).epsilon(1e-9));
  CHECK(sysid::MotionSource(r, derive) == "x (central)");
}

TEST_CASE("dominance and compare use derive's columns and say so, --derivative re-derives",
          "[motion][cli]") {
  // The case: v, a from `derive --method butterworth` used to give the raw file's
  // numbers in dominance (it re-derived) and the columns' in compare.
  sysid::test::TempDir dir;
  const std::string raw = sysid::test::SourcePath("datasets/virtual/training.csv");
  const std::string va = dir / "training_va.csv";
  REQUIRE(RunCli({"derive", raw, "--method", "butterworth", "--cutoff", "50", "-o", va})
              .exit_code == 0);
  sysid::WriteModel(dir / "m.json", sysid::FrictionModel::Paper());
  auto dominance = [&](std::vector<std::string> extra, const std::string& file) {
    std::vector<std::string> args{"dominance", "--model", dir / "m.json", "--json", file};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = RunCli(args);
    REQUIRE(r.exit_code == 0);
    auto j = nlohmann::json::parse(r.out);
    return std::make_pair(j["recordings"][0]["ranking"], r.err);
  };
  // x is the same in both files (derive keeps it): re-derived, they must agree exactly.
  const auto [raw_derived, raw_err] = dominance({"--derivative", "central"}, raw);
  const auto [va_rank, va_err] = dominance({}, va);
  const auto [va_derived, va_derived_err] = dominance({"--derivative", "central"}, va);
  CHECK(va_err.find("sysid: v, a: columns v, a of the recording as they are") !=
        std::string::npos);
  CHECK(va_derived_err.find("sysid: v, a: x (central)") != std::string::npos);
  CHECK(raw_err.find("sysid: v, a: x (central)") != std::string::npos);
  CHECK(va_rank != raw_derived);  // the Butterworth columns, not a re-derivation
  CHECK(va_derived == raw_derived);

  auto compare = [&](std::vector<std::string> extra) {
    std::vector<std::string> args{"compare", "--model", dir / "m.json", "--json", va};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = RunCli(args);
    REQUIRE(r.exit_code == 0);
    return nlohmann::json::parse(r.out)["recordings"][0];
  };
  const auto cols = compare({});
  const auto derived = compare({"--derivative", "central"});
  CHECK(cols["v_a_from"] == "columns v, a");
  CHECK(derived["v_a_from"] == "x (central)");
  CHECK(cols["analytic"] != derived["analytic"]);
}
