// `sysid track --plant piezo-stack`: the chain generate -> hysteresis fit -> track through the
// program, the stack file detected by its "plant" key, and the errors: a bad stack file
// (positioned, exit 2), the stage's schemes on the stack and the stack's on the stage (exit 1),
// a reference outside the model's range (exit 2), nothing written.
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/stack.hpp"

using Catch::Contains;
using sysid::test::RunCli;
using sysid::test::SourcePath;
using sysid::test::TempDir;
using sysid::test::WriteText;

TEST_CASE("sysid track on the piezo stack: traces -> pi fit -> feedforward beats PI alone",
          "[stack][cli]") {
  TempDir dir;
  // A stack file with the exact integrator (fast), detected by its "plant" key.
  WriteText(dir / "stack.json",
            "{\"plant\": \"piezo-stack\", \"integrator\": {\"method\": \"exact\"}}");
  for (const char* f : {"2", "10", "40"}) {
    const auto r =
        RunCli({"track", "--plant", dir / "stack.json", "--ff", "none", "--freq", f, "--amplitude",
                "22e-6", "--seed", "2", "--no-plots", "-o", dir / (std::string("train_") + f)});
    REQUIRE(r.exit_code == 0);
    CHECK_THAT(r.out, Contains("gain 2.23, phase 92.6 deg, crossover 32.5 Hz"));
  }
  const auto fit = RunCli({"hysteresis", "fit", "--model", "pi", "--operators", "10",
                           dir / "train_2/track_none.csv", dir / "train_10/track_none.csv",
                           dir / "train_40/track_none.csv", "-o", dir / "pi.json"});
  REQUIRE(fit.exit_code == 0);
  const auto r =
      RunCli({"track", "--plant", dir / "stack.json", "--ff", "none,hysteresis", "--hysteresis",
              dir / "pi.json", "--waveform", "triangle", "--freq", "10", "--seed", "3", "--json"});
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["schemes"].size() == 2);
  const double none = j["schemes"][0]["rms_error_m"], ff = j["schemes"][1]["rms_error_m"];
  INFO("RMS e: PI alone " << none << " m, with the pi inverse " << ff << " m");
  CHECK(ff < 0.05 * none);  // docs/piezo_stack.md: 2.195 um and 0.027 um
  CHECK(j["schemes"][1]["stage_limits"] == "none");

  // The fitted model as the plant, ahead of the stack's mechanics: named in the JSON and the
  // table; its own inverse as feedforward still wins.
  const auto on_model = RunCli({"track", "--plant", dir / "pi.json", "--ff", "none,hysteresis",
                                "--hysteresis", dir / "pi.json", "--freq", "10", "--json"});
  REQUIRE(on_model.exit_code == 0);
  const auto jm = nlohmann::json::parse(on_model.out);
  CHECK(jm["plant"] == dir / "pi.json");
  CHECK(jm["schemes"][1]["rms_error_m"].get<double>() <
        0.05 * jm["schemes"][0]["rms_error_m"].get<double>());
  const auto named = RunCli({"track", "--plant", dir / "pi.json", "--freq", "10"});
  REQUIRE(named.exit_code == 0);
  CHECK_THAT(named.out, Contains("piezo stack with the hysteresis of " + dir / "pi.json"));

  // Out of the model's range: a reference twice the training stroke.
  const auto far = RunCli({"track", "--plant", "piezo-stack", "--ff", "hysteresis", "--hysteresis",
                           dir / "pi.json", "--amplitude", "40e-6", "-o", dir / "far"});
  CHECK(far.exit_code == 2);
  CHECK_THAT(far.err, Contains("outside the pi model's range"));
  CHECK_FALSE(std::filesystem::exists(dir / "far"));
  // The stage's schemes on the stack, the stack's on the stage, a missing model.
  CHECK(RunCli({"track", "--plant", "piezo-stack", "--ff", "analytic"}).exit_code == 1);
  CHECK(
      RunCli({"track", "--plant", "virtual", "--ff", "hysteresis", "--hysteresis", dir / "pi.json"})
          .exit_code == 1);
  CHECK_THAT(RunCli({"track", "--plant", "virtual", "--waveform", "triangle"}).err,
             Contains("--waveform is the piezo stack's reference"));
  CHECK_THAT(RunCli({"track", "--plant", "piezo-stack", "--ff", "hysteresis"}).err,
             Contains("--ff hysteresis needs --hysteresis"));
}

TEST_CASE("sysid track: a bad stack file is a positioned error, exit 2, nothing written",
          "[stack][cli]") {
  TempDir dir;
  WriteText(dir / "bad.json",
            "{\"plant\": \"piezo-stack\",\n \"mechanics\": {\"damping_ratio\": -0.1}}");
  const auto r = RunCli({"track", "--plant", dir / "bad.json", "-o", dir / "out"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("bad.json:2:16: mechanics.damping_ratio: expected damping_ratio in "
                             "[1e-4, 2], found -0.1"));
  CHECK_FALSE(std::filesystem::exists(dir / "out"));
  // The bundled file is the preset.
  const auto a = RunCli({"track", "--plant", SourcePath("datasets/piezo_stack/stack.json"),
                         "--cycles", "1", "--json"});
  const auto b = RunCli({"track", "--plant", "piezo-stack", "--cycles", "1", "--json"});
  REQUIRE(a.exit_code == 0);
  REQUIRE(b.exit_code == 0);
  CHECK(nlohmann::json::parse(a.out)["schemes"] == nlohmann::json::parse(b.out)["schemes"]);
}
