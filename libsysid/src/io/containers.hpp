// Private: the MAT (libmatio) and HDF5 (HDF5 C library) readers behind ReadRecording,
// ListVariables and ReadSignal, and the helpers they share. Nothing of matio or HDF5 leaks out
// of the .cpp files that use them.
#ifndef SYSID_SRC_IO_CONTAINERS_HPP_
#define SYSID_SRC_IO_CONTAINERS_HPP_

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"

namespace sysid::internal {

/// A parsed variable spec: `NAME`, `/group/dataset`, `NAME[:,k]`, `NAME[k,:]` (k 1-based).
struct VariableSpec {
  enum class Pick { kWhole, kColumn, kRow };
  std::string text;  ///< as the user wrote it (for messages)
  std::string name;  ///< the variable / dataset path without the index part
  Pick pick = Pick::kWhole;
  std::uint64_t index = 0;  ///< 1-based column or row
};
/// Parses `spec`; throws InputError naming `path`, the spec and the rule (k 1-based).
VariableSpec ParseVariableSpec(const std::string& path, const std::string& spec);

/// A MAT or HDF5 file open for reading signals.
class SignalContainer {
 public:
  virtual ~SignalContainer() = default;
  /// Every variable (HDF5: every dataset) with its shape; ranges for numeric vectors.
  virtual std::vector<VariableInfo> List() = 0;
  /// The real numeric vector `spec` names, as doubles, every value finite. Throws InputError
  /// "path:spec: ..." (missing variables list the ones present; bad values give [index]).
  virtual Eigen::VectorXd Read(const VariableSpec& spec) = 0;
  /// Names usable without a mapping: top-level real numeric vectors (more than one sample)
  /// whose names are plain identifiers.
  virtual std::vector<std::string> DefaultColumns() = 0;
  /// A time vector the layout implies (the dSPACE ControlDesk struct's X.Data); false if none.
  virtual bool ImpliedTime(Eigen::VectorXd* t_s) {
    (void)t_s;
    return false;
  }
  /// Non-empty when the file holds a struct whose signals must be named (ControlDesk): the
  /// message to show when no mapping was given.
  virtual std::string MappingRequiredReason() { return {}; }
};

std::unique_ptr<SignalContainer> OpenMatContainer(const std::string& path);
/// Walks a MAT v5 file's elements (compressed ones inflated) before matio reads it, and throws
/// InputError "path:VAR: malformed or truncated MAT file: declares 1x8 (8 elements), holds 3"
/// when a variable's data hold another number of values than its dims declare (matio would
/// read past them), when an element's size runs past the file, or when something other than a
/// variable sits where one belongs. A MAT v7.3 file must open in HDF5 and pass the container
/// policy's walk (container_policy.hpp); a MAT v4 header may not declare a name or data past the
/// file's end (matio allocates them first). Every walk is bounded as the policy says. Returns how
/// many variables matio must list (fewer means it stopped at an error); nullopt when unchecked.
std::optional<std::size_t> CheckMatLayout(const std::string& path);
std::unique_ptr<SignalContainer> OpenHdf5Container(const std::string& path);
/// By DetectFileFormat; throws InputError for a text file.
std::unique_ptr<SignalContainer> OpenContainer(const std::string& path);

/// Checks `spec`'s pick against a variable of `dims` (`shape` and `kind`, "matrix" or "dataset",
/// name it in messages) and returns the length of the vector it picks. Throws InputError
/// "where: is a matrix (...); pick a column with NAME[:,k] ..." without an index on a matrix,
/// "... column 4 out of range ..." or "... is 3-dimensional ..." (k 1-based in every message).
std::uint64_t PickedLength(const VariableSpec& spec, const std::vector<std::uint64_t>& dims,
                           const std::string& shape, const char* kind, const std::string& where);

/// Turns off the HDF5 library's printing of its error stack (this thread): its failures become
/// our InputErrors instead.
void SilenceHdf5Errors();

/// `rec` with `t_s` as its first column t (source and metadata kept); lengths are the caller's
/// check.
Recording WithTimeFirst(const Recording& rec, const Eigen::VectorXd& t_s);

/// "1x8192", "40960x1".
std::string FormatDims(const std::vector<std::uint64_t>& dims);
/// Product of `dims`, at most kElementCountCap (below 2^64, so that it converts to uint64_t and
/// size_t without overflow; far above kMaxVariableElements).
inline constexpr double kElementCountCap = 1.8e19;
double ElementCount(const std::vector<std::uint64_t>& dims);
/// Throws InputError "where: expected a finite number, found NaN" at the first bad value,
/// `where` followed by [i] with i 1-based.
void CheckFinite(const Eigen::VectorXd& v, const std::string& where);
/// Throws NumericalError naming `path`, the column and the row of the first inf or NaN in
/// `rec`: every recording writer calls it first, since the readers refuse such values.
void RequireFiniteToWrite(const Recording& rec, const std::string& path);
/// Fills numeric_vector, length, min, max of `info` from `values`.
void SetRange(VariableInfo& info, const Eigen::VectorXd& values);
/// Comma-separated names, shortened after 20.
std::string JoinList(const std::vector<std::string>& names);

/// The column mapping's last steps, shared by every format: scales, t from the rate, then the
/// reader's checks (required columns, one of any_of_columns, non-empty, strictly increasing t).
/// `origin(column)` names where a column came from in messages ("train.h5:/multisine/u").
void FinishMappedRecording(Recording& rec, const ReadOptions& options,
                           const std::vector<std::pair<std::string, std::string>>& origins);

/// ReadRecording for a MAT or HDF5 file.
Recording ReadContainerRecording(const std::string& path, const ReadOptions& options);
/// ParseRecording when options.mapping is not empty: the CSV's columns renamed by the mapping.
Recording ParseMappedCsv(std::string_view text, const std::string& source,
                         const ReadOptions& options);

/// A text file (whitespace- or comma-separated, optional header, '#' comments) as columns.
struct TextTable {
  std::vector<std::string> names;  ///< header names; empty when the file has no header
  std::vector<std::vector<double>> columns;
};
TextTable ReadTextTable(const std::string& path);

}  // namespace sysid::internal

#endif  // SYSID_SRC_IO_CONTAINERS_HPP_
