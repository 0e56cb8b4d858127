// Plain HDF5 files (groups of datasets) through the HDF5 C library. MAT v7.3 files, which are
// HDF5 too, go through matio (mat_container.cpp) so that their MATLAB layout is honoured.
#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "io/container_policy.hpp"
#include "io/containers.hpp"
#include "sysid/error.hpp"

namespace sysid::internal {

void SilenceHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

namespace {

std::string TypeName(hid_t type) {
  const H5T_class_t cls = H5Tget_class(type);
  const size_t size = H5Tget_size(type);
  switch (cls) {
    case H5T_FLOAT:
      return size == 4 ? "single" : size == 8 ? "double" : "float";
    case H5T_INTEGER: {
      const bool is_signed = H5Tget_sign(type) == H5T_SGN_2;
      return fmt::format("{}int{}", is_signed ? "" : "u", size * 8);
    }
    case H5T_STRING:
      return "string";
    case H5T_COMPOUND:
      return "compound";
    case H5T_ENUM:
      return "enum";
    case H5T_ARRAY:
      return "array";
    case H5T_VLEN:
      return "vlen";
    case H5T_REFERENCE:
      return "reference";
    case H5T_OPAQUE:
      return "opaque";
    case H5T_BITFIELD:
      return "bitfield";
    default:
      return "unknown";
  }
}

// Throws InputError "where: malformed HDF5 dataset: ..." when a contiguous or compact dataset's
// storage holds fewer bytes than its dataspace declares (`count` elements of the file type).
// HDF5 1.10 reads such a dataset at the offsets the dataspace gives without comparing the two:
// a dataspace patched from 16x1 to 16x17 over storage for 16 doubles read [:,2] from whatever
// follows in the file (other datasets, metadata, zeros), exit 0.
// Not checked: storage never allocated (size 0: HDF5 defines the values as the fill value, as
// for a dataset created and never written); chunked layouts, whose storage size is the sum of
// the allocated, possibly compressed chunks (unallocated chunks read as the fill value, by
// design: an extendible dataset), so it cannot be compared with the dataspace. Virtual datasets
// and external storage never get here: the walk refuses them (container_policy.hpp).
void CheckStorage(hid_t ds, hid_t type, double count, const std::string& where) {
  Hdf5Handle dcpl(H5Dget_create_plist(ds), H5Pclose);
  if (!dcpl.ok()) throw InputError(where + ": malformed HDF5 dataset: cannot read its layout");
  const H5D_layout_t layout = H5Pget_layout(dcpl.get());
  if (layout != H5D_CONTIGUOUS && layout != H5D_COMPACT) return;
  const hsize_t stored = H5Dget_storage_size(ds);
  const double needed = count * static_cast<double>(H5Tget_size(type));
  if (stored != 0 && static_cast<double>(stored) < needed)
    throw InputError(fmt::format(
        "{}: malformed HDF5 dataset: its dataspace declares {:.0f} "
        "elements ({:.0f} bytes), its {} storage holds {} bytes",
        where, count, needed, layout == H5D_CONTIGUOUS ? "contiguous" : "compact", stored));
}

class Hdf5Container : public SignalContainer {
 public:
  explicit Hdf5Container(const std::string& path) : path_(path), file_(Open(path), H5Fclose) {
    if (!file_.ok())
      throw InputError(path + ": not a readable HDF5 file (bad superblock, or truncated)");
    datasets_ = WalkHdf5(file_.get(), path, Hdf5Walk::kDatasets).datasets;
  }

  // Every dataset with its range. A dataset's values are read once however many links name it,
  // and no more than kMaxRangeValues values in all: past them, and for storage never allocated
  // (every value the fill value), a dataset is listed without its range.
  std::vector<VariableInfo> List() override {
    std::vector<VariableInfo> out;
    std::unordered_map<haddr_t, VariableInfo> described;
    double budget = kMaxRangeValues;
    for (const auto& d : datasets_) {
      const auto known = described.find(d.address);
      if (known != described.end()) {
        out.push_back(known->second);
        out.back().name = d.path;
        continue;
      }
      VariableInfo info = Describe(d.path, true);
      if (info.numeric_vector && info.length > 0) {
        info.min = info.max = std::numeric_limits<double>::quiet_NaN();
        const double n = static_cast<double>(info.length);
        if (n <= kMaxVariableElements && n <= budget) {
          budget -= n;
          Hdf5Handle ds(H5Dopen2(file_.get(), d.path.c_str(), H5P_DEFAULT), H5Dclose);
          Eigen::VectorXd v(static_cast<Eigen::Index>(info.length));
          if (ds.ok() && H5Dget_storage_size(ds.get()) > 0 &&
              H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) >= 0)
            SetRange(info, v);
        }
      }
      described.emplace(d.address, info);
      out.push_back(info);
    }
    return out;
  }

  Eigen::VectorXd Read(const VariableSpec& spec) override {
    const std::string where = path_ + ":" + spec.text;
    const std::string name = spec.name.front() == '/' ? spec.name : "/" + spec.name;
    if (std::none_of(datasets_.begin(), datasets_.end(),
                     [&](const Hdf5Dataset& d) { return d.path == name; })) {
      std::vector<std::string> names;
      for (const auto& d : datasets_) names.push_back(d.path);
      throw InputError(
          fmt::format("{}: no dataset '{}' (datasets: {})", path_, name, JoinList(names)));
    }
    Hdf5Handle ds(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!ds.ok()) throw InputError(where + ": cannot open the dataset (corrupt file)");
    Hdf5Handle type(H5Dget_type(ds.get()), H5Tclose);
    if (!type.ok()) throw InputError(where + ": cannot read the dataset's type (corrupt file)");
    const H5T_class_t cls = H5Tget_class(type.get());
    const auto dims = Shape(ds.get());
    const std::string shape = TypeName(type.get()) + " " + FormatDims(dims);
    if (cls == H5T_COMPOUND)
      throw InputError(where + ": is a compound type (" + shape +
                       ", complex numbers?); expected real numbers");
    if (cls != H5T_FLOAT && cls != H5T_INTEGER)
      throw InputError(where + ": is " + TypeName(type.get()) + " (" + FormatDims(dims) +
                       "); expected a real numeric vector");
    const double count = ElementCount(dims);
    if (count == 0) throw InputError(where + ": is empty (" + shape + ")");
    Hdf5Handle file_space(H5Dget_space(ds.get()), H5Sclose);
    if (!file_space.ok()) throw InputError(where + ": cannot read the dataset's shape");
    const std::uint64_t n = PickedLength(spec, dims, shape, "dataset", where);
    CheckStorage(ds.get(), type.get(), count, where);
    if (spec.pick != VariableSpec::Pick::kWhole) {
      const bool column = spec.pick == VariableSpec::Pick::kColumn;
      hsize_t start[2] = {column ? 0 : spec.index - 1, column ? spec.index - 1 : 0};
      hsize_t edge[2] = {column ? dims[0] : 1, column ? 1 : dims[1]};
      if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, edge, nullptr) < 0)
        throw InputError(where + ": cannot select the " + (column ? "column" : "row"));
    }
    Eigen::VectorXd v(static_cast<Eigen::Index>(n));
    hsize_t mem_dims[1] = {n};
    Hdf5Handle mem_space(H5Screate_simple(1, mem_dims, nullptr), H5Sclose);
    if (H5Dread(ds.get(), H5T_NATIVE_DOUBLE, mem_space.get(), file_space.get(), H5P_DEFAULT,
                v.data()) < 0)
      throw InputError(where + ": cannot read the dataset's data (truncated or corrupt file)");
    CheckFinite(v, where);
    return v;
  }

  // From the datasets' types and shapes only: reading a file without a mapping reads the values
  // of the columns it takes and no others.
  std::vector<std::string> DefaultColumns() override {
    std::vector<std::string> out;
    for (const auto& d : datasets_) {
      const std::string bare = d.path.substr(1);
      if (bare.find('/') != std::string::npos) continue;
      const VariableInfo v = Describe(d.path, false);
      if (v.numeric_vector && v.length >= 2) out.push_back(bare);
    }
    return out;
  }

 private:
  static hid_t Open(const std::string& path) {
    SilenceHdf5Errors();
    // No other file is opened through this one: the walk follows no external link and refuses
    // datasets whose values live elsewhere (container_policy.hpp).
    return H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  }

  static std::vector<std::uint64_t> Shape(hid_t ds) {
    Hdf5Handle space(H5Dget_space(ds), H5Sclose);
    std::vector<std::uint64_t> dims;
    if (!space.ok()) return dims;
    // A null dataspace holds nothing (and has rank 0, like a scalar): reading one fills nothing.
    if (H5Sget_simple_extent_type(space.get()) == H5S_NULL) return {0};
    const int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank == 0) return {1};  // a scalar
    if (rank < 0 || rank > 32) return {0};
    std::vector<hsize_t> d(static_cast<size_t>(rank));
    H5Sget_simple_extent_dims(space.get(), d.data(), nullptr);
    for (const auto x : d) dims.push_back(x);
    return dims;
  }

  // A dataset's type and shape, without its values; `check` compares a numeric dataset's
  // storage with its dataspace (CheckStorage) before anything may read it.
  VariableInfo Describe(const std::string& name, bool check) const {
    VariableInfo info;
    info.name = name;
    Hdf5Handle ds(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!ds.ok()) {
      info.type = "unreadable";
      return info;
    }
    Hdf5Handle type(H5Dget_type(ds.get()), H5Tclose);
    info.type = type.ok() ? TypeName(type.get()) : "unreadable";
    info.complex = info.type == "compound";
    info.dims = Shape(ds.get());
    const H5T_class_t cls = type.ok() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
    if (cls != H5T_FLOAT && cls != H5T_INTEGER) return info;
    if (check) CheckStorage(ds.get(), type.get(), ElementCount(info.dims), path_ + ":" + name);
    if (std::count_if(info.dims.begin(), info.dims.end(), [](auto d) { return d != 1; }) <= 1) {
      info.numeric_vector = true;
      info.length = static_cast<std::uint64_t>(ElementCount(info.dims));
    }
    return info;
  }

  std::string path_;
  Hdf5Handle file_;
  std::vector<Hdf5Dataset> datasets_;
};

}  // namespace

std::unique_ptr<SignalContainer> OpenHdf5Container(const std::string& path) {
  return std::make_unique<Hdf5Container>(path);
}

}  // namespace sysid::internal
