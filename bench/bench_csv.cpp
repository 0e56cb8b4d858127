// CSV recording throughput: sysid::ReadRecording against a baseline parse of the same file
// (std::getline + std::strtod, the way such a reader is commonly written), in one process.
//
//   bench_csv [FILE.csv] [--mb 100] [--repeats 3]
// Without FILE a synthetic recording of about --mb megabytes is written to a temp file first.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_clock.hpp"
#include "sysid/io.hpp"

namespace {

std::string MakeFile(double megabytes) {
  const auto path = std::filesystem::temp_directory_path() / "sysid_bench_csv.csv";
  sysid::Recording rec;
  rec.names = {"t", "u", "x", "v", "a"};
  // About 95 bytes a row at full precision.
  const auto rows = static_cast<Eigen::Index>(megabytes * 1e6 / 95);
  rec.data.resize(rows, 5);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const double t = static_cast<double>(k) * 1e-3;
    rec.data.row(k) << t, 1.6 * std::sin(3.1 * t), 0.01 * std::sin(0.7 * t) + 1e-7 * (k % 7),
        0.007 * std::cos(0.7 * t), -0.0049 * std::sin(0.7 * t);
  }
  sysid::WriteRecording(path.string(), rec);
  return path.string();
}

// Baseline: getline per line, split on commas, strtod per cell.
size_t BaselineParse(const std::string& path, std::vector<double>& out) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);  // header
  size_t rows = 0;
  while (std::getline(f, line)) {
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) out.push_back(std::strtod(cell.c_str(), nullptr));
    ++rows;
  }
  return rows;
}

// A faster baseline: the same loop with strtod straight on the line buffer (no stringstream).
size_t BaselineStrtod(const std::string& path, std::vector<double>& out) {
  std::ifstream f(path);
  std::string line;
  std::getline(f, line);
  size_t rows = 0;
  while (std::getline(f, line)) {
    const char* p = line.c_str();
    char* end = nullptr;
    while (*p) {
      out.push_back(std::strtod(p, &end));
      p = *end == ',' ? end + 1 : end;
      if (end == p && *p) break;
    }
    ++rows;
  }
  return rows;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path;
  double mb = 100;
  int repeats = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--mb" && i + 1 < argc) mb = std::atof(argv[++i]);
    else if (a == "--repeats" && i + 1 < argc) repeats = std::atoi(argv[++i]);
    else path = a;
  }
  const bool made = path.empty();
  if (made) path = MakeFile(mb);
  const double size_mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  std::fprintf(stderr, "file %s: %.1f MB\n", path.c_str(), size_mb);

  auto best = [&](auto&& fn) { return sysid::bench::BestWallSeconds(repeats, fn); };
  Eigen::Index rows = 0;
  const double t_ours = best([&] { rows = sysid::ReadRecording(path).rows(); });
  std::vector<double> sink;
  size_t rows_b = 0, rows_c = 0;
  const double t_base = best([&] {
    sink.clear();
    rows_b = BaselineParse(path, sink);
  });
  const double t_strtod = best([&] {
    sink.clear();
    rows_c = BaselineStrtod(path, sink);
  });
  fmt::print("{:<42} {:>10} {:>10} {:>12}\n", "parser", "time [s]", "MB/s", "ours faster");
  fmt::print("{:<42} {:>10.3f} {:>10.0f} {:>12}\n", "sysid::ReadRecording (validating)", t_ours,
             size_mb / t_ours, "1.0x");
  fmt::print("{:<42} {:>10.3f} {:>10.0f} {:>11.1f}x\n", "baseline getline+stringstream+strtod",
             t_base, size_mb / t_base, t_base / t_ours);
  fmt::print("{:<42} {:>10.3f} {:>10.0f} {:>11.1f}x\n", "baseline getline+strtod in place",
             t_strtod, size_mb / t_strtod, t_strtod / t_ours);
  fmt::print("rows: {} (baselines: {}, {}); best of {} runs each\n", rows, rows_b, rows_c,
             repeats);
  if (made) std::filesystem::remove(path);
  return 0;
}
