// The pipeline's report: report.md with tables and plots, the model files and CSV tables. The
// sections (report_sections.hpp) are made from the result alone; this file puts them in order,
// draws their plots and writes their files.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <filesystem>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "report/report_sections.hpp"
#include "sysid/io.hpp"
#include "sysid/pipeline.hpp"
#include "sysid/report.hpp"

namespace sysid {
namespace {
namespace fs = std::filesystem;
using internal::ReportSection;

// The opening lines: what was read, and how.
std::string Header(const PipelineResult& r) {
  const PipelineInputs& in = r.inputs;
  const std::string sets =
      in.PulsesOnly() ? std::string(" alone (no training or test set), ")
                      : ", training set `" + fs::path(in.training).filename().string() +
                            "`, test set `" + fs::path(in.test).filename().string() + "`, ";
  std::string md = "# libsysid pipeline report\n\n";
  md += "Inputs: `" + in.root + "` — " + std::to_string(in.pulses.size()) + " pulse recording(s)" +
        sets + std::to_string(in.waveforms.size()) + " test waveform(s)" +
        (in.loops.empty() ? std::string()
                          : ", " + std::to_string(in.loops.size()) + " voltage-loop sweep(s)") +
        "." + internal::MappingSentence(in) + "\n";
  if (r.reference) md += "Reference numbers (" + r.reference->label + ") are set beside ours.\n";
  return md;
}

// Every section in the report's order.
ReportSection Sections(const PipelineResult& r) {
  ReportSection all;
  all.markdown = Header(r);
  all.Append(internal::PulseSection(r));
  all.Append(internal::DelaySection(r));
  if (r.skipped.empty()) {
    all.Append(internal::DominanceSection(r));
    all.Append(internal::NetworkSection(r));
    all.Append(internal::ComparisonSection(r));
  } else {
    all.Append(internal::SkippedSection(r));
  }
  all.Append(internal::ValidationSection(r));
  all.Append(internal::TrackingSection(r));
  all.Append(internal::MarginsSection(r));
  all.Append(internal::ModelTrackingSection(r));
  all.Append(internal::FactsSection(r));
  all.Append(internal::LoopsSection(r));
  all.Append(internal::StepsSection(r));
  return all;
}

// Draws the plots side by side (each is a gnuplot process: drawn one after another they were
// most of the report's time), colours fixed beforehand in report order; plots.json indexes them.
std::vector<PlotOutcome> DrawPlots(std::vector<internal::ReportPlot>& plots, const std::string& dir,
                                   int threads) {
  PlotColours colours;  // one colour per label across the report's plots
  for (auto& p : plots) {
    DrawMeasuredLast(p.spec);
    colours.Apply(p.spec);
  }
  std::vector<PlotOutcome> outcomes(plots.size());
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < plots.size(); i = next++) {
      try {
        outcomes[i] = WritePlot((fs::path(dir) / plots[i].file).string(), plots[i].spec);
      } catch (const std::exception& e) {  // a worker thread must not throw
        outcomes[i] = {false, "plot " + plots[i].file + " failed: " + e.what()};
      }
    }
  };
  const unsigned cores = std::max(1U, std::thread::hardware_concurrency());
  const std::size_t n =
      std::min<std::size_t>(plots.size(), threads > 0 ? static_cast<unsigned>(threads) : cores);
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < n; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  std::vector<std::pair<std::string, PlotSpec>> index;
  for (const auto& p : plots) index.emplace_back(p.file, p.spec);
  WriteFileAtomically((fs::path(dir) / "plots.json").string(), PlotIndexJson(index));
  return outcomes;
}

std::vector<std::string> WriteReport(const PipelineResult& r, const std::string& dir) {
  fs::create_directories(dir);
  auto path = [&](const std::string& name) { return (fs::path(dir) / name).string(); };
  ReportSection all = Sections(r);
  for (const auto& [name, text] : all.files) WriteFileAtomically(path(name), text);
  for (const auto& [name, write] : all.writes) write(path(name));
  const std::vector<PlotOutcome> outcomes = DrawPlots(all.plots, dir, r.options.threads);
  std::vector<std::string> notes = std::move(all.notes);
  for (std::size_t i = 0; i < all.plots.size(); ++i) {
    const auto& p = all.plots[i];
    const std::string line =
        outcomes[i].written
            ? "\n![" + p.caption + "](" + p.file + ")\n"
            : "\n*(plot `" + p.file + "` not drawn: " + outcomes[i].message + ")*\n";
    if (!outcomes[i].written) notes.push_back(outcomes[i].message);
    const std::string marker = ReportSection::Marker(i);
    all.markdown.replace(all.markdown.find(marker), marker.size(), line);
  }
  WriteFileAtomically(path("report.md"), all.markdown);
  return notes;
}

}  // namespace

std::vector<std::string> WritePipelineReport(const PipelineResult& result,
                                             const std::string& out_dir) {
  if (result.inputs.IsStack()) return WriteStackReport(result, out_dir);  // stack_report.cpp
  return WriteReport(result, out_dir);
}

}  // namespace sysid
