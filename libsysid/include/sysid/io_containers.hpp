// Recordings kept where labs keep them: MATLAB MAT files (v4, v5, v5 compressed, v7.3) and HDF5
// files, read through libmatio and the HDF5 C library (inside libsysid/src/io only), plus the
// `sysid import` builder that assembles one CSV recording from columns of any of these files and
// of whitespace- or comma-separated text.
//
// Indices in variable specs and error messages are 1-based, like MATLAB: `data[:,2]` is the
// second column, `u[1523]` the 1523rd sample.
#ifndef SYSID_IO_CONTAINERS_HPP_
#define SYSID_IO_CONTAINERS_HPP_

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sysid/io.hpp"

namespace sysid {

/// How a file is read, decided by its first bytes (never by its name alone): MAT v5 has "MI"/"IM"
/// at byte 126 of its 128-byte header; HDF5 has the signature "\x89HDF\r\n\x1a\n" at byte 0,
/// 512, 1024, 2048, ... (MAT v7.3 is HDF5 behind a 512-byte MAT header); a MAT v4 file (no
/// magic) is recognised by a ".mat" name whose first bytes are not text. Anything else is text
/// (CSV).
enum class FileFormat { kText, kMat, kHdf5 };
FileFormat DetectFileFormat(const std::string& path);
/// "text", "MAT v5", "MAT v7.3", "MAT v4", "HDF5" (the file's detected format, for messages).
std::string DescribeFileFormat(const std::string& path);

/// The most elements one MAT/HDF5 variable (a whole matrix, or all the leaves of a struct) may
/// declare: larger declarations are refused before anything is allocated.
inline constexpr double kMaxVariableElements = kMaxSignalSamples;

/// One variable of a MAT file or dataset of an HDF5 file, as `sysid info` lists it.
struct VariableInfo {
  std::string name;                 ///< MAT: variable name (struct fields as S.F); HDF5: /path
  std::string type;                 ///< "double", "single", "int16", "char", "struct", "cell", ...
  std::vector<std::uint64_t> dims;  ///< as MATLAB shows them (MAT) or h5py (HDF5)
  bool complex = false;
  bool sparse = false;
  bool numeric_vector = false;  ///< real numeric with one non-singleton dimension (or 1x1)
  /// For numeric vectors: length and range over the samples (NaN when a value is not finite).
  std::uint64_t length = 0;
  double min = 0, max = 0;
};

/// Lists a MAT or HDF5 file's variables (HDF5: every dataset, groups walked depth-first).
/// Throws InputError for text files and unreadable or malformed files.
std::vector<VariableInfo> ListVariables(const std::string& path);
/// `sysid info --json` for a MAT/HDF5 file: {"file", "format", "variables": [{name, type, dims,
/// complex, sparse, and for numeric vectors length, min, max}]}.
std::string VariableListToJson(const std::string& path, const std::vector<VariableInfo>& vars,
                               int indent = 2);

/// Reads one signal: a MAT variable, HDF5 dataset, ControlDesk Y(i).Name, or a column of a text
/// file (by header name, or a 1-based column index for a headerless file). The values must be
/// finite; errors name `path:spec[index]`.
Eigen::VectorXd ReadSignal(const std::string& path, const std::string& spec);

/// Writes `recording` as a MAT v5 file (zlib-compressed), one double column vector per column
/// named as the column, atomically. Metadata lines are not kept (MAT has no place for them);
/// `description`, when given, goes into the file's 116-byte text header after
/// "MATLAB 5.0 MAT-file, " (cut to fit) in place of matio's platform line.
void WriteRecordingMat(const std::string& path, const Recording& recording,
                       const std::string& description = "");
/// WriteRecordingMat when `path` ends in ".mat" (any case), else WriteRecording (CSV).
void WriteRecordingByExtension(const std::string& path, const Recording& recording);

/// `sysid import`: one column of the new recording per entry.
struct ImportColumn {
  std::string column;  ///< the recording's column name (t, u, x, ...)
  std::string file;    ///< MAT, HDF5 or text file
  /// Spec inside the file. Empty: the variable named like the column, else (MAT/HDF5) the
  /// file's only numeric vector.
  std::string variable;
};
struct ImportOptions {
  std::vector<ImportColumn> columns;
  double rate_hz = 0;  ///< [Hz] required when no t column is given; t = k / rate_hz
  std::vector<std::pair<std::string, double>> scales;  ///< column -> factor to SI units
  /// column -> SI unit written as `unit.COLUMN` metadata (default: ColumnUnit(column)), e.g.
  /// u -> "N" when the input is a force.
  std::vector<std::pair<std::string, std::string>> units;
};
/// Builds the recording (t first when derived from the rate), checking equal lengths, finite
/// values, a strictly increasing t, and recording the provenance as metadata: `source.COLUMN`
/// (file and variable), `scale.COLUMN`, `sample_rate_hz` and `unit.COLUMN`.
Recording ImportRecording(const ImportOptions& options);

}  // namespace sysid

#endif  // SYSID_IO_CONTAINERS_HPP_
