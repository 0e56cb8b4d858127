// Input signals: values (right-continuous), edges, pulse trains, named waveforms, table files.
#include "sysid/input.hpp"

#include <catch2/catch.hpp>
#include <cmath>

#include "support/test_support.hpp"
#include "sysid/error.hpp"

namespace sysid {
namespace {

TEST_CASE("zero-order hold is right-continuous and reports its jumps", "[input]") {
  const PiecewiseConstantInput u({0.0, 1.0, 2.0, 3.0}, {1.0, 2.0, 2.0, -1.0});
  CHECK(u.Value(-5) == 1.0);  // first value holds before the table
  CHECK(u.Value(0.999) == 1.0);
  CHECK(u.Value(1.0) == 2.0);  // a value given at t applies from t on
  CHECK(u.Value(3.0) == -1.0);
  CHECK(u.Value(99) == -1.0);
  CHECK(u.Edges(0.0, 10.0) == std::vector<double>{1.0, 3.0});  // 2.0 repeats the value
  CHECK(u.Edges(1.0, 2.9) == std::vector<double>{});           // (t0, t1]: 1.0 excluded
  CHECK(u.ConstantBetweenEdges());
}

TEST_CASE("linear interpolation reports its slope changes", "[input]") {
  const PiecewiseLinearInput u({0.0, 1.0, 2.0, 3.0}, {0.0, 1.0, 2.0, 0.0});
  CHECK(u.Value(0.5) == Approx(0.5));
  CHECK(u.Value(2.5) == Approx(1.0));
  CHECK(u.Value(-1) == 0.0);
  CHECK(u.Value(4) == 0.0);
  CHECK(u.Edges(-1.0, 5.0) == std::vector<double>{0.0, 2.0, 3.0});  // 1.0: same slope
}

TEST_CASE("the paper's pulse train", "[input]") {
  const PulseTrainSpec spec;
  CHECK(spec.duration_s() == Approx(10.0));
  const PiecewiseConstantInput u = MakePulseTrain(spec);
  CHECK(u.Value(-0.1) == 0.0);
  CHECK(u.Value(0.0) == 1.6);
  CHECK(u.Value(0.4) == 0.0);
  CHECK(u.Value(1.0) == -2.3);
  CHECK(u.Value(9.39) == -2.3);
  CHECK(u.Value(9.4) == 0.0);
  const auto edges = u.Edges(0.0, 10.0);
  REQUIRE(edges.size() == 19);  // 20 switches, the one at t = 0 is not in (0, 10]
  CHECK(edges[0] == 0.4);
  CHECK(edges[18] == 9.4);
  PulseTrainSpec bad;
  bad.on_s = 0;
  CHECK_THROWS_WITH(MakePulseTrain(bad),
                    Catch::Contains("PulseTrainSpec::on_s") && Catch::Contains("on_s > 0"));
}

TEST_CASE("a pulse train is bounded by the signal limit before allocation", "[input]") {
  PulseTrainSpec spec;
  spec.amplitudes_v = {1.0};
  spec.repeats = 2000000000;  // 4e9 table rows, 64 GB: refused at once
  CHECK_THROWS_WITH(MakePulseTrain(spec), Catch::Contains("PulseTrainSpec::repeats") &&
                                              Catch::Contains("<= 20000000 table rows") &&
                                              Catch::Contains("asked for 4000000000"));
  spec.repeats = 10000001;  // one pulse (two rows) past the limit
  CHECK_THROWS_WITH(MakePulseTrain(spec), Catch::Contains("asked for 20000002"));
  spec.off_s = 0;  // without rests one row a pulse: 3 x 6666667 = 20000001 rows
  spec.amplitudes_v = {1.0, -1.0, 2.0};
  spec.repeats = 6666667;
  CHECK_THROWS_AS(MakePulseTrain(spec), OptionsError);
  spec.repeats = 1000;
  CHECK(MakePulseTrain(spec).Value(0.1) == 1.0);
}

TEST_CASE("named waveforms", "[input]") {
  for (const auto& name : NamedWaveformNames()) {
    const NamedWaveform w = MakeNamedWaveform(name);
    CHECK(w.duration_s > 0);
    REQUIRE(w.signal);
  }
  const NamedWaveform sine = MakeNamedWaveform("paper-sine");
  // u = 1.5 sin(pi/2 t - pi/2) - 0.3: -1.8 V at t = 0, +1.2 V at t = 2 s.
  CHECK(sine.signal->Value(0) == Approx(-1.8));
  CHECK(sine.signal->Value(2) == Approx(1.2));
  CHECK(sine.signal->MaxStepHint() == Approx(0.2));  // 4 s period / 20
  const NamedWaveform tri = MakeNamedWaveform("paper-triangle");
  CHECK(tri.signal->Value(1.5) == Approx(1.5));
  CHECK(tri.signal->Value(4.5) == Approx(-2.1));
  CHECK_THROWS_WITH(MakeNamedWaveform("square"), Catch::Contains("paper-pulses"));
}

TEST_CASE("input tables from CSV", "[input]") {
  test::TempDir dir;
  const std::string ok = dir / "u.csv";
  test::WriteText(ok, "t,u\n0,0\n0.5,1.2\n1.0,-1\n");
  const auto zoh = ReadInputTable(ok, InputHold::kZeroOrder);
  CHECK(zoh->Value(0.75) == 1.2);
  const auto lin = ReadInputTable(ok, InputHold::kLinear);
  CHECK(lin->Value(0.75) == Approx(0.1));
  const std::string bad = dir / "bad.csv";
  test::WriteText(bad, "t,u\n0,0\n0.5,abc\n");
  CHECK_THROWS_AS(ReadInputTable(bad, InputHold::kZeroOrder), InputError);
  CHECK_THROWS_WITH(ReadInputTable(bad, InputHold::kZeroOrder), Catch::Contains("bad.csv:3:"));
  const std::string no_u = dir / "no_u.csv";
  test::WriteText(no_u, "t,x\n0,0\n");
  CHECK_THROWS_WITH(ReadInputTable(no_u, InputHold::kZeroOrder), Catch::Contains("'u'"));
  CHECK_THROWS_WITH(MakeTableInput({0, 1, 1}, {0, 1, 2}, InputHold::kZeroOrder, "mine"),
                    Catch::Contains("mine: row 3"));
  CHECK_THROWS_AS(ParseInputHold("cubic"), OptionsError);
}

TEST_CASE("input files and pulse trains as waveforms with their natural length", "[input]") {
  test::TempDir dir;
  const std::string path = dir / "u.csv";
  test::WriteText(path, "t,u\n0,0\n0.5,1.2\n1.25,-1\n");
  const NamedWaveform table = ReadInputWaveform(path, InputHold::kLinear);
  CHECK(table.duration_s == 1.25);  // the last row's t
  CHECK(table.description == path + " (linear)");
  CHECK(table.signal->Value(0.25) == Approx(0.6));
  CHECK(ReadInputWaveform(path, InputHold::kZeroOrder).description == path + " (zoh)");
  PulseTrainSpec spec;
  spec.amplitudes_v = {1.5, -2};
  spec.on_s = 0.2;
  spec.off_s = 0.3;
  spec.repeats = 2;
  const NamedWaveform pulses = PulseTrainWaveform(spec);
  CHECK(pulses.duration_s == Approx(2 * 2 * (0.2 + 0.3)));
  CHECK(pulses.signal->Value(0.1) == 1.5);
  CHECK(pulses.signal->Value(0.6) == -2);
  CHECK(pulses.signal->Value(0.3) == 0);
  CHECK(pulses.description == "pulses 1.5/-2 V, 0.2 s on, 0.3 s off, 2 repeats");
}

}  // namespace
}  // namespace sysid
