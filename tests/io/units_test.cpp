// Units (issue 29): the reader honours '# units: x=mm' (and um, and the "x [mm]" form), and a
// recording whose speeds or travel are implausible for a stage draws a warning naming the likely
// unit and the fix.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>
#include <string>

#include "support/test_support.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

using sysid::test::RunCli;

namespace {

// The bundled pulse test with x (and v, a) written in another unit, optionally declared.
std::string ScaledPulses(const sysid::test::TempDir& dir, const std::string& name, double factor,
                         const std::string& units_line) {
  sysid::Recording r = sysid::ReadRecording(sysid::test::SourcePath("datasets/virtual/pulses.csv"));
  for (const char* c : {"x", "v", "a"}) r.data.col(r.index_of(c)) *= factor;
  r.metadata.clear();
  if (!units_line.empty()) r.metadata.emplace_back("units", units_line);
  const std::string path = dir / name;
  sysid::WriteRecording(path, r);
  return path;
}

}  // namespace

TEST_CASE("the reader converts columns declared in mm or um to SI", "[io]") {
  const auto csv = [](const std::string& units) {
    return "# units: " + units + "\nt,u,x,v\n0,0,1000,2\n0.001,1,2000,4\n";
  };
  for (const auto& [units, factor] :
       {std::pair<std::string, double>{"x=mm, v=mm/s", 1e-3}, {"t [s], x [um], v [um/s]", 1e-6},
        {"x = motor position [mm], v = speed [mm/s]", 1e-3}, {"x [m], v [m/s]", 1.0}}) {
    const sysid::Recording r = sysid::ParseRecording(csv(units), "mm.csv");
    CHECK(r.column("x")[1] == Approx(2000 * factor).epsilon(1e-15));  // exact scaling
    CHECK(r.column("v")[0] == Approx(2 * factor).epsilon(1e-15));
    CHECK(r.column("t")[1] == 0.001);
    if (factor != 1.0) CHECK(r.meta("units").find("x [m]") != std::string::npos);
  }
  CHECK_THROWS_AS(sysid::ParseRecording(csv("x=inch"), "in.csv"), sysid::InputError);
  CHECK_THROWS_WITH(sysid::ParseRecording(csv("x=inch"), "in.csv"),
                    Catch::Matchers::Contains("in.csv:1:1: '# units:' metadata: column 'x' in "
                                              "'inch': expected one of"));
  // Columns the model does not read keep their remarks (a reader is not a unit library).
  CHECK_NOTHROW(sysid::ParseRecording(csv("x [m], f_pulse = applied force [N]"), "f.csv"));
}

TEST_CASE("x in mm read as metres draws a warning naming mm and the fix", "[io]") {
  sysid::test::TempDir dir;
  const std::string mm = ScaledPulses(dir, "pulses_mm.csv", 1e3, "");
  const auto warnings = sysid::UnitSanityWarnings(sysid::ReadRecording(mm));
  std::string all;
  for (const auto& w : warnings) all += w + "\n";
  CHECK(all.find("more than the 5 m/s a stage reaches") != std::string::npos);
  CHECK(all.find("'# units: x=mm'") != std::string::npos);
  // The bundled recordings are in metres: no warning (no false alarm on the real thing).
  CHECK(sysid::UnitSanityWarnings(
            sysid::ReadRecording(sysid::test::SourcePath("datasets/virtual/pulses.csv")))
            .empty());
  // Declared, the same file reads as the SI one: no warning and the same identified model.
  const std::string declared = ScaledPulses(dir, "declared.csv", 1e3, "x=mm, v=mm/s, a=mm/s^2");
  CHECK(sysid::UnitSanityWarnings(sysid::ReadRecording(declared)).empty());
  const auto si = RunCli({"identify", "--a3", "6", "--json",
                          sysid::test::SourcePath("datasets/virtual/pulses.csv")});
  const auto from_mm = RunCli({"identify", "--a3", "6", "--json", declared});
  REQUIRE(si.exit_code == 0);
  REQUIRE(from_mm.exit_code == 0);
  const auto a = nlohmann::json::parse(si.out), b = nlohmann::json::parse(from_mm.out);
  CHECK(b["a1p"].get<double>() == Approx(a["a1p"].get<double>()).epsilon(1e-9));  // rounding
  CHECK(b["a2n"].get<double>() == Approx(a["a2n"].get<double>()).epsilon(1e-9));
}

TEST_CASE("sysid identify --a3 6 pulses_mm.csv warns about the unit (issue 29)", "[io][cli]") {
  sysid::test::TempDir dir;
  const std::string mm = ScaledPulses(dir, "pulses_mm.csv", 1e3, "");
  const auto r = RunCli({"identify", "--a3", "6", mm});
  CHECK(r.err.find("sysid: warning: " + mm + ": x moves at up to") != std::string::npos);
  CHECK(r.err.find("if x is in mm, declare it with a '# units: x=mm' line") != std::string::npos);
  CHECK(r.err.find("if v is in mm/s, declare it with a '# units: v=mm/s' line") !=
        std::string::npos);
  const auto info = RunCli({"info", mm});
  CHECK(info.exit_code == 0);
  CHECK(info.err.find("'# units: x=mm'") != std::string::npos);
}
