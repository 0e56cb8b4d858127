#include <catch2/catch.hpp>

#include <string>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/model.hpp"

TEST_CASE("a model file round-trips and validates", "[model]") {
  const auto paper = sysid::FrictionModel::Paper();
  const auto back = sysid::ParseModel(sysid::ModelToJson(paper), "mem");
  CHECK(back.a1p == paper.a1p);
  CHECK(back.a2n == paper.a2n);
  CHECK(back.tau_s == paper.tau_s);
}

TEST_CASE("a model file keeps its published keys, order and units", "[model]") {
  // The text the hand-written writer produced before the model was described (Serialize).
  CHECK(sysid::ModelToJson(sysid::FrictionModel::Paper(), -1) ==
        R"j({"a1p":104.0154,"a1n":117.1441,"a2p":3.1023,"a2n":6.8216,"a3":6.0,"tau":0.0035,)j"
        R"j("units":{"a1p":"1/s","a1n":"1/s","a2p":"m/s^2","a2n":"m/s^2","a3":"m/(s^2 V)",)j"
        R"j("tau":"s"}})j"
        "\n");
  // tau may be left out (no delay); the coefficients may not.
  CHECK(sysid::ParseModel(R"({"a1p":1,"a1n":1,"a2p":1,"a2n":1,"a3":6})", "m.json").tau_s == 0.0);
  CHECK_THROWS_WITH(sysid::ParseModel(R"({"a1n":1,"a2p":1,"a2n":1,"a3":6,"tau":0})", "m.json"),
                    Catch::StartsWith("m.json:1:1: missing required key 'a1p'"));
}

TEST_CASE("model file errors name the place and the rule", "[model][errors]") {
  CHECK_THROWS_WITH(sysid::ParseModel("{\"a1p\": 1,\n \"a1n\": }", "m.json"),
                    Catch::StartsWith("m.json:2:9: invalid JSON"));
  CHECK_THROWS_WITH(
      sysid::ParseModel(R"({"a1p":1,"a1n":1,"a2p":1,"a2n":1,"a3":6,"tua":0.1})", "m.json"),
      Catch::Contains("m.json:1:41: unknown key 'tua'"));
  CHECK_THROWS_WITH(sysid::ParseModel(R"({"a1p":1,"a1n":1,"a2p":1,"a3":6})", "m.json"),
                    Catch::StartsWith("m.json:1:1: missing required key 'a2n'"));
  CHECK_THROWS_WITH(
      sysid::ParseModel(R"({"a1p":"1","a1n":1,"a2p":1,"a2n":1,"a3":6})", "m.json"),
      Catch::Equals("m.json:1:2: a1p: expected a number >= 0, found string \"1\""));
  // Every value error is positioned and says what was expected and what was found.
  CHECK_THROWS_WITH(
      sysid::ParseModel(R"({"a1p":-1,"a1n":1,"a2p":1,"a2n":1,"a3":6})", "m.json"),
      Catch::Equals("m.json:1:2: a1p: expected a number >= 0, found -1"));
  CHECK_THROWS_WITH(
      sysid::ParseModel("{\"a1p\":1,\"a1n\":1,\"a2p\":1,\"a2n\":1,\n  \"a3\":0}", "m.json"),
      Catch::Equals("m.json:2:3: a3: expected a number > 0, found 0"));
  CHECK_THROWS_WITH(
      sysid::ParseModel(R"({"a1p":1,"a1n":1,"a2p":-0.5,"a2n":1,"a3":6})", "m.json"),
      Catch::Equals("m.json:1:18: a2p: expected a number >= 0, found -0.5"));
  CHECK_THROWS_WITH(
      sysid::ParseModel(R"({"a1p":1,"a1n":1,"a2p":1,"a2n":1,"a3":6,"tau":-1})", "m.json"),
      Catch::Equals("m.json:1:41: tau: expected a number in [0, 1], found -1"));
  CHECK_THROWS_WITH(sysid::ParseModel(R"({"a1p":1,"a1n":1,"a2p":1,"a2n":null,"a3":6})", "m.json"),
                    Catch::Equals("m.json:1:26: a2n: expected a number >= 0, found null"));
  CHECK_THROWS_WITH(sysid::ParseModel(R"([1, 2])", "m.json"),
                    Catch::StartsWith("m.json:1:1: expected an object with keys a1p, a1n"));
  // Control bytes of a hostile file never reach the terminal.
  CHECK_THROWS_WITH(
      sysid::ParseModel("{\"a1p\":\"\\u001b[2J\",\"a1n\":1,\"a2p\":1,\"a2n\":1,\"a3\":6}", "m.json"),
      Catch::Equals("m.json:1:2: a1p: expected a number >= 0, found string \"\\x1B[2J\""));
  // a1 = 0 is pure Coulomb friction, a valid model.
  CHECK(sysid::ParseModel(R"({"a1p":0,"a1n":0,"a2p":1,"a2n":1,"a3":6})", "m.json").a1p == 0.0);
  // Reports may ride along in a model file.
  CHECK_NOTHROW(sysid::ParseModel(
      R"({"a1p":1,"a1n":1,"a2p":1,"a2n":1,"a3":6,"diagnostics":{"x":1},"_c":"y"})", "m.json"));
}

TEST_CASE("steady velocity and analytic inverse agree with the paper's equations", "[model]") {
  const auto m = sysid::FrictionModel::Paper();
  // Closed forms from a1 v + a2 = a3 u per direction.
  CHECK(m.SteadyVelocity(1.6) == Approx((6 * 1.6 - 3.1023) / 104.0154).epsilon(1e-14));
  CHECK(m.SteadyVelocity(-2.3) == Approx((-6 * 2.3 + 6.8216) / 117.1441).epsilon(1e-14));
  CHECK(m.SteadyVelocity(0.5) == 0.0);  // 3 < a2p: friction holds
  // The inverse of a steady state gives back its voltage.
  const double v = m.SteadyVelocity(1.6);
  CHECK(m.InverseVoltage(0.0, v, v) == Approx(1.6).epsilon(1e-14));
  const double w = m.SteadyVelocity(-2.3);
  CHECK(m.InverseVoltage(0.0, w, w) == Approx(-2.3).epsilon(1e-14));
}
