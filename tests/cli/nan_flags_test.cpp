// Real-valued flags refuse "nan" by their own name. CLI11's range checks compare the value with
// their bounds, and every comparison with NaN is false, so they let it through to the library,
// whose errors then named a field ("PiOptions::sample_time_s = nan") instead of the flag.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "support/test_support.hpp"

using sysid::test::RunCli;

TEST_CASE("a real-valued flag given nan or inf is refused by the flag's name", "[cli]") {
  // One flag of each kind of check: a positive number, a non-negative one, bounded ranges.
  const std::vector<std::vector<std::string>> cases = {
      {"simulate", "--pulse-on"},          // PositiveNumber
      {"excite", "pulses", "--rest"},      // NonNegativeNumber
      {"track", "--kp"},                   // FiniteRange(0, 1e9)
      {"stage", "facts", "--collect-kp"},  // FiniteRange(1, 1e6)
  };
  for (const auto& args : cases) {
    const std::string flag = args.back();
    for (const char* value : {"nan", "NaN"}) {
      auto a = args;
      a.push_back(value);
      INFO(flag << " " << value);
      const auto r = RunCli(a);
      CHECK(r.exit_code == 1);
      CHECK(r.out.empty());
      // A number's validators say "not a number", a finite range's "not a finite number".
      const bool ranged = flag == "--kp" || flag == "--collect-kp";
      CHECK(r.err.find(flag + ": Value " + value +
                       (ranged ? " is not a finite number" : " is not a number")) !=
            std::string::npos);
    }
  }
  // A positive number is finite too, and its message does not print the largest double.
  const auto zero = RunCli({"track", "--freq", "0"});
  CHECK(zero.exit_code == 1);
  CHECK(zero.err.find("--freq: Value 0: expected a number > 0") != std::string::npos);
  CHECK(zero.err.size() < 200);
  const auto big = RunCli({"simulate", "--pulse-on", "1e400"});
  CHECK(big.err.find("--pulse-on: Value 1e400 is not a finite number") != std::string::npos);
  const auto inf = RunCli({"track", "--ki", "inf"});
  CHECK(inf.exit_code == 1);
  CHECK(inf.err.find("--ki: Value inf is not a finite number") != std::string::npos);
}
