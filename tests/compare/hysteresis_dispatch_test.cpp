#include <catch2/catch.hpp>
#include <cmath>

#include "sysid/compare_hysteresis.hpp"
#include "sysid/error.hpp"

TEST_CASE("FitHysteresis dispatches by kind and ReadHysteresisModel reads any file back",
          "[compare]") {
  const int n = 800;
  sysid::Recording rec;
  rec.source = "d.csv";
  rec.names = {"t", "u", "x"};
  rec.data.resize(n, 3);
  for (int k = 0; k < n; ++k) {
    const double u = 1 + std::sin(0.05 * k) * (1 + 0.5 * std::cos(0.003 * k));
    rec.data.row(k) << k * 0.005, u, 1e-6 * u * u;  // anything smooth: the dispatch is tested
  }
  for (const std::string kind : {"pi", "gpi", "rdpi"}) {
    sysid::HysteresisFitOptions o;
    o.operators = 4;
    sysid::HysteresisFitSummary s;
    const auto m = sysid::FitHysteresis(kind, {rec}, o, &s);
    CHECK(m->kind() == kind);
    CHECK(s.kind == kind);
    const auto back = sysid::HysteresisModelFromJson(m->ToJson(), "m.json");
    CHECK(back->kind() == kind);
    const Eigen::VectorXd u = rec.column("u");
    CHECK(back->Simulate(u, 0.005) == m->Simulate(u, 0.005));
  }
  {  // bouc-wen-piezo is fitted through the door (a few seconds on these 800 samples)
    sysid::HysteresisFitSummary s;
    const auto m = sysid::FitHysteresis("bouc-wen-piezo", {rec}, {}, &s);
    CHECK(m->kind() == "bouc-wen-piezo");
    CHECK(s.kind == "bouc-wen-piezo");
    const auto back = sysid::HysteresisModelFromJson(m->ToJson(), "m.json");
    const Eigen::VectorXd u = rec.column("u");
    CHECK(back->Simulate(u, 0.005) == m->Simulate(u, 0.005));
  }
  {  // bouc-wen (mechanical): its fit is the benchmark's (tests/hysteresis); here the file door
    sysid::MechanicalBoucWenParameters p;  // the benchmark's defaults
    const sysid::MechanicalBoucWen m(p);
    const auto back = sysid::HysteresisModelFromJson(m.ToJson(), "m.json");
    CHECK(back->kind() == "bouc-wen");
    const Eigen::VectorXd u = 50 * rec.column("u");  // a force [N]
    CHECK(back->Simulate(u, 0.005) == m.Simulate(u, 0.005));
  }
  CHECK_THROWS_AS(sysid::FitHysteresis("preisach", {rec}), sysid::OptionsError);
  CHECK_THROWS_WITH(sysid::HysteresisModelFromJson("{\"kind\": \"preisach\"}", "p.json"),
                    Catch::Contains("p.json:1:") && Catch::Contains("kind"));
  sysid::HysteresisFitOptions too_many;
  too_many.operators = sysid::kMaxPlayOperators + 1;
  CHECK_THROWS_WITH(sysid::FitHysteresis("pi", {rec}, too_many), Catch::Contains("operators"));
}
