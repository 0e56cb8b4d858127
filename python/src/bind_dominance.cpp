// Dominance (sysid/dominance.hpp). Results keep the C++ field names and also give plain dicts
// and records that pandas.DataFrame takes directly.
#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "bind_common.hpp"
#include "bind_fields.hpp"
#include "sysid/dominance.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

namespace sysid::python {
namespace {

/// The library's JSON text as Python objects (json.loads): the same keys and values as the CLI.
py::object JsonObject(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

/// One flat row per recording: source, dominant, margin, sample counts, the paper's ratios and
/// rms_<variable> / ratio_<variable> for every ranked variable.
py::dict DominanceRow(const DominanceResult& r) {
  py::dict d;
  d["source"] = r.source;
  d["dominant"] = r.dominant;
  d["margin"] = r.margin;
  d["samples"] = r.samples;
  d["moving_samples"] = r.moving_samples;
  d["peak_ratio"] = r.peak_ratio;
  d["pointwise_ratio_quantile"] = r.pointwise_ratio_quantile;
  d["pointwise_ratio_max"] = r.pointwise_ratio_max;
  for (const auto& s : r.ranking) {
    d[py::str("rms_" + s.name)] = s.rms;
    d[py::str("ratio_" + s.name)] = s.ratio_to_top;
  }
  return d;
}

/// Rows of DominanceTableCsv: one per (recording, ranked variable).
py::list DominanceRecords(const std::vector<DominanceResult>& results) {
  py::list rows;
  for (const auto& r : results) {
    int rank = 0;
    for (const auto& s : r.ranking) {
      py::dict d;
      d["source"] = r.source;
      d["rank"] = ++rank;
      d["variable"] = s.name;
      d["rms"] = s.rms;
      d["peak"] = s.peak;
      d["ratio_to_top"] = s.ratio_to_top;
      d["ratio_bound"] = s.ratio_bound;
      d["ratio_max"] = s.ratio_max;
      d["negligible"] = s.negligible;
      d["dominant"] = r.dominant == s.name;
      d["margin"] = r.margin;
      d["moving_samples"] = r.moving_samples;
      rows.append(d);
    }
  }
  return rows;
}

/// Dominance of many recordings on the calling thread with the GIL released (one task of
/// sysid.batch): files are read here too. Each entry is the result, or the error message with
/// the exception's Python name when that recording failed (the batch decides whether to raise).
struct BatchEntry {
  std::optional<DominanceResult> result;
  std::string error_type, error;
};

template <typename Item, typename Analyze>
std::vector<BatchEntry> RunEntries(const std::vector<Item>& items, const Analyze& analyze) {
  std::vector<BatchEntry> out(items.size());
  py::gil_scoped_release release;
  for (size_t i = 0; i < items.size(); ++i) {
    try {
      out[i].result = analyze(items[i]);
    } catch (const InputError& e) {
      out[i].error_type = "DataError";
      out[i].error = e.what();
    } catch (const OptionsError& e) {
      out[i].error_type = "OptionsError";
      out[i].error = e.what();
    } catch (const NumericalError& e) {
      out[i].error_type = "NumericalError";
      out[i].error = e.what();
    } catch (const Error& e) {
      out[i].error_type = "Error";
      out[i].error = e.what();
    }
  }
  return out;
}

py::list EntryRows(const std::vector<BatchEntry>& entries, const std::vector<std::string>& sources) {
  py::list rows;
  for (size_t i = 0; i < entries.size(); ++i) {
    if (entries[i].result) {
      rows.append(DominanceRow(*entries[i].result));
    } else {
      py::dict d;
      d["source"] = sources[i];
      d["error_type"] = entries[i].error_type;
      d["error"] = entries[i].error_type + ": " + entries[i].error;
      rows.append(d);
    }
  }
  return rows;
}

}  // namespace

// Long function: a pybind11 registration table, one entry per bound type and field in the
// header's order; split, it would only scatter the table.
void BindDominance(py::module_& m) {
  // ---- Dominance ----
  py::class_<CandidateTerm>(m, "CandidateTerm")
      .def(py::init([](std::string variable, std::string column, double gain) {
             return CandidateTerm{std::move(variable), std::move(column), gain};
           }),
           py::arg("variable"), py::arg("column"), py::arg("gain") = 1.0,
           "The candidate term gain * column [m/s^2] named `variable` in the ranking.")
      .def_readwrite("variable", &CandidateTerm::variable)
      .def_readwrite("column", &CandidateTerm::column)
      .def_readwrite("gain", &CandidateTerm::gain);
  py::class_<DominanceOptions> dominance_options(m, "DominanceOptions");
  AddKeywordInit(dominance_options);
  AddOptionsJson(dominance_options, &DominanceOptionsFromJson);
  DefFields(dominance_options);
  dominance_options.def("validate", &DominanceOptions::Validate);
  py::class_<TermStats> term_stats(m, "TermStats");
  DefReadOnlyFields(term_stats);
  py::class_<DominanceResult> dominance(m, "DominanceResult");
  DefReadOnlyFields(dominance)
      .Stored("terms", &DominanceResult::terms,
              "every term in fixed order; the JSON holds the ranking (the same terms ranked)")
      .Derived(
          "termination", [](const DominanceResult&) { return "analysed"; },
          "the analysis always ends analysed (the termination every result states)")
      .Derived(
          "message",
          [](const DominanceResult& r) {
            return DominanceVerdict(r.dominant, r.ranking.size() > 1 ? r.ranking[1].name : "",
                                    r.margin);
          },
          "the verdict in words, from the ranking and margin");
  dominance.def("brief_report", &DominanceResult::BriefReport)
      .def(
          "to_dict", [](const DominanceResult& r) { return JsonObject(ToJson(r, -1)); },
          "The CLI's JSON object for this recording (`dominance --json` \"recordings\" entry).")
      .def("to_json", py::overload_cast<const DominanceResult&, int>(&ToJson),
           py::arg("indent") = 2)
      .def("row", &DominanceRow, "One flat dict: source, dominant, margin, rms_<variable>, ...")
      .def(
          "records", [](const DominanceResult& r) { return DominanceRecords({r}); },
          "One dict per ranked variable (the CSV table's rows).");
  py::class_<DominanceSummary>(m, "DominanceSummary")
      .def("to_json", py::overload_cast<const DominanceSummary&, int>(&ToJson),
           py::arg("indent") = 2, "`sysid dominance --json`'s text")
      .def_readonly("results", &DominanceSummary::results)
      .def_readonly("dominant_counts", &DominanceSummary::dominant_counts)
      .def_readonly("dominant", &DominanceSummary::dominant)
      .def_readonly("min_margin", &DominanceSummary::min_margin)
      .def_readonly("median_margin", &DominanceSummary::median_margin)
      .def("records", [](const DominanceSummary& s) { return DominanceRecords(s.results); },
           "One dict per (recording, ranked variable): the rows of table_csv().")
      .def("rows",
           [](const DominanceSummary& s) {
             py::list rows;
             for (const auto& r : s.results) rows.append(DominanceRow(r));
             return rows;
           },
           "One flat dict per recording.")
      .def("table_csv", &DominanceTableCsv, "The CLI's -o table.")
      .def("brief_report", [](const DominanceSummary& s) {
        std::string out;
        for (const auto& r : s.results) out += r.BriefReport();
        return out;
      });
  m.def("analyze_dominance",
        py::overload_cast<const FrictionModel&, const Recording&, const DominanceOptions&>(
            &AnalyzeDominance),
        py::arg("model"), py::arg("recording"), py::arg("options") = DominanceOptions{},
        ReleaseGil());
  m.def(
      "dominance_rows_files",
      [](const FrictionModel& model, const std::vector<std::string>& paths,
         const DominanceOptions& options) {
        // One reader and one workspace for the chunk: after the first file, same-length
        // recordings allocate nothing of their size (a Dask worker's glibc, with the nanny's
        // MALLOC_TRIM_THRESHOLD_, would otherwise return and re-fault those pages per file).
        RecordingReader reader;
        DominanceWorkspace workspace;
        const auto entries = RunEntries(paths, [&](const std::string& path) {
          return AnalyzeDominance(model, reader.Read(path), options, &workspace);
        });
        return EntryRows(entries, paths);
      },
      py::arg("model"), py::arg("paths"), py::arg("options"),
      "Rows (one flat dict per file) of a chunk of sysid.batch; failures give source/error.");
  m.def(
      "dominance_rows",
      [](const FrictionModel& model, const std::vector<const Recording*>& recordings,
         const DominanceOptions& options) {
        std::vector<std::string> sources;
        for (const Recording* r : recordings) sources.push_back(r->source);
        DominanceWorkspace workspace;
        const auto entries = RunEntries(recordings, [&](const Recording* r) {
          return AnalyzeDominance(model, *r, options, &workspace);
        });
        return EntryRows(entries, sources);
      },
      py::arg("model"), py::arg("recordings"), py::arg("options"));
  m.def("analyze_dominance_batch", &AnalyzeDominanceBatch, py::arg("model"),
        py::arg("recordings"), py::arg("options") = DominanceOptions{}, ReleaseGil());
}

}  // namespace sysid::python
