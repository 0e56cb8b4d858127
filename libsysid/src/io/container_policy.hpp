// Private: what sysid accepts from a MAT or HDF5 file it did not write, in one place. Both
// readers (hdf5_container.cpp, and mat_layout.cpp before matio opens a file) walk a file under
// these rules before they read a value; docs/robustness.md, "Files from elsewhere", states them.
//
// Why: an HDF5 file (and so a MAT v7.3 file) is a program for the HDF5 library. A virtual
// dataset or external storage makes it read other files (a FIFO blocks forever; HDF5 1.10
// crashes reading a virtual dataset whose source is the file itself); an object reference that
// leads back to itself makes matio recurse until the stack ends; a few kilobytes can declare
// thousands of nested groups, hard links or empty cells, each costing time and memory in the
// libraries. Every bound below is checked before the libraries do that work, and every refusal
// names the file, the object and the bound.
#ifndef SYSID_SRC_IO_CONTAINER_POLICY_HPP_
#define SYSID_SRC_IO_CONTAINER_POLICY_HPP_

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sysid/io_containers.hpp"

namespace sysid::internal {

/// Objects one walk over a file may visit: links, groups, datasets, MAT variables, cells,
/// struct fields and followed object references, each counted where it is visited (an object
/// matio reads twice counts twice).
inline constexpr std::uint64_t kMaxContainerObjects = 100000;
/// Levels a walk may descend: groups in groups, cells and structs in cells and structs, object
/// references followed one from the next.
inline constexpr int kMaxContainerDepth = 32;
/// Bytes one compressed MAT v5 variable may inflate to: the most the reader reads of a variable
/// (kMaxVariableElements values of 16 bytes, a complex pair) and 64 MiB for its headers.
inline constexpr std::uint64_t kMaxInflatedVariableBytes =
    static_cast<std::uint64_t>(16 * kMaxVariableElements) + (std::uint64_t{64} << 20);
/// Bytes all compressed variables of a MAT v5 file may inflate to together.
inline constexpr std::uint64_t kMaxInflatedFileBytes = std::uint64_t{1} << 30;
/// Bytes of a MAT v5 name element (a variable's name with its padding; MATLAB names have at
/// most 63 characters): matio allocates what the element declares.
inline constexpr std::uint64_t kMaxNameBytes = 4096;
/// Values `sysid info` reads in all for the ranges it lists; past them a variable is listed
/// without its range (min and max NaN).
inline constexpr double kMaxRangeValues = 1e8;

/// Counts the objects and checks the depth of one walk; throws InputError naming the bound.
/// `where` names the place in messages, file included: "s.h5:/g/u", "c.mat:c{3}".
class WalkBudget {
 public:
  /// One more object, at `where`.
  void Count(const std::string& where) { Add(1, where); }
  void Add(std::uint64_t n, const std::string& where);
  /// Throws as Add(n) would, without counting: `n` objects declared and about to be allocated.
  void Reserve(double n, const std::string& where) const;
  /// `depth` levels below the file's root at `where`.
  void Depth(int depth, const std::string& where) const;
  std::uint64_t count() const { return count_; }

 private:
  std::uint64_t count_ = 0;
};

/// A name inside a file as messages show it: printable (core/json_text.hpp's Printable), and
/// only its end when it is long.
std::string Shown(const std::string& where);

/// Closes an HDF5 handle with its own close function.
class Hdf5Handle {
 public:
  Hdf5Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Hdf5Handle() {
    if (id_ >= 0) close_(id_);
  }
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

/// Throws InputError "where: refused: ..." when dataset `ds` keeps its values anywhere but in
/// the file itself: a virtual dataset (mapped from other datasets, possibly in other files) or
/// external storage (raw bytes of another file). Called before its storage is touched.
void RequireStoredInFile(hid_t ds, const std::string& where);

/// How an HDF5 file is walked.
enum class Hdf5Walk {
  /// sysid's HDF5 reader: hard links only, each object visited once (a second hard link to a
  /// dataset lists it again under that path without visiting it again; a group is entered once).
  kDatasets,
  /// A MAT v7.3 file as matio 1.5.23 reads it: the root's variables (not "#refs#" nor
  /// "#subsystem#"), hard and soft links and object references (cells, struct arrays) all
  /// followed, an object reached twice read twice. A reference or link leading back to an object
  /// it is inside of is refused (matio would recurse until the stack ends), as is an external
  /// link (matio would open the other file).
  kMat73,
};

/// One dataset the walk found: its path (HDF5: "/g/u") and its object's address in the file.
struct Hdf5Dataset {
  std::string path;
  haddr_t address = HADDR_UNDEF;
};

struct Hdf5Walked {
  std::vector<Hdf5Dataset> datasets;  ///< kDatasets: depth first, by name
  std::size_t root_variables = 0;     ///< kMat73: the root links matio lists as variables
};

/// Walks the open file `file` (`path` names it in messages) under the policy: at most
/// kMaxContainerObjects objects and kMaxContainerDepth levels, each dataset's values stored in
/// the file (RequireStoredInFile), before any value is read. Throws InputError.
Hdf5Walked WalkHdf5(hid_t file, const std::string& path, Hdf5Walk mode);

}  // namespace sysid::internal

#endif  // SYSID_SRC_IO_CONTAINER_POLICY_HPP_
