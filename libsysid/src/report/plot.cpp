#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "sysid/io.hpp"
#include "sysid/report.hpp"

namespace sysid {
namespace {

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

bool GnuplotAvailable() {
  static const bool available = [] {
    const char* path = std::getenv("PATH");
    if (!path) return false;
    std::string p = path;
    size_t start = 0;
    while (start <= p.size()) {
      const size_t end = p.find(':', start);
      const std::string dir = p.substr(start, end == std::string::npos ? end : end - start);
      if (!dir.empty() && access((dir + "/gnuplot").c_str(), X_OK) == 0) return true;
      if (end == std::string::npos) break;
      start = end + 1;
    }
    return false;
  }();
  return available;
}

PlotOutcome WritePlot(const std::string& path, const PlotSpec& spec) {
  namespace fs = std::filesystem;
  if (!GnuplotAvailable())
    return {false, "plot " + path + " skipped: gnuplot not found (apt-get install gnuplot-nox)"};
  const bool svg = fs::path(path).extension() == ".svg";
  // Data and script go to a private temp folder; gnuplot writes a temp image we then rename.
  std::string tmpl = (fs::temp_directory_path() / "sysid-plot-XXXXXX").string();
  if (!mkdtemp(tmpl.data())) return {false, "plot " + path + " skipped: no temp folder"};
  const fs::path dir(tmpl);
  const fs::path target(path);
  const fs::path tmp_image = (target.has_parent_path() ? target.parent_path() : fs::path(".")) /
                             ("." + target.filename().string() + ".tmp");
  std::ofstream script(dir / "plot.gp");
  script << (svg ? "set terminal svg size " : "set terminal pngcairo size ") << spec.width_px << ","
         << spec.height_px << (svg ? " dynamic\n" : "\n");
  script << "set output \"" << Escape(tmp_image.string()) << "\"\n";
  script << "set title \"" << Escape(spec.title) << "\" noenhanced\n";
  script << "set xlabel \"" << Escape(spec.x_label) << "\" noenhanced\n";
  script << "set ylabel \"" << Escape(spec.y_label) << "\" noenhanced\n";
  script << "set grid\nset key outside right top noenhanced\n";
  if (spec.log_y) script << "set logscale y\n";
  script << "plot ";
  for (size_t i = 0; i < spec.series.size(); ++i) {
    const auto& s = spec.series[i];
    const fs::path data = dir / ("s" + std::to_string(i) + ".dat");
    std::ofstream d(data);
    d.precision(10);
    for (Eigen::Index k = 0; k < std::min(s.x.size(), s.y.size()); ++k)
      d << s.x[k] << ' ' << s.y[k] << '\n';
    script << (i ? ", " : "") << '"' << Escape(data.string()) << "\" using 1:2 with " << s.style
           << " title \"" << Escape(s.label) << '"';
  }
  script << "\n";
  script.close();
  const std::string cmd =
      "gnuplot \"" + (dir / "plot.gp").string() + "\" 2>\"" + (dir / "err.txt").string() + "\"";
  const int rc = std::system(cmd.c_str());
  PlotOutcome outcome;
  if (rc == 0 && fs::exists(tmp_image)) {
    std::error_code ec;
    fs::rename(tmp_image, target, ec);
    outcome = ec ? PlotOutcome{false, "plot " + path + ": " + ec.message()} : PlotOutcome{true, ""};
  } else {
    std::ifstream e(dir / "err.txt");
    std::string first;
    std::getline(e, first);
    outcome = {false, "plot " + path + " failed: gnuplot: " + first};
    std::error_code ec;
    fs::remove(tmp_image, ec);
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  return outcome;
}

std::string MarkdownTable(const std::vector<std::string>& header,
                          const std::vector<std::vector<std::string>>& rows) {
  std::string out = "|";
  for (const auto& h : header) out += " " + h + " |";
  out += "\n|";
  for (size_t i = 0; i < header.size(); ++i) out += "---|";
  out += "\n";
  for (const auto& r : rows) {
    out += "|";
    for (const auto& c : r) out += " " + c + " |";
    out += "\n";
  }
  return out;
}

}  // namespace sysid
