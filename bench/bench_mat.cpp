// MAT v5 recording throughput: sysid::ReadRecording on a 10^6-sample MAT v5 file (one double
// vector per column, as `-o OUT.mat` writes them) against the CSV reader on the same recording,
// in one process. The ratio is the number to read (the machine's speed cancels).
//
//   bench_mat [--samples 1000000] [--repeats 3]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "bench_clock.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"

int main(int argc, char** argv) {
  long samples = 1000000;
  int repeats = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--samples" && i + 1 < argc)
      samples = std::atol(argv[++i]);
    else if (a == "--repeats" && i + 1 < argc)
      repeats = std::atoi(argv[++i]);
  }
  sysid::Recording rec;
  rec.names = {"t", "u", "x", "v", "a"};
  rec.data.resize(samples, 5);
  for (Eigen::Index k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) * 1e-3;
    rec.data.row(k) << t, 1.6 * std::sin(3.1 * t), 0.01 * std::sin(0.7 * t) + 1e-7 * (k % 7),
        0.007 * std::cos(0.7 * t), -0.0049 * std::sin(0.7 * t);
  }
  const auto dir = std::filesystem::temp_directory_path();
  const std::string csv = (dir / "sysid_bench_mat.csv").string();
  const std::string mat = (dir / "sysid_bench_mat.mat").string();
  sysid::WriteRecording(csv, rec);
  sysid::WriteRecordingMat(mat, rec);
  auto best = [&](auto&& fn) { return sysid::bench::BestWallSeconds(repeats, fn); };
  Eigen::Index rows_csv = 0, rows_mat = 0;
  bool same = false;
  const double t_csv = best([&] { rows_csv = sysid::ReadRecording(csv).rows(); });
  const double t_mat = best([&] {
    const sysid::Recording r = sysid::ReadRecording(mat);
    rows_mat = r.rows();
    same = r.data == rec.data;
  });
  const double n = static_cast<double>(samples);
  fmt::print("{:<44} {:>10} {:>14} {:>10}\n", "reader (5 columns)", "time [s]", "samples/s",
             "vs CSV");
  fmt::print("{:<44} {:>10.3f} {:>14.3g} {:>9.2f}x\n", "sysid::ReadRecording, CSV (baseline)",
             t_csv, n / t_csv, 1.0);
  fmt::print("{:<44} {:>10.3f} {:>14.3g} {:>9.2f}x\n", "sysid::ReadRecording, MAT v5 (zlib, matio)",
             t_mat, n / t_mat, t_csv / t_mat);
  fmt::print("rows: CSV {}, MAT {}; MAT values equal the written ones: {}\n", rows_csv, rows_mat,
             same ? "yes" : "NO");
  std::filesystem::remove(csv);
  std::filesystem::remove(mat);
  return same && rows_csv == rows_mat ? 0 : 1;
}
