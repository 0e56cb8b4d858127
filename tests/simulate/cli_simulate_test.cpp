// The sysid simulate command: outputs, event log, JSON summary, exit codes, no partial output.
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"
#include "sysid/io.hpp"

namespace sysid {
namespace {

TEST_CASE("sysid simulate writes t,u,x,v,a and the event log", "[cli][simulate]") {
  test::TempDir dir;
  test::WriteText(dir / "m.json", R"({"a1p":104.0154,"a1n":117.1441,"a2p":3.1023,)"
                                  R"("a2n":6.8216,"a3":6,"tau":0.0035})");
  test::WriteText(dir / "u.csv", "t,u\n0,1.6\n0.4,0\n1.0,-2.3\n1.4,0\n2,0\n");
  const auto r =
      test::RunCli({"simulate", "--model", dir / "m.json", "--input", dir / "u.csv", "--t-end", "2",
                    "--dt", "0.001", "-o", dir / "out.csv", "--events", dir / "ev.csv"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const Recording out = ReadRecording(dir / "out.csv");
  CHECK(out.names == std::vector<std::string>{"t", "u", "x", "v", "a"});
  CHECK(out.rows() == 2001);
  // The plateau of the first pulse, (a3 u - a2p) / a1p, to the simulator's accuracy.
  CHECK(out.column("v")[399] == Approx((6 * 1.6 - 3.1023) / 104.0154).epsilon(1e-9));
  const std::string events = test::ReadText(dir / "ev.csv");
  CHECK(events.rfind("# generator: sysid ", 0) == 0);  // the mark of a file sysid wrote
  CHECK(events.find("\nt,kind\n0,slip+\n") != std::string::npos);
  CHECK(events.find(",stick\n") != std::string::npos);
  CHECK(events.find(",reverse\n") != std::string::npos);
  CHECK(events.find(",a1-switch\n") != std::string::npos);
}

TEST_CASE("sysid simulate --json and the input shortcuts", "[cli][simulate]") {
  const auto r = test::RunCli(
      {"simulate", "--paper-model", "--pulses", "1.6,-2.3", "--pulse-repeats", "1", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["t_end_s"] == 2.0);
  CHECK(j["samples"] == 2001);
  CHECK(j["summary"]["termination"] == "converged");
  CHECK(j["summary"]["steps"].get<long>() > 0);
  CHECK(j["events"][0]["kind"] == "slip+");
  const auto w = test::RunCli(
      {"simulate", "--paper-model", "--waveform", "paper-sine", "--t-end", "1", "--json"});
  INFO(w.err);
  CHECK(w.exit_code == 0);
}

TEST_CASE("sysid simulate rejects bad input with exit 2 and writes nothing", "[cli][simulate]") {
  test::TempDir dir;
  test::WriteText(dir / "m.json", R"({"a1p":104,"a1n":117,"a2p":3.1,"a2n":6.8,"a3":6,)"
                                  R"("tau":0.0035,"tua":1})");
  test::WriteText(dir / "u.csv", "t,u\n0,1.6\n0.4,x\n");
  test::WriteText(dir / "good.json", R"({"a1p":104,"a1n":117,"a2p":3.1,"a2n":6.8,"a3":6,)"
                                     R"("tau":0.0035})");
  auto r =
      test::RunCli({"simulate", "--model", dir / "m.json", "--pulses", "1", "-o", dir / "out.csv"});
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("m.json") != std::string::npos);
  r = test::RunCli({"simulate", "--model", dir / "good.json", "--input", dir / "u.csv", "-o",
                    dir / "out.csv", "--events", dir / "ev.csv"});
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("u.csv:3:") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir / "out.csv"));
  CHECK_FALSE(std::filesystem::exists(dir / "ev.csv"));
  r = test::RunCli({"simulate", "--model", dir / "good.json"});  // no input
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("exactly one input") != std::string::npos);
  r = test::RunCli({"simulate", "--paper-model", "--waveform", "square"});
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("paper-pulses") != std::string::npos);
}

}  // namespace
}  // namespace sysid
