#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sysid/io.hpp"
#include "sysid/report.hpp"

extern char** environ;  // POSIX: the environment passed to the spawned gnuplot

namespace sysid {
namespace {

// Titles and labels may hold file names: gnuplot substitutes back-quoted text and macros even in
// a script file, so everything that could end the double-quoted string, substitute or end a line
// is dropped, not escaped. A single quote is plain text inside double quotes, and kept: x'' is
// the acceleration.
std::string Sanitise(const std::string& s) {
  std::string out;
  for (unsigned char c : s) {
    if (c < 0x20 || c == 0x7f || c == '`' || c == '$' || c == '"' || c == '\\' || c == '@')
      continue;
    out += static_cast<char>(c);
  }
  return out;
}

// Runs gnuplot on `script` with an argument vector (no shell); stderr goes to `err`.
int RunGnuplot(const std::string& script, const std::string& err) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  std::string prog = "gnuplot";
  std::string arg = script;
  char* argv[] = {prog.data(), arg.data(), nullptr};
  pid_t pid = 0;
  const int spawn = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawn != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool IsHexColour(const std::string& c) {
  if (c.size() != 7 || c[0] != '#') return false;
  for (size_t i = 1; i < c.size(); ++i)
    if (!std::isxdigit(static_cast<unsigned char>(c[i]))) return false;
  return true;
}

}  // namespace

std::string GnuplotScript(const PlotSpec& spec, const std::string& image,
                          const std::vector<std::string>& data_files) {
  const bool svg = std::filesystem::path(image).extension() == ".svg";
  std::ostringstream script;
  script << (svg ? "set terminal svg size " : "set terminal pngcairo size ") << spec.width_px << ","
         << spec.height_px << (svg ? " dynamic\n" : "\n");
  script << "set output \"" << Sanitise(image) << "\"\n";
  script << "set title \"" << Sanitise(spec.title) << "\" noenhanced\n";
  script << "set xlabel \"" << Sanitise(spec.x_label) << "\" noenhanced\n";
  script << "set ylabel \"" << Sanitise(spec.y_label) << "\" noenhanced\n";
  // The legend below the frame, in columns: beside it, long labels took the plot's width.
  script << "set grid\nset key below horizontal noenhanced\n";
  if (spec.log_y) script << "set logscale y\n";
  if (std::isfinite(spec.y_min) && std::isfinite(spec.y_max) && spec.y_min < spec.y_max)
    script << "set yrange [" << spec.y_min << ":" << spec.y_max << "]\n";
  script << "plot ";
  for (size_t i = 0; i < spec.series.size() && i < data_files.size(); ++i) {
    const auto& s = spec.series[i];
    script << (i ? ", " : "") << '"' << Sanitise(data_files[i]) << "\" using 1:2 with " << s.style;
    if (IsHexColour(s.colour)) script << " lc rgb \"" << s.colour << '"';
    script << " title \"" << Sanitise(s.label) << '"';
  }
  script << "\n";
  return script.str();
}

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
  // gnuplot only ever sees toolkit-made names inside the private folder; the image is then
  // copied next to the target and renamed into place.
  const fs::path gp_image = dir / (svg ? "image.svg" : "image.png");
  const fs::path tmp_image = (target.has_parent_path() ? target.parent_path() : fs::path(".")) /
                             ("." + target.filename().string() + ".tmp");
  std::vector<std::string> data_files;
  for (size_t i = 0; i < spec.series.size(); ++i) {
    const auto& s = spec.series[i];
    data_files.push_back((dir / ("s" + std::to_string(i) + ".dat")).string());
    std::ofstream d(data_files.back());
    d.precision(10);
    for (Eigen::Index k = 0; k < std::min(s.x.size(), s.y.size()); ++k)
      d << s.x[k] << ' ' << s.y[k] << '\n';
  }
  WriteFileAtomically((dir / "plot.gp").string(),
                      GnuplotScript(spec, gp_image.string(), data_files));
  const int rc = RunGnuplot((dir / "plot.gp").string(), (dir / "err.txt").string());
  PlotOutcome outcome;
  if (rc == 0 && fs::exists(gp_image)) {
    std::error_code ec;
    fs::copy_file(gp_image, tmp_image, fs::copy_options::overwrite_existing, ec);
    if (!ec) fs::rename(tmp_image, target, ec);
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

std::vector<std::pair<std::string, PlotSpec>> TrackingPlots(const std::vector<SchemeTracking>& runs) {
  PlotSpec err{"tracking error", "t [s]", "e [mm]", {}, false, 900, 500};
  PlotSpec u{"control signal", "t [s]", "u [V]", {}, false, 900, 500};
  for (const auto& run : runs) {
    const std::string scheme = ToString(run.scheme);
    err.series.push_back({scheme, run.result.t_s, 1e3 * run.result.e_m, "lines"});
    u.series.push_back({scheme, run.result.t_s, run.result.u_v, "lines"});
  }
  // One colour per scheme in both plots.
  PlotColours colours;
  colours.Apply(err);
  colours.Apply(u);
  return {{"tracking_error.png", err}, {"control_signal.png", u}};
}

}  // namespace sysid
