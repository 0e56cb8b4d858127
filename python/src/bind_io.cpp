// Recordings (sysid/io.hpp) and signal conditioning (sysid/signal.hpp, the motion part of
// sysid/identify.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "bind_common.hpp"
#include "bind_fields.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/io_csv_table.hpp"
#include "sysid/io_output.hpp"
#include "sysid/signal.hpp"

namespace sysid::python {
namespace {

/// set_column keeps a recording that `save` can write and every reader takes back: the CSV
/// reader's rules for a column name (printable, no comma, not starting like a number, no
/// surrounding blanks) and its values (finite; t strictly increasing by at least
/// kMinTimeStep_s, with a finite duration).
void CheckColumnForFile(const Recording& r, const std::string& name, const Eigen::VectorXd& v) {
  const std::string where = (r.source.empty() ? "recording" : r.source) + ": set_column";
  const bool printable = std::none_of(name.begin(), name.end(), [](char c) {
    const auto b = static_cast<unsigned char>(c);
    return b < 0x20 || b == 0x7F || c == ',';
  });
  const auto numeric_start = [](const std::string& s) {
    return std::isdigit(static_cast<unsigned char>(s[0])) || s[0] == '-' || s[0] == '.';
  };
  if (name.empty() || !printable || numeric_start(name) || name.front() == ' ' ||
      name.back() == ' ' || name.front() == '#')
    throw InputError(fmt::format(
        "{}: column name {}: expected a name of printable characters without ',', not starting "
        "like a number, '#' or a blank (the CSV reader's rule for a header)",
        where, py::repr(py::str(name)).cast<std::string>()));
  for (Eigen::Index k = 0; k < v.size(); ++k)
    if (!std::isfinite(v[k]))
      throw InputError(fmt::format("{}: column '{}'[{}]: expected a finite number, found {}",
                                   where, name, k, v[k]));
  if (name != "t") return;
  for (Eigen::Index k = 1; k < v.size(); ++k)
    if (!(v[k] - v[k - 1] >= kMinTimeStep_s) || !std::isfinite(v[k] - v[0]))
      throw InputError(fmt::format(
          "{}: column 't'[{}]: time must be strictly increasing by at least {:g} s with a "
          "finite duration, found {} after {}",
          where, k, kMinTimeStep_s, v[k], v[k - 1]));
}

/// A recording from named 1-D arrays. The columns go through the strict reader's rules (the
/// same checks and messages as a file: finite numbers, strictly increasing t, required columns)
/// by rendering them at 17 significant digits, which round-trips every double exactly.
Recording RecordingFromArrays(const py::dict& columns, const std::string& source,
                              const ReadOptions& options,
                              const std::vector<std::pair<std::string, std::string>>& metadata) {
  Recording r;
  r.source = source;
  r.metadata = metadata;
  Eigen::Index rows = -1;
  std::string first;
  for (const auto& item : columns) {
    const std::string name = py::str(item.first);
    const Eigen::VectorXd values =
        RealVector(item.second, fmt::format("{}: column '{}'", source, name));
    if (rows >= 0)
      CheckSameLength(source, fmt::format("column '{}'", name), values.size(),
                      fmt::format("column '{}'", first), rows);
    else
      first = name;
    rows = values.size();
    // The reader's rule, said here: the CSV text below cannot carry inf or NaN.
    for (Eigen::Index k = 0; k < values.size(); ++k)
      if (!std::isfinite(values[k]))
        throw InputError(fmt::format("{}: column '{}'[{}]: expected a finite number, found {}",
                                     source, name, k, values[k]));
    r.SetColumn(name, values);
  }
  if (rows < 0) throw InputError(source + ": no columns");
  return ParseRecording(FormatRecording(r), source, options);
}

// ---- NumPy views into a recording's storage ----
// rec[name] and rec.data are views into Recording::data (no copy), and appending a column grows
// that matrix (Recording::SetColumn -> conservativeResize -> realloc), which may move it and free
// the old buffer: a view taken before then would read and write freed heap (glibc's `double
// free or corruption`). Of the sound fixes this is the cheapest for users: copying on every rec[name]
// would cost a column per access and stop writes reaching the recording, and refusing set_column
// while any view lives would make appending fail because of a stray variable. Instead every view
// of a recording's current buffer has one owner (a capsule, the views' `base`), which holds the
// recording alive; when set_column must grow the storage while that owner lives, the owner takes
// the old buffer and the recording continues in a copy. The views stay valid with the values
// they had (detached: writes through them no longer reach the recording). With no live view,
// appending costs what it always did.

struct ViewOwner {
  const Recording* recording;  // whose storage the views show; nullptr once detached
  PyObject* recording_object;  // strong reference while attached: a view keeps its recording
  PyObject* capsule;           // borrowed: the Python object owning this struct
  Eigen::MatrixXd detached;    // the buffer the views show, once detached
};

/// The live owner of each recording's views; used only with the GIL held. Leaked on purpose: a
/// capsule freed during interpreter shutdown must not find it destroyed.
std::unordered_map<const Recording*, ViewOwner*>& ViewOwners() {
  static auto* owners = new std::unordered_map<const Recording*, ViewOwner*>();
  return *owners;
}

void ReleaseViewOwner(void* pointer) {
  auto* owner = static_cast<ViewOwner*>(pointer);
  if (owner->recording) ViewOwners().erase(owner->recording);
  PyObject* recording = owner->recording_object;
  delete owner;
  Py_XDECREF(recording);  // last: may destroy the recording
}

/// The owner of the views of `self`'s current buffer (made on the first view).
py::object ViewOwnerOf(const py::object& self) {
  const Recording* r = &self.cast<const Recording&>();
  auto& owners = ViewOwners();
  if (const auto it = owners.find(r); it != owners.end())
    return py::reinterpret_borrow<py::object>(it->second->capsule);
  auto made = std::make_unique<ViewOwner>(ViewOwner{r, nullptr, nullptr, {}});
  py::object capsule = py::capsule(made.get(), &ReleaseViewOwner);
  ViewOwner* owner = made.release();  // the capsule's now
  owner->recording_object = self.inc_ref().ptr();
  owner->capsule = capsule.ptr();
  owners.emplace(r, owner);
  return capsule;
}

/// Before `r`'s storage moves: hands the current buffer to its views' owner, if any view lives.
void DetachViews(Recording& r) {
  auto& owners = ViewOwners();
  const auto it = owners.find(&r);
  if (it == owners.end()) return;
  ViewOwner* owner = it->second;
  owners.erase(it);
  owner->detached = std::move(r.data);  // the views' buffer, now the owner's
  r.data = owner->detached;             // the recording continues in a copy
  owner->recording = nullptr;
  // The caller holds the recording, so this reference is not its last.
  Py_CLEAR(owner->recording_object);
}

/// rows x cols column-major view of `r.data` (or of column `column` alone), owned by ViewOwnerOf.
py::array StorageView(const py::object& self, int column) {
  const Recording& r = self.cast<const Recording&>();
  const auto rows = static_cast<py::ssize_t>(r.data.rows());
  const auto item = static_cast<py::ssize_t>(sizeof(double));
  const py::object owner = ViewOwnerOf(self);
  if (column >= 0) return py::array_t<double>({rows}, {item}, r.data.data() + column * rows, owner);
  return py::array_t<double>({rows, static_cast<py::ssize_t>(r.data.cols())}, {item, item * rows},
                             r.data.data(), owner);
}

Recording DeriveRecording(Recording recording, const DerivativeOptions& options,
                          double max_relative_jitter) {
  const SamplingReport sampling = AnalyzeSampling(recording.column("t"), max_relative_jitter);
  if (sampling.irregular)
    throw InputError(fmt::format(
        "{}: irregular sampling: t[{}] - t[{}] (data rows, 0-based) deviates {:.3g} % from the "
        "median interval {:.6g} s (tolerance {:.3g} %); resample first",
        recording.source, sampling.worst_index + 1, sampling.worst_index,
        100 * sampling.max_relative_jitter, sampling.nominal_dt_s, 100 * max_relative_jitter));
  const Derivatives d = Differentiate(recording.column("x"), sampling.nominal_dt_s, options);
  recording.SetColumn("v", d.v_mps);
  recording.SetColumn("a", d.a_mps2);
  return recording;
}

// sysid.csv_table: Python's cells through the library's one CSV writer.
std::string CsvTableOf(const std::vector<std::string>& header, const std::vector<py::list>& rows,
                       int digits) {
  CsvTable table(header);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].size() != header.size())
      throw py::value_error(fmt::format("csv_table: row {} has {} fields, the header {}", i,
                                        rows[i].size(), header.size()));
    for (const py::handle cell : rows[i]) {
      if (cell.is_none()) table.Empty();
      else if (py::isinstance<py::str>(cell)) table.Text(cell.cast<std::string>());
      else if (py::isinstance<py::bool_>(cell)) table.Integer(cell.cast<bool>() ? 1 : 0);
      else if (py::isinstance<py::int_>(cell)) table.Integer(cell.cast<long long>());
      else if (py::isinstance<py::float_>(cell)) table.Number(cell.cast<double>(), digits);
      else
        throw py::type_error(fmt::format("csv_table: row {}: expected str, int, float or None, "
                                         "got {}",
                                         i, py::str(cell.get_type()).cast<std::string>()));
    }
    table.EndRow();
  }
  return table.str();
}

}  // namespace

// Long function: a pybind11 registration table, one entry per bound type and field in the
// header's order; split, it would only scatter the table.
void BindIo(py::module_& m) {
  py::class_<ReadOptions> read_options(m, "ReadOptions",
                                       "Which columns the recording reader insists on.");
  AddKeywordInit(read_options);
  read_options.def_readwrite("required_columns", &ReadOptions::required_columns)
      .def_readwrite("any_of_columns", &ReadOptions::any_of_columns)
      .def_readwrite("require_increasing_time", &ReadOptions::require_increasing_time);

  py::class_<Recording> recording(
      m, "Recording",
      "A table of named, equally long columns in SI units (t [s], u [V], x [m], v [m/s], "
      "a [m/s^2]) with the file's '# key: value' metadata. rec['x'] is a NumPy view (no copy; "
      "see set_column).");
  recording.def(py::init<>())
      .def_readwrite("source", &Recording::source)
      .def_readonly("names", &Recording::names)
      .def_readwrite("metadata", &Recording::metadata)
      .def_property_readonly(
          "data", [](const py::object& self) { return StorageView(self, -1); },
          "rows x columns view (column-major); detached by appending a column (see set_column)")
      .def_property_readonly("rows", &Recording::rows)
      .def("__len__", &Recording::rows)
      .def("__contains__", &Recording::has)
      .def(
          "__getitem__",
          [](py::object self, const std::string& name) {
            Recording& r = self.cast<Recording&>();
            const int c = r.index_of(name);
            if (c < 0) {
              // The library's message for a missing column.
              (void)r.column(name);
            }
            return StorageView(self, c);
          },
          "The named column as a NumPy view [SI unit of the column]; DataError if absent.")
      .def(
          "set_column",
          [](Recording& r, const std::string& name, const py::object& values) {
            const Eigen::VectorXd v = RealVector(values, "set_column: values", true);
            CheckColumnForFile(r, name, v);
            if (!r.names.empty())
              CheckSameLength((r.source.empty() ? "recording" : r.source) + ": set_column",
                              "values", v.size(), "the recording", r.rows());
            if (!r.has(name)) DetachViews(r);  // appending may move the storage
            r.SetColumn(name, v);
          },
          py::arg("name"), py::arg("values"),
          "Appends or replaces a column (as long as the others). Replacing writes in place, so "
          "views see the new values; appending detaches the views taken before (rec[name], "
          "rec.data): they stay valid with the values they had, but no longer track the "
          "recording (take them again).")
      .def("meta", &Recording::meta, py::arg("key"), py::arg("fallback") = "")
      .def("to_csv", &FormatRecording, "CSV text: metadata lines, header, 17 significant digits")
      .def(
          "save",
          [](const Recording& r, const std::string& path) { WriteRecordingByExtension(path, r); },
          py::arg("path"),
          "Writes the CSV (MAT v5 when the path ends in .mat) atomically (temporary file, then "
          "rename).")
      .def("__repr__", [](const Recording& r) {
        std::string cols;
        for (const auto& n : r.names) cols += (cols.empty() ? "" : ", ") + n;
        return fmt::format("<sysid.Recording '{}': {} rows [{}]>", r.source, r.rows(), cols);
      });
  recording.def_static("from_arrays", &RecordingFromArrays, py::arg("columns"),
                       py::arg("source") = "arrays", py::arg("options") = ReadOptions{},
                       py::arg("metadata") = std::vector<std::pair<std::string, std::string>>{},
                       "A recording from {name: 1-D array}, checked by the reader's rules.");

  m.def(
      "read_recording",
      [](const std::string& path, ReadOptions options,
         std::vector<std::pair<std::string, std::string>> var, double rate,
         std::vector<std::pair<std::string, double>> scale) {
        options.mapping.variables = std::move(var);
        options.mapping.rate_hz = rate;
        options.mapping.scales = std::move(scale);
        return ReadRecording(path, options);
      },
      py::arg("path"), py::arg("options") = ReadOptions{},
      py::arg("var") = std::vector<std::pair<std::string, std::string>>{}, py::arg("rate") = 0.0,
      py::arg("scale") = std::vector<std::pair<std::string, double>>{}, ReleaseGil(),
      "Reads and validates a recording: CSV (the strict reader: DataError 'FILE:LINE:COLUMN: "
      "...' for any bad cell), or MAT (v4, v5, v7.3) / HDF5 through the column mapping `var` "
      "[(column, variable spec)], sample rate `rate` [Hz] and `scale` [(column, factor)].");
  m.def(
      "list_variables_json",
      [](const std::string& path) { return VariableListToJson(path, ListVariables(path)); },
      py::arg("path"), "The variables of a MAT or HDF5 file as `sysid info --json` prints them.");
  m.def("unit_warnings", &UnitSanityWarnings, py::arg("recording"),
        "Warnings when x spans more than 10 m or moves faster than 5 m/s (likely mm or um): "
        "each names the likely unit and the fix ('# units: x=mm').");
  m.def("parse_recording", &ParseRecording, py::arg("text"), py::arg("source"),
        py::arg("options") = ReadOptions{}, ReleaseGil());

  py::class_<SamplingReport>(m, "SamplingReport")
      .def_readonly("nominal_dt_s", &SamplingReport::nominal_dt_s)
      .def_readonly("sample_rate_hz", &SamplingReport::sample_rate_hz)
      .def_readonly("max_jitter_s", &SamplingReport::max_jitter_s)
      .def_readonly("rms_jitter_s", &SamplingReport::rms_jitter_s)
      .def_readonly("max_relative_jitter", &SamplingReport::max_relative_jitter)
      .def_readonly("irregular", &SamplingReport::irregular)
      .def_readonly("worst_index", &SamplingReport::worst_index);
  m.def(
      "analyze_sampling",
      [](const py::object& t_s, double tolerance) {
        return AnalyzeSampling(RealVector(t_s, "t_s"), tolerance);
      },
      py::arg("t_s"), py::arg("tolerance") = 0.01);
  m.def("resample", &Resample, py::arg("recording"), py::arg("rate_hz"), ReleaseGil());
  m.def("crop", &CropRecording, py::arg("recording"), py::arg("t_start_s"), py::arg("t_end_s"),
        ReleaseGil(),
        "The rows with t_start_s <= t <= t_end_s [s], t kept as recorded (not shifted to 0), "
        "metadata kept and 'crop_s: START END' added (`--t-start/--t-end`). DataError naming the "
        "source when a bound lies outside the recording, the start is not before the end, or "
        "fewer than two rows remain.");

  m.def(
      "csv_table",
      &CsvTableOf,
      py::arg("header"), py::arg("rows"), py::arg("digits") = 17,
      "A CSV table as sysid writes every table (the report's, the CLI's): RFC 4180 quoting (a "
      "field with a comma, quote, CR or LF quoted, quotes doubled), LF line ends; str fields as "
      "text, int as integers, float with `digits` significant digits (17: exact round trip), "
      "None empty, bool as 1/0. ValueError when a row is not as wide as the header.");

  // ---- Signal conditioning ----
  py::enum_<DerivativeMethod> method(m, "DerivativeMethod");
  method.value("central", DerivativeMethod::kCentral)
      .value("butterworth", DerivativeMethod::kButterworthCentral)
      .value("savgol", DerivativeMethod::kSavitzkyGolay)
      .def(py::init(&ParseDerivativeMethod));
  py::implicitly_convertible<py::str, DerivativeMethod>();

  py::class_<DerivativeOptions> derivative(m, "DerivativeOptions",
                                           "How v and a come from x (method: 'central', "
                                           "'butterworth', 'savgol').");
  AddKeywordInit(derivative);
  DefFields(derivative);
  derivative.def("validate", &DerivativeOptions::Validate, py::arg("dt_s"));

  py::class_<Derivatives>(m, "Derivatives")
      .def_readonly("x_m", &Derivatives::x_m)
      .def_readonly("v_mps", &Derivatives::v_mps)
      .def_readonly("a_mps2", &Derivatives::a_mps2);
  m.def(
      "differentiate",
      [](const py::object& x_m, double dt_s, const DerivativeOptions& options) {
        const Eigen::VectorXd x = RealVector(x_m, "x_m");
        py::gil_scoped_release release;
        return Differentiate(x, dt_s, options);
      },
      py::arg("x_m"), py::arg("dt_s"), py::arg("options") = DerivativeOptions{},
        "Velocity [m/s] and acceleration [m/s^2] of a uniformly sampled position [m].");
  m.def("derive", &DeriveRecording, py::arg("recording"), py::arg("options") = DerivativeOptions{},
        py::arg("max_relative_jitter") = 0.01, ReleaseGil(),
        "The recording with columns v [m/s] and a [m/s^2] from x (as `sysid derive`).");

  py::class_<MotionOptions> motion(m, "MotionOptions",
                                   "How velocity and acceleration are obtained from a recording.");
  AddKeywordInit(motion);
  AddOptionsJson(motion, &MotionOptionsFromJson);
  DefFields(motion);
  motion.def("validate", &MotionOptions::Validate);

  py::class_<MotionSignals>(m, "MotionSignals")
      .def_readonly("source", &MotionSignals::source)
      .def_readonly("dt_s", &MotionSignals::dt_s)
      .def_readonly("t_s", &MotionSignals::t_s)
      .def_readonly("u_v", &MotionSignals::u_v)
      .def_readonly("x_m", &MotionSignals::x_m)
      .def_readonly("v_mps", &MotionSignals::v_mps)
      .def_readonly("a_mps2", &MotionSignals::a_mps2)
      .def_readonly("velocity_from", &MotionSignals::velocity_from);
  m.def("extract_motion", py::overload_cast<const Recording&, const MotionOptions&>(&ExtractMotion),
        py::arg("recording"), py::arg("options") = MotionOptions{}, ReleaseGil());
}

}  // namespace sysid::python
