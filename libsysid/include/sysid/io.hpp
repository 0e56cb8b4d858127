// Recordings: CSV files of time, voltage and position (and any other named columns).
//
// Format: optional '#' comment lines anywhere before the header ("# key: value" lines are
// metadata and are kept), one header line of column names, then numeric rows. Units are SI:
// t [s], u [V], x [m], v [m/s], a [m/s^2]. Every cell is parsed whole: empty cells, "abc",
// "1e", "1.2.3", trailing garbage, NaN and Inf are errors, never zeros. A UTF-8 BOM, CRLF line
// ends and a missing final newline are accepted. Errors throw sysid::InputError whose message
// starts with "FILE:LINE:COLUMN:" (physical lines and 1-based character columns of the file).
#ifndef SYSID_IO_HPP_
#define SYSID_IO_HPP_

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sysid {

/// The most samples (rows) of one signal the toolkit generates or simulates: larger requests
/// (a long --t-end, a high rate, many cycles) are refused with OptionsError before allocation.
/// 2e7 rows is 5.5 h at 1 kHz, about 1 GB in a five-column recording.
inline constexpr double kMaxSignalSamples = 2e7;

/// A table of named, equally long numeric columns with the file's metadata.
struct Recording {
  std::string source;                  ///< file path, or a name given by the caller
  std::vector<std::string> names;      ///< column names in file order
  Eigen::MatrixXd data;                ///< rows x columns, SI units
  std::vector<std::pair<std::string, std::string>> metadata;  ///< "# key: value" lines, in order
  /// Where the rows came from in the file: (first row, its 1-based file line) of each run of
  /// consecutive data lines (one entry unless comment lines sit between rows); empty when not
  /// read from a file. See line_of().
  std::vector<std::pair<Eigen::Index, long>> row_lines;
  Eigen::Index row_lines_rows = 0;  ///< rows when row_lines was filled (a guard for copies)

  Eigen::Index rows() const { return data.rows(); }
  /// Index of the named column, or -1.
  int index_of(std::string_view name) const;
  bool has(std::string_view name) const { return index_of(name) >= 0; }
  /// The file line of data row `row` (0-based), or 0 when unknown (not read from a file, or the
  /// rows were changed since).
  long line_of(Eigen::Index row) const;
  /// "SOURCE:LINE" of data row `row`, or "SOURCE: row N" (1-based) when its line is unknown.
  std::string where(Eigen::Index row) const;
  /// The named column; throws InputError naming the source and the missing column.
  Eigen::MatrixXd::ConstColXpr column(std::string_view name) const;
  /// Value of a metadata key, or `fallback` when absent.
  std::string meta(std::string_view key, std::string fallback = "") const;
  /// Appends (or replaces) a column.
  void SetColumn(const std::string& name, const Eigen::VectorXd& values);
};

/// Where a recording's columns come from when the file's own names are not ours, or the file
/// is MATLAB MAT (v4, v5, v7.3) or HDF5 (`sysid ... --var t=NAME,u=NAME --rate HZ --scale x=1e-6`).
/// Variable specs: `NAME` (a MAT variable, an HDF5 dataset at the root, a CSV column, or the
/// `Y(i).Name` of a dSPACE ControlDesk struct), `/group/dataset` (HDF5), `NAME[:,k]` or
/// `NAME[k,:]` (column or row k of a 2-D matrix; k is 1-based, like MATLAB).
struct SourceMapping {
  /// column -> variable spec, in output column order. For CSV input the named columns are
  /// renamed (a column that has the target's name is dropped, the others are kept); for MAT and
  /// HDF5 input the recording holds exactly these columns (plus t from `rate_hz`, or from the
  /// ControlDesk struct's X.Data).
  std::vector<std::pair<std::string, std::string>> variables;
  /// [Hz] sample rate: when > 0 and the recording has no column t, t = k / rate_hz [s],
  /// k = 0, 1, ... is added as the first column. With a t column present it is an error.
  double rate_hz = 0;
  /// column -> factor to SI (e.g. x -> 1e-6 for a sensor in µm); applied after the mapping.
  std::vector<std::pair<std::string, double>> scales;
  /// [s] keep only the rows with t_start_s <= t <= t_end_s (CropRecording), after the mapping
  /// and scales; unset: the recording's first or last t.
  std::optional<double> t_start_s, t_end_s;

  bool empty() const {
    return variables.empty() && rate_hz == 0 && scales.empty() && !t_start_s && !t_end_s;
  }
};

/// Which columns a reader insists on.
struct ReadOptions {
  /// Columns that must all be present. The default is a recording: t [s] and u [V].
  std::vector<std::string> required_columns{"t", "u"};
  /// At least one of these must be present (default: position x [m] or velocity v [m/s]).
  std::vector<std::string> any_of_columns{"x", "v"};
  /// When a column "t" exists it must be strictly increasing.
  bool require_increasing_time = true;
  /// Column mapping, sample rate and scales (empty: the file's own column or variable names).
  SourceMapping mapping{};  // (an initialiser: {{cols}, {}} aggregates need not list it)
};

/// Speeds and travel beyond these are implausible for a positioning stage: a recording that
/// exceeds them most likely has x in mm or µm (UnitSanityWarnings says so).
inline constexpr double kMaxPlausibleSpeed_mps = 5.0;  ///< [m/s] |v|, or |dx/dt| between samples
inline constexpr double kMaxPlausibleTravel_m = 10.0;  ///< [m] max x - min x

/// Warnings (empty when none) when x spans more than kMaxPlausibleTravel_m, or x or the v column
/// moves faster than kMaxPlausibleSpeed_mps: each names the source, the value, the likely unit
/// and the fix (a CSV: a '# units: x=mm' line, which the reader honours; a MAT or HDF5 file, whose
/// source is the file: --scale x=1e-3).
std::vector<std::string> UnitSanityWarnings(const Recording& recording);

/// Reads and validates a recording: CSV, or MATLAB MAT (v4, v5, v7.3) or HDF5 recognised by the
/// file's first bytes (sysid/io_containers.hpp), through `options.mapping`. Without a mapping, a
/// MAT or HDF5 file's top-level numeric vectors become the columns of their names. Throws
/// InputError ("FILE:LINE:COLUMN: ..." for CSV, "FILE:VARIABLE[INDEX]: ..." for MAT and HDF5).
/// A '# units:' line declaring x=mm, x=um (or "x [mm]"; likewise t, u, v, a, x_ref) makes the
/// CSV reader convert those columns to SI and say so in the line.
Recording ReadRecording(const std::string& path, const ReadOptions& options = {});

/// Parses recording text already in memory; `source` names it in error messages.
Recording ParseRecording(std::string_view text, const std::string& source,
                         const ReadOptions& options = {});

/// Reads recordings one after another into the same buffers (the file's text, the parser's
/// row-major values, the recording's matrix), so that a batch of files of one size allocates
/// nothing per file after the first. Same checks, errors and values as ReadRecording. Not
/// thread-safe: one reader per thread.
class RecordingReader {
 public:
  explicit RecordingReader(ReadOptions options = {}) : options_(std::move(options)) {}
  /// The recording at `path`, valid until the next Read. Throws InputError as ReadRecording.
  const Recording& Read(const std::string& path);

 private:
  ReadOptions options_;
  std::string text_;
  std::vector<double> values_;
  Recording recording_;
};

/// Renders a recording as CSV text: metadata lines, header, rows with 17 significant digits.
std::string FormatRecording(const Recording& recording);

/// Writes `recording` to `path` atomically (temporary file in the same folder, then rename).
void WriteRecording(const std::string& path, const Recording& recording);

/// The SI unit of a standard column name: t "s"; u, u_ff "V"; x, x_ref, e "m"; v, v_ref "m/s";
/// a, a_ref "m/s^2"; "1" for any other column (an index such as waveform, a count).
std::string ColumnUnit(const std::string& column);
/// A recording's shape as JSON: {"samples", "duration_s" (last t minus first t [s]; 0 without
/// rows or a t column), "columns", "units" (ColumnUnit of each column)}. `sysid excite --json`
/// lists one per file.
std::string RecordingShapeToJson(const Recording& recording, int indent = 2);
/// A recording's summary as `sysid info --json` prints it: {"file" (the recording's source),
/// "rows", "columns", "duration_s" [s], "t_start_s" [s], "sample_rate_hz" [Hz] (null below 2
/// rows), "sampling" (AnalyzeSampling's report with `jitter_tolerance` and, when irregular, a
/// "warning"), "column_stats" {column: {min, max, mean}} in each column's unit, "metadata"}.
std::string RecordingSummaryToJson(const Recording& recording, double jitter_tolerance,
                                   int indent = 2);

/// Writes `content` to `path` atomically: a reader sees the old file or the whole new one,
/// never a partial one. Throws InputError when the folder is not writable.
void WriteFileAtomically(const std::string& path, std::string_view content);

/// Reads a whole file; throws InputError "FILE: cannot open: reason".
std::string ReadFile(const std::string& path);
/// ReadFile into `text`, reusing its storage.
void ReadFile(const std::string& path, std::string* text);

/// Sampling of a time column.
struct SamplingReport {
  double nominal_dt_s = 0;      ///< [s] median sample interval
  double sample_rate_hz = 0;    ///< [Hz] 1 / nominal_dt_s
  double max_jitter_s = 0;      ///< [s] max |dt_k - nominal_dt_s|
  double rms_jitter_s = 0;      ///< [s] rms of dt_k - nominal_dt_s
  double max_relative_jitter = 0;  ///< max |dt_k - nominal_dt_s| / nominal_dt_s
  bool irregular = false;       ///< max_relative_jitter > the tolerance asked for
  Eigen::Index worst_index = 0; ///< row k where |dt_k - nominal| is largest (dt_k = t[k+1]-t[k])
};

/// Analyses the sampling of `t` (strictly increasing, at least 2 samples). `tolerance` is the
/// relative jitter above which the sampling is called irregular (default 1 %).
SamplingReport AnalyzeSampling(const Eigen::VectorXd& t, double tolerance = 0.01);
/// AnalyzeSampling with `scratch` for the interval median (its first t.size() - 1 values; grown
/// when shorter, never shrunk), so that a caller looping over recordings reuses one buffer.
/// Same report.
SamplingReport AnalyzeSampling(const Eigen::VectorXd& t, double tolerance,
                               Eigen::VectorXd* scratch);

/// The rows of `recording` with t_start_s <= t <= t_end_s, t kept as it is (not shifted to 0),
/// metadata kept and "crop_s: START END" added. Throws InputError naming the source when the
/// recording has no t, a bound lies outside [first t, last t], t_start_s >= t_end_s, or fewer
/// than two rows remain.
Recording CropRecording(const Recording& recording, double t_start_s, double t_end_s);

/// Resamples every column onto the uniform grid t0, t0 + 1/rate, ... <= t_end by linear
/// interpolation (the column "t" becomes the grid). Throws OptionsError for rate_hz <= 0.
Recording Resample(const Recording& recording, double rate_hz);

}  // namespace sysid

#endif  // SYSID_IO_HPP_
