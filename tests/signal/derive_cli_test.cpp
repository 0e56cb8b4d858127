// sysid derive: output columns and values against analytic derivatives, decimation, and the
// exit codes / messages for bad options (1) and bad data (2), with no output file on error.
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "signal_test_util.hpp"
#include "support/test_support.hpp"
#include "sysid/io.hpp"
#include "sysid/signal.hpp"

using namespace sysid;
using namespace sysid::test;

namespace {

// t, u, x, x_ref at 1 kHz with x = 5 mm sin(2 pi 2 t).
std::string SineRecording(Eigen::Index n) {
  std::ostringstream s;
  s.precision(17);
  s << "# rig: test bench\nt,u,x,x_ref\n";
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = 1e-3 * static_cast<double>(k);
    s << t << ',' << std::sin(t) << ',' << 5e-3 * std::sin(2 * kPi * 2 * t) << ',' << 0.0 << '\n';
  }
  return s.str();
}

}  // namespace

TEST_CASE("derive writes v and a that match the analytic derivatives", "[signal][cli]") {
  TempDir dir;
  const std::string in = dir / "rec.csv", out = dir / "out.csv";
  const Eigen::Index n = 1000;
  WriteText(in, SineRecording(n));
  const double amp = 5e-3, w = 2 * kPi * 2;
  for (std::string method : {"central", "savgol"}) {
    const auto r = RunCli({"derive", in, "--method", method, "-o", out});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const Recording rec = ReadRecording(out);
    CHECK(rec.names == std::vector<std::string>{"t", "u", "x", "x_ref", "v", "a"});
    CHECK(rec.meta("rig") == "test bench");
    CHECK(rec.meta("derive").find("method=" + method) == 0);
    const Eigen::VectorXd v = rec.column("v"), a = rec.column("a");
    if (method == "central") {
      const auto v_ref = Sample([&](double t) { return amp * w * std::cos(w * t); }, n, 1e-3);
      const auto a_ref = Sample([&](double t) { return -amp * w * w * std::sin(w * t); }, n, 1e-3);
      // Central bounds h^2/6 max|x'''| and h^2/3 max|x''''| (interior), plus the 17-digit CSV
      // rounding of x (~1e-19 m) over 2h and 4h^2.
      CHECK(MaxError(v, v_ref, 2, n - 2) <= 1e-6 / 6 * amp * std::pow(w, 3) + 1e-15);
      CHECK(MaxError(a, a_ref, 2, n - 2) <= 1e-6 / 3 * amp * std::pow(w, 4) + 1e-12);
    } else {
      // The accuracy of Savitzky-Golay is tested in savitzky_golay_test.cpp; here the command
      // must apply the documented defaults (window 21, order 3) at the file's rate.
      DerivativeOptions o;
      o.method = DerivativeMethod::kSavitzkyGolay;
      const Derivatives d = Differentiate(rec.column("x"), 1e-3, o);
      CHECK(MaxError(v, d.v_mps, 0, n) < 1e-12);  // dt from the CSV's median step: ~1e-16 off
      CHECK(MaxError(a, d.a_mps2, 0, n) < 1e-9);
    }
  }
}

TEST_CASE("derive --decimate keeps every K-th time and reports JSON", "[signal][cli]") {
  TempDir dir;
  const std::string in = dir / "rec.csv", out = dir / "out.csv";
  WriteText(in, SineRecording(1000));
  const auto r = RunCli({"derive", in, "--method", "butterworth", "--cutoff", "20", "--decimate",
                         "5", "--json", "-o", out});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["rows"] == 200);
  CHECK(j["dt_s"].get<double>() == Approx(5e-3).epsilon(1e-12));  // median of exact steps
  CHECK(j["method"] == "butterworth");
  const Recording rec = ReadRecording(out);
  REQUIRE(rec.rows() == 200);
  CHECK(rec.column("t")[7] == Approx(35e-3).epsilon(1e-15));  // t is subsampled, not filtered
  // The 2 Hz sine passes the 20 Hz low-pass and the 40 Hz anti-alias filter: |H|^2 > 1 - 1e-12,
  // central differences at h = 5 ms: bound h^2/6 max|x'''| away from the ends.
  const double amp = 5e-3, w = 2 * kPi * 2, h = 5e-3;
  const auto v_ref = Sample([&](double t) { return amp * w * std::cos(w * t); }, 200, h);
  CHECK(MaxError(rec.column("v"), v_ref, 60, 140) <= h * h / 6 * amp * std::pow(w, 3) + 1e-9);
}

TEST_CASE("derive rejects bad options with exit 1 and bad data with exit 2", "[signal][cli]") {
  TempDir dir;
  const std::string in = dir / "rec.csv", out = dir / "out.csv";
  WriteText(in, SineRecording(100));
  auto fails = [&](std::vector<std::string> args, int code, const std::string& text) {
    const auto r = RunCli(args);
    INFO(r.err);
    CHECK(r.exit_code == code);
    CHECK(r.err.find(text) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(out));  // no partial output
  };
  fails({"derive", in, "--method", "lanczos", "-o", out}, 1, "--method");
  fails({"derive", in, "--method", "savgol", "--window", "20", "-o", out}, 1,
        "--window: DerivativeOptions::savgol_window = 20. Violated constraint");
  fails({"derive", in, "--method", "butterworth", "--cutoff", "700", "-o", out}, 1, "--cutoff: ");
  fails({"derive", in, "--decimate", "0", "-o", out}, 1,
        "--decimate = 0. Violated constraint: --decimate >= 1");
  fails({"derive", in, "--method", "savgol", "--window", "101", "-o", out}, 2,
        "rec.csv: SavitzkyGolay: the signal has 100 samples");

  const std::string no_x = dir / "nox.csv";
  WriteText(no_x, "t,u,v\n0,1,2\n0.001,1,2\n0.002,1,2\n");
  fails({"derive", no_x, "-o", out}, 2, "nox.csv");
  const std::string jitter = dir / "jitter.csv";
  WriteText(jitter, "t,u,x\n0,0,0\n0.001,0,0\n0.002,0,0\n0.0035,0,0\n0.0045,0,0\n");
  fails({"derive", jitter, "-o", out}, 2, "irregular sampling");
  // The documented way out: resampling onto a uniform grid.
  const auto r = RunCli({"derive", jitter, "--resample", "1000", "-o", out});
  CHECK(r.exit_code == 0);
  CHECK(ReadRecording(out).rows() == 5);
}
