// Small MAT (v5, v5 compressed, v7.3) and HDF5 files written with matio and the HDF5 library
// in the tests themselves, including the dSPACE ControlDesk struct layout.
#ifndef SYSID_TESTS_IO_CONTAINER_FIXTURES_HPP_
#define SYSID_TESTS_IO_CONTAINER_FIXTURES_HPP_

#include <cstdint>
#include <string>
#include <vector>

namespace sysid::test {

enum class MatVersion { kV4, kV5, kV5Compressed, kV73 };

/// A real double matrix rows x cols, column-major values.
struct MatArray {
  std::string name;
  std::size_t rows = 1, cols = 1;
  std::vector<double> values;
};

/// Writes `arrays` as double variables.
void WriteMat(const std::string& path, MatVersion version, const std::vector<MatArray>& arrays);
/// One variable of another class: "int16", "single", "complex", "sparse", "char", "cell",
/// "struct" (a 1x1 struct with a field "a"), "empty".
void WriteMatOddVariable(const std::string& path, MatVersion version, const std::string& name,
                         const std::string& kind);
/// A dSPACE ControlDesk export: struct `name` with X.Data = t and Y(i).Name / Y(i).Data.
void WriteControlDesk(const std::string& path, MatVersion version, const std::string& name,
                      const std::vector<double>& t, const std::vector<std::string>& signal_names,
                      const std::vector<std::vector<double>>& signals);

/// A MAT v4 file of one double matrix, written byte by byte (little-endian, type 0): a header
/// declaring `rows` x `cols` values and a name of `name_length` bytes (0: the name's length + 1
/// for its NUL), then the name with its NUL and `stored` (fewer values for a corrupt file).
void WriteRawMat4(const std::string& path, const std::string& name, std::int32_t rows,
                  std::int32_t cols, const std::vector<double>& stored,
                  std::int32_t name_length = 0);

/// One HDF5 dataset: a path such as "/multisine/u" (groups created), dims, values (row-major).
struct H5Array {
  std::string path;
  std::vector<std::uint64_t> dims;
  std::vector<double> values;
};
void WriteH5(const std::string& path, const std::vector<H5Array>& arrays);
/// A dataset declaring `rows` x 1 doubles (chunked, nothing written: no storage allocated).
void WriteH5Huge(const std::string& path, const std::string& dataset, std::uint64_t rows);
/// `arrays` written by WriteH5, then the dataspace of the one 2-D dataset of dims
/// {rows, from_cols} patched in the file's bytes to declare rows x `to_cols` (dims and maximum
/// dims): its contiguous storage still holds rows x from_cols values. Throws unless the
/// dataspace's bytes occur exactly once.
void WriteH5PatchedDims(const std::string& path, const std::vector<H5Array>& arrays,
                        std::uint64_t rows, std::uint64_t from_cols, std::uint64_t to_cols);
/// An integer (int32) dataset and a compound (complex-like) dataset.
void WriteH5Odd(const std::string& path);

/// A MAT v5 file, written byte by byte, whose double variable `u` declares 1 x `cols` elements
/// but holds one value (a hostile header: the reader must refuse it before allocating).
void WriteMatHugeDeclaration(const std::string& path, std::uint32_t cols);

/// One double row vector of a MAT v5 file written byte by byte (WriteRawMat): it declares
/// 1 x `declared` elements and its data element stores `stored` (fewer or more for a corrupt
/// file; the data element's byte count is 8 x stored.size(), as a writer that lost values would
/// leave it).
struct RawMatVariable {
  std::string name;
  std::uint32_t declared = 0;
  std::vector<double> stored;
};
/// Writes `vars` in order, each in its own zlib-compressed element when `compressed` (as MATLAB
/// -v7 does). Independent of matio: the bytes are the MAT v5 format's, little-endian.
void WriteRawMat(const std::string& path, const std::vector<RawMatVariable>& vars, bool compressed);

// Hostile layouts (the container policy, container_policy.hpp): files as another program could
// write them, built with the HDF5 C API, matio and zlib.

/// "/t" (9 doubles) and "/u", a virtual dataset of 9 doubles mapped from
/// `source_file`:`source_dataset`; `unlimited`: u is extendible, mapped block by block from the
/// files `source_file` names with "%b" (the block's number), which HDF5 opens to learn u's size.
void WriteH5Virtual(const std::string& path, const std::string& source_file,
                    const std::string& source_dataset, bool unlimited = false);
/// "/t" and "/u", 9 doubles kept in bytes 0..71 of `external_file` (external storage).
void WriteH5External(const std::string& path, const std::string& external_file);
/// "/t" and "/d", `rows` doubles in chunks of 10 (deflated), and `links` more hard links to
/// "/d": "/l1", "/l2", ...
void WriteH5HardLinks(const std::string& path, std::uint64_t rows, int links);
/// "/t" and `depth` nested groups "/g/g/.../g".
void WriteH5DeepGroups(const std::string& path, int depth);
/// "/t" and "/e", a double dataset with a null dataspace (H5S_NULL: no elements at all).
void WriteH5Null(const std::string& path);

/// MAT v7.3 files matio writes (t: 9 doubles, and a 1x1 cell c holding [1 2 3]) and HDF5 then
/// changes: c{1} made a reference to c itself; a double variable u added whose values are
/// external storage in `other` or a virtual dataset mapped from `other`:/t; or a double variable
/// e added with a null dataspace.
enum class Mat73Hostile { kSelfReference, kExternal, kVirtual, kNull };
void WriteMat73Hostile(const std::string& path, Mat73Hostile kind, const std::string& other = "");
/// A struct nested `depth` levels (s.a.a...a = [1 2 3]).
void WriteMatNestedStructs(const std::string& path, MatVersion version, int depth);

/// MAT v5, compressed and written byte by byte: a 1 x `cells` cell c of empty elements (each an
/// 8-byte tag: 2e7 of them deflate to about 233 KB).
void WriteMatEmptyCells(const std::string& path, std::uint32_t cells);
/// MAT v5, compressed, byte by byte: t (1x100 doubles), then u declaring 1x100 doubles and
/// holding 3, its name element "u" padded with NULs to `name_bytes`.
void WriteMatPaddedName(const std::string& path, std::uint64_t name_bytes);
/// MAT v5, compressed, byte by byte: `variables` variables, all named a, each declaring and
/// holding 1 x `values` zeros (each inflates to 8 x values bytes and more).
void WriteMatZeros(const std::string& path, int variables, std::uint64_t values);

}  // namespace sysid::test

#endif  // SYSID_TESTS_IO_CONTAINER_FIXTURES_HPP_
