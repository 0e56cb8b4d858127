#include "container_fixtures.hpp"

#include <hdf5.h>
#include <matio.h>
#include <zlib.h>

#include <complex>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace sysid::test {
namespace {

mat_ft FileType(MatVersion v) {
  return v == MatVersion::kV73 ? MAT_FT_MAT73 : v == MatVersion::kV4 ? MAT_FT_MAT4 : MAT_FT_MAT5;
}
matio_compression Compression(MatVersion v) {
  return v == MatVersion::kV5Compressed ? MAT_COMPRESSION_ZLIB : MAT_COMPRESSION_NONE;
}

mat_t* Create(const std::string& path, MatVersion version) {
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, FileType(version));
  if (!mat) throw std::runtime_error("fixture: cannot create " + path);
  return mat;
}

void Write(mat_t* mat, matvar_t* var, MatVersion version) {
  if (!var || Mat_VarWrite(mat, var, Compression(version)) != 0)
    throw std::runtime_error("fixture: cannot write a variable");
  Mat_VarFree(var);
}

matvar_t* CharVar(const char* name, const std::string& s) {
  size_t dims[2] = {1, s.size()};
  return Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UINT8, 2, dims, const_cast<char*>(s.data()),
                       0);  // copies
}

matvar_t* DoubleVar(const char* name, const std::vector<double>& v, size_t rows, size_t cols) {
  size_t dims[2] = {rows, cols};
  return Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, const_cast<double*>(v.data()), 0);
}

}  // namespace

void WriteMat(const std::string& path, MatVersion version, const std::vector<MatArray>& arrays) {
  mat_t* mat = Create(path, version);
  for (const auto& a : arrays)
    Write(mat, DoubleVar(a.name.c_str(), a.values, a.rows, a.cols), version);
  Mat_Close(mat);
}

void WriteMatOddVariable(const std::string& path, MatVersion version, const std::string& name,
                         const std::string& kind) {
  mat_t* mat = Create(path, version);
  size_t dims[2] = {1, 3};
  matvar_t* v = nullptr;
  if (kind == "int16") {
    std::int16_t d[3] = {-2, 0, 7};
    v = Mat_VarCreate(name.c_str(), MAT_C_INT16, MAT_T_INT16, 2, dims, d, 0);
  } else if (kind == "single") {
    float d[3] = {0.5f, 1.25f, -3.0f};
    v = Mat_VarCreate(name.c_str(), MAT_C_SINGLE, MAT_T_SINGLE, 2, dims, d, 0);
  } else if (kind == "complex") {
    double re[3] = {1, 2, 3}, im[3] = {0, 1, 0};
    mat_complex_split_t z{re, im};
    v = Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, &z, MAT_F_COMPLEX);
  } else if (kind == "sparse") {
    double values[2] = {1, 2};
    mat_uint32_t ir[2] = {0, 0}, jc[4] = {0, 1, 1, 2};
    mat_sparse_t s{};
    s.nzmax = 2;
    s.ir = ir;
    s.nir = 2;
    s.jc = jc;
    s.njc = 4;
    s.ndata = 2;
    s.data = values;
    v = Mat_VarCreate(name.c_str(), MAT_C_SPARSE, MAT_T_DOUBLE, 2, dims, &s, 0);
  } else if (kind == "char") {
    v = CharVar(name.c_str(), "abc");
  } else if (kind == "cell") {
    size_t cdims[2] = {1, 1};
    v = Mat_VarCreate(name.c_str(), MAT_C_CELL, MAT_T_CELL, 2, cdims, nullptr, 0);
    Mat_VarSetCell(v, 0, DoubleVar(nullptr, {1, 2, 3}, 1, 3));
  } else if (kind == "struct") {
    size_t sdims[2] = {1, 1};
    const char* fields[] = {"a", nullptr};
    v = Mat_VarCreateStruct2(name.c_str(), 2, sdims, fields);
    Mat_VarSetStructFieldByName(v, "a", 0, DoubleVar("a", {1, 2, 3}, 1, 3));
  } else if (kind == "empty") {
    size_t edims[2] = {0, 0};
    v = Mat_VarCreate(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, edims, nullptr, 0);
  } else {
    throw std::runtime_error("fixture: unknown kind " + kind);
  }
  Write(mat, v, version);
  Mat_Close(mat);
}

void WriteControlDesk(const std::string& path, MatVersion version, const std::string& name,
                      const std::vector<double>& t, const std::vector<std::string>& signal_names,
                      const std::vector<std::vector<double>>& signals) {
  mat_t* mat = Create(path, version);
  const char* top_fields[] = {"X", "Y", "Description", nullptr};
  const char* x_fields[] = {"Name", "Type", "Data", "Unit", nullptr};
  const char* y_fields[] = {"Name", "Type", "Raster", "Data", "Unit", nullptr};
  size_t one[2] = {1, 1};
  size_t ny[2] = {1, signals.size()};
  matvar_t* top = Mat_VarCreateStruct2(name.c_str(), 2, one, top_fields);
  matvar_t* x = Mat_VarCreateStruct2("X", 2, one, x_fields);
  Mat_VarSetStructFieldByName(x, "Name", 0, CharVar("Name", "Time"));
  Mat_VarSetStructFieldByName(x, "Type", 0, CharVar("Type", "Time"));
  Mat_VarSetStructFieldByName(x, "Data", 0, DoubleVar("Data", t, 1, t.size()));
  Mat_VarSetStructFieldByName(x, "Unit", 0, CharVar("Unit", "s"));
  matvar_t* y = Mat_VarCreateStruct2("Y", 2, ny, y_fields);
  for (size_t i = 0; i < signals.size(); ++i) {
    Mat_VarSetStructFieldByName(y, "Name", i, CharVar("Name", signal_names[i]));
    Mat_VarSetStructFieldByName(y, "Type", i, CharVar("Type", "Value"));
    Mat_VarSetStructFieldByName(y, "Raster", i, CharVar("Raster", "Host Service 1"));
    Mat_VarSetStructFieldByName(y, "Data", i, DoubleVar("Data", signals[i], 1, signals[i].size()));
    Mat_VarSetStructFieldByName(y, "Unit", i, CharVar("Unit", ""));
  }
  Mat_VarSetStructFieldByName(top, "X", 0, x);
  Mat_VarSetStructFieldByName(top, "Y", 0, y);
  Mat_VarSetStructFieldByName(top, "Description", 0, CharVar("Description", "test capture"));
  Write(mat, top, version);
  Mat_Close(mat);
}

void WriteRawMat4(const std::string& path, const std::string& name, std::int32_t rows,
                  std::int32_t cols, const std::vector<double>& stored, std::int32_t name_length) {
  std::string bytes;
  const auto i32 = [&](std::int32_t v) {
    for (int i = 0; i < 4; ++i)
      bytes += static_cast<char>((static_cast<std::uint32_t>(v) >> (8 * i)) & 0xff);
  };
  i32(0);  // MOPT 0000: little-endian, double, full matrix
  i32(rows);
  i32(cols);
  i32(0);  // real
  i32(name_length != 0 ? name_length : static_cast<std::int32_t>(name.size() + 1));
  bytes += name;
  bytes += '\0';
  for (const double d : stored) bytes.append(reinterpret_cast<const char*>(&d), 8);
  std::ofstream(path, std::ios::binary) << bytes;
}

namespace {
hid_t EnsureGroups(hid_t file, const std::string& path) {
  size_t pos = 1;
  while (true) {
    const size_t slash = path.find('/', pos);
    if (slash == std::string::npos) break;
    const std::string group = path.substr(0, slash);
    if (H5Lexists(file, group.c_str(), H5P_DEFAULT) <= 0) {
      const hid_t g = H5Gcreate2(file, group.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
      H5Gclose(g);
    }
    pos = slash + 1;
  }
  return file;
}
}  // namespace

void WriteH5(const std::string& path, const std::vector<H5Array>& arrays) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error("fixture: cannot create " + path);
  for (const auto& a : arrays) {
    EnsureGroups(file, a.path);
    std::vector<hsize_t> dims(a.dims.begin(), a.dims.end());
    const hid_t space = H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr);
    const hid_t ds = H5Dcreate2(file, a.path.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT,
                                H5P_DEFAULT, H5P_DEFAULT);
    if (!a.values.empty())
      H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, a.values.data());
    H5Dclose(ds);
    H5Sclose(space);
  }
  H5Fclose(file);
}

void WriteH5PatchedDims(const std::string& path, const std::vector<H5Array>& arrays,
                        std::uint64_t rows, std::uint64_t from_cols, std::uint64_t to_cols) {
  WriteH5(path, arrays);
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  // The version-1 dataspace message (HDF5's default file format) stores the dims and then the
  // maximum dims as 8-byte little-endian integers.
  const auto le64 = [](std::uint64_t v) {
    std::string b(8, '\0');
    for (int i = 0; i < 8; ++i)
      b[static_cast<size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xff);
    return b;
  };
  const std::string pattern = le64(rows) + le64(from_cols) + le64(rows) + le64(from_cols);
  const size_t at = bytes.find(pattern);
  if (at == std::string::npos || bytes.find(pattern, at + 1) != std::string::npos)
    throw std::runtime_error("fixture: the dataspace's bytes do not occur exactly once");
  bytes.replace(at, pattern.size(), le64(rows) + le64(to_cols) + le64(rows) + le64(to_cols));
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

void WriteH5Huge(const std::string& path, const std::string& dataset, std::uint64_t rows) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hsize_t dims[2] = {rows, 1};
  hsize_t chunk[2] = {1024, 1};
  const hid_t space = H5Screate_simple(2, dims, nullptr);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, 2, chunk);
  const hid_t ds =
      H5Dcreate2(file, dataset.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Dclose(ds);
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Fclose(file);
}

void WriteH5Odd(const std::string& path) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hsize_t dims[1] = {3};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const int ints[3] = {4, -5, 6};
  hid_t ds =
      H5Dcreate2(file, "/counts", H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(ds, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, ints);
  H5Dclose(ds);
  const hid_t ctype = H5Tcreate(H5T_COMPOUND, 2 * sizeof(double));
  H5Tinsert(ctype, "r", 0, H5T_NATIVE_DOUBLE);
  H5Tinsert(ctype, "i", sizeof(double), H5T_NATIVE_DOUBLE);
  const std::complex<double> z[3] = {{1, 0}, {2, 1}, {3, 0}};
  ds = H5Dcreate2(file, "/z", ctype, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(ds, ctype, H5S_ALL, H5S_ALL, H5P_DEFAULT, z);
  H5Dclose(ds);
  H5Tclose(ctype);
  H5Sclose(space);
  H5Fclose(file);
}

void WriteMatHugeDeclaration(const std::string& path, std::uint32_t cols) {
  WriteRawMat(path, {{"u", cols, {1.0}}}, false);
}

namespace {
void Append32(std::string& bytes, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) bytes += static_cast<char>((v >> (8 * i)) & 0xff);
}
}  // namespace

void WriteRawMat(const std::string& path, const std::vector<RawMatVariable>& vars,
                 bool compressed) {
  std::string header(116, ' ');
  const char text[] = "MATLAB 5.0 MAT-file, written byte by byte by a test";
  std::memcpy(header.data(), text, sizeof text - 1);
  std::string bytes = header;
  bytes.append(8, '\0');                // subsystem offset
  bytes += std::string("\x00\x01", 2);  // version 0x0100, little-endian
  bytes += "IM";
  for (const auto& v : vars) {
    // miMATRIX: array flags (8 + 8), dims (8 + 8), name (8 + padded), real part (8 + 8 n).
    std::string name = v.name;
    name.resize((name.size() + 7) / 8 * 8, '\0');
    const std::uint32_t data_bytes = static_cast<std::uint32_t>(8 * v.stored.size());
    std::string m;
    Append32(m, 14);  // miMATRIX
    Append32(m, static_cast<std::uint32_t>(16 + 16 + 8 + name.size() + 8 + data_bytes));
    Append32(m, 6);  // miUINT32 array flags
    Append32(m, 8);
    Append32(m, 6);  // mxDOUBLE_CLASS
    Append32(m, 0);
    Append32(m, 5);  // miINT32 dims: 1 x declared
    Append32(m, 8);
    Append32(m, 1);
    Append32(m, v.declared);
    Append32(m, 1);  // miINT8 name
    Append32(m, static_cast<std::uint32_t>(v.name.size()));
    m += name;
    Append32(m, 9);  // miDOUBLE
    Append32(m, data_bytes);
    for (const double d : v.stored) m.append(reinterpret_cast<const char*>(&d), 8);
    if (!compressed) {
      bytes += m;
      continue;
    }
    uLongf size = compressBound(static_cast<uLong>(m.size()));
    std::string z(size, '\0');
    if (compress(reinterpret_cast<Bytef*>(z.data()), &size,
                 reinterpret_cast<const Bytef*>(m.data()), static_cast<uLong>(m.size())) != Z_OK)
      throw std::runtime_error("fixture: zlib compress failed");
    Append32(bytes, 15);  // miCOMPRESSED
    Append32(bytes, static_cast<std::uint32_t>(size));
    bytes.append(z.data(), size);
  }
  std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace sysid::test

namespace sysid::test {
namespace {

void H5Doubles(hid_t file, const char* name, hid_t dcpl, const double* values) {
  hsize_t dims[1] = {9};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t ds = H5Dcreate2(file, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (ds < 0) throw std::runtime_error(std::string("fixture: cannot create ") + name);
  if (values) H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values);
  H5Dclose(ds);
  H5Sclose(space);
}

const double kNine[9] = {0, 1, 2, 3, 4, 5, 6, 7, 8};

hid_t CreateH5(const std::string& path) {
  const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error("fixture: cannot create " + path);
  H5Doubles(file, "/t", H5P_DEFAULT, kNine);
  return file;
}

void SetMatlabClass(hid_t object, const char* cls) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, std::strlen(cls));
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t attr = H5Acreate2(object, "MATLAB_class", type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, type, cls);
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
}

// zlib's stream over `parts`, each a byte string repeated a number of times (gigabytes of
// zeros are never held in memory).
std::string DeflateRepeated(const std::vector<std::pair<std::string, std::uint64_t>>& parts,
                            int level) {
  z_stream z{};
  if (deflateInit(&z, level) != Z_OK) throw std::runtime_error("fixture: deflateInit");
  std::string out, in;
  std::vector<unsigned char> buffer(1 << 20);
  const auto pump = [&](int flush) {
    z.next_in = reinterpret_cast<Bytef*>(in.data());
    z.avail_in = static_cast<uInt>(in.size());
    do {
      z.next_out = buffer.data();
      z.avail_out = static_cast<uInt>(buffer.size());
      deflate(&z, flush);
      out.append(reinterpret_cast<char*>(buffer.data()), buffer.size() - z.avail_out);
    } while (z.avail_out == 0);
    in.clear();
  };
  for (const auto& [bytes, times] : parts)
    for (std::uint64_t i = 0; i < times; ++i) {
      in += bytes;
      if (in.size() >= (1u << 20)) pump(Z_NO_FLUSH);
    }
  pump(Z_FINISH);
  deflateEnd(&z);
  return out;
}

std::string MatHeader() {
  std::string header(116, ' ');
  const char text[] = "MATLAB 5.0 MAT-file, written byte by byte by a test";
  std::memcpy(header.data(), text, sizeof text - 1);
  header.append(8, '\0');
  header += std::string("\x00\x01", 2);
  header += "IM";
  return header;
}

std::string U32(std::uint32_t v) {
  std::string b;
  Append32(b, v);
  return b;
}

// A double row vector's miMATRIX up to its name tag: flags, dims 1 x `declared`.
std::string DoubleMatrixStart(std::uint32_t declared) {
  return U32(6) + U32(8) + U32(6) + U32(0) + U32(5) + U32(8) + U32(1) + U32(declared);
}

// One compressed element (miCOMPRESSED) holding a miMATRIX of `content_bytes` bytes.
std::string Compressed(std::vector<std::pair<std::string, std::uint64_t>> parts,
                       std::uint64_t content_bytes, int level = Z_BEST_SPEED) {
  parts.insert(parts.begin(), {U32(14) + U32(static_cast<std::uint32_t>(content_bytes)), 1});
  const std::string z = DeflateRepeated(parts, level);
  return U32(15) + U32(static_cast<std::uint32_t>(z.size())) + z;
}

}  // namespace

void WriteH5Virtual(const std::string& path, const std::string& source_file,
                    const std::string& source_dataset, bool unlimited) {
  const hid_t file = CreateH5(path);
  hsize_t dims[1] = {9}, max[1] = {H5S_UNLIMITED};
  const hid_t space = H5Screate_simple(1, dims, unlimited ? max : nullptr);
  const hid_t source = H5Screate_simple(1, dims, nullptr);
  if (unlimited) {
    hsize_t start[1] = {0}, stride[1] = {9}, count[1] = {H5S_UNLIMITED}, block[1] = {9};
    H5Sselect_hyperslab(space, H5S_SELECT_SET, start, stride, count, block);
  }
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_virtual(dcpl, space, source_file.c_str(), source_dataset.c_str(), source);
  const hid_t ds = H5Dcreate2(file, "/u", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (ds < 0) throw std::runtime_error("fixture: cannot create the virtual dataset");
  H5Dclose(ds);
  H5Pclose(dcpl);
  H5Sclose(source);
  H5Sclose(space);
  H5Fclose(file);
}

void WriteH5External(const std::string& path, const std::string& external_file) {
  const hid_t file = CreateH5(path);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_external(dcpl, external_file.c_str(), 0, 72);
  H5Doubles(file, "/u", dcpl, nullptr);
  H5Pclose(dcpl);
  H5Fclose(file);
}

void WriteH5HardLinks(const std::string& path, std::uint64_t rows, int links) {
  const hid_t file = CreateH5(path);
  hsize_t dims[1] = {rows}, chunk[1] = {10};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, 1, chunk);
  H5Pset_deflate(dcpl, 1);
  const hid_t ds = H5Dcreate2(file, "/d", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  const std::vector<double> values(rows, 0.5);
  H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  for (int i = 1; i <= links; ++i)
    H5Lcreate_hard(ds, ".", file, ("/l" + std::to_string(i)).c_str(), H5P_DEFAULT, H5P_DEFAULT);
  H5Dclose(ds);
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Fclose(file);
}

void WriteH5DeepGroups(const std::string& path, int depth) {
  const hid_t file = CreateH5(path);
  hid_t parent = file;
  for (int i = 0; i < depth; ++i) {
    const hid_t g = H5Gcreate2(parent, "g", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (parent != file) H5Gclose(parent);
    parent = g;
  }
  if (parent != file) H5Gclose(parent);
  H5Fclose(file);
}

void WriteH5Null(const std::string& path) {
  const hid_t file = CreateH5(path);
  const hid_t space = H5Screate(H5S_NULL);
  const hid_t ds =
      H5Dcreate2(file, "/e", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dclose(ds);
  H5Sclose(space);
  H5Fclose(file);
}

void WriteMat73Hostile(const std::string& path, Mat73Hostile kind, const std::string& other) {
  {
    mat_t* mat = Create(path, MatVersion::kV73);
    Write(mat, DoubleVar("t", std::vector<double>(kNine, kNine + 9), 1, 9), MatVersion::kV73);
    size_t cdims[2] = {1, 1};
    matvar_t* c = Mat_VarCreate("c", MAT_C_CELL, MAT_T_CELL, 2, cdims, nullptr, 0);
    Mat_VarSetCell(c, 0, DoubleVar(nullptr, {1, 2, 3}, 1, 3));
    Write(mat, c, MatVersion::kV73);
    Mat_Close(mat);
  }
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (file < 0) throw std::runtime_error("fixture: HDF5 cannot open " + path);
  if (kind == Mat73Hostile::kSelfReference) {
    hobj_ref_t self;
    H5Rcreate(&self, file, "/c", H5R_OBJECT, -1);
    const hid_t ds = H5Dopen2(file, "/c", H5P_DEFAULT);
    H5Dwrite(ds, H5T_STD_REF_OBJ, H5S_ALL, H5S_ALL, H5P_DEFAULT, &self);
    H5Dclose(ds);
  } else if (kind == Mat73Hostile::kNull) {
    const hid_t space = H5Screate(H5S_NULL);
    const hid_t ds =
        H5Dcreate2(file, "/e", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    SetMatlabClass(ds, "double");
    H5Dclose(ds);
    H5Sclose(space);
  } else {
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    hsize_t dims[1] = {9};
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    if (kind == Mat73Hostile::kExternal)
      H5Pset_external(dcpl, other.c_str(), 0, 72);
    else
      H5Pset_virtual(dcpl, space, other.c_str(), "/t", space);
    const hid_t ds = H5Dcreate2(file, "/u", H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    SetMatlabClass(ds, "double");
    H5Dclose(ds);
    H5Sclose(space);
    H5Pclose(dcpl);
  }
  H5Fclose(file);
}

void WriteMatNestedStructs(const std::string& path, MatVersion version, int depth) {
  mat_t* mat = Create(path, version);
  size_t one[2] = {1, 1};
  const char* fields[] = {"a", nullptr};
  matvar_t* inner = DoubleVar("a", {1, 2, 3}, 1, 3);
  for (int level = depth - 1; level >= 0; --level) {
    matvar_t* s = Mat_VarCreateStruct2(level == 0 ? "s" : "a", 2, one, fields);
    Mat_VarSetStructFieldByName(s, "a", 0, inner);
    inner = s;
  }
  Write(mat, inner, version);
  Mat_Close(mat);
}

void WriteMatEmptyCells(const std::string& path, std::uint32_t cells) {
  // Cell flags, dims 1 x cells, name "c", then `cells` empty miMATRIX tags.
  const std::string start = U32(6) + U32(8) + U32(1) + U32(0) + U32(5) + U32(8) + U32(1) +
                            U32(cells) + U32(1) + U32(1) + std::string("c\0\0\0\0\0\0\0", 8);
  const std::uint64_t content = start.size() + 8ull * cells;
  std::ofstream(path, std::ios::binary)
      << MatHeader()
      << Compressed({{start, 1}, {U32(14) + U32(0), cells}}, content, Z_DEFAULT_COMPRESSION);
}

void WriteMatPaddedName(const std::string& path, std::uint64_t name_bytes) {
  std::string t = DoubleMatrixStart(100) + U32(1) + U32(1) + std::string("t\0\0\0\0\0\0\0", 8) +
                  U32(9) + U32(800);
  for (int i = 0; i < 100; ++i) {
    const double v = 0.01 * i;
    t.append(reinterpret_cast<const char*>(&v), 8);
  }
  const std::uint64_t padded = (name_bytes + 7) / 8 * 8;
  std::string tail = U32(9) + U32(24);
  for (const double v : {1.0, 2.0, 3.0}) tail.append(reinterpret_cast<const char*>(&v), 8);
  const std::string u_start =
      DoubleMatrixStart(100) + U32(1) + U32(static_cast<std::uint32_t>(name_bytes)) + "u";
  const std::uint64_t content = u_start.size() + (padded - 1) + tail.size();
  const std::string zeros(1 << 16, '\0');
  std::ofstream(path, std::ios::binary)
      << MatHeader() << Compressed({{t, 1}}, t.size())
      << Compressed({{u_start, 1},
                     {zeros, (padded - 1) / zeros.size()},
                     {std::string((padded - 1) % zeros.size(), '\0'), 1},
                     {tail, 1}},
                    content);
}

void WriteMatZeros(const std::string& path, int variables, std::uint64_t values) {
  // One variable deflated once and written `variables` times (all named a): the file is what
  // matters, and deflating gigabytes takes seconds.
  const std::string start = DoubleMatrixStart(static_cast<std::uint32_t>(values)) + U32(1) +
                            U32(1) + std::string("a\0\0\0\0\0\0\0", 8) + U32(9) +
                            U32(static_cast<std::uint32_t>(8 * values));
  const std::uint64_t bytes = 8 * values;
  const std::string zeros(1 << 16, '\0');
  const std::string one = Compressed(
      {{start, 1}, {zeros, bytes / zeros.size()}, {std::string(bytes % zeros.size(), '\0'), 1}},
      start.size() + bytes);
  std::ofstream out(path, std::ios::binary);
  out << MatHeader();
  for (int v = 0; v < variables; ++v) out << one;
}

}  // namespace sysid::test
