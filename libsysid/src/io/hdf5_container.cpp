// Plain HDF5 files (groups of datasets) through the HDF5 C library. MAT v7.3 files, which are
// HDF5 too, go through matio (mat_container.cpp) so that their MATLAB layout is honoured.
#include <fmt/format.h>
#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/containers.hpp"
#include "sysid/error.hpp"

namespace sysid::internal {

void SilenceHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

namespace {

// Closes an HDF5 handle with its own close function.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

herr_t CollectDataset(hid_t group, const char* name, const H5L_info_t* info, void* data) {
  auto* out = static_cast<std::vector<std::string>*>(data);
  if (info->type != H5L_TYPE_HARD) return 0;  // soft and external links are not followed
  H5O_info_t oinfo;
  if (H5Oget_info_by_name(group, name, &oinfo, H5P_DEFAULT) < 0) return 0;
  if (oinfo.type == H5O_TYPE_DATASET) out->push_back(std::string("/") + name);
  if (out->size() > 100000) return 1;  // stop: too many
  return 0;
}

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
// design: an extendible dataset), so it cannot be compared with the dataspace; virtual ones.
void CheckStorage(hid_t ds, hid_t type, double count, const std::string& where) {
  Handle dcpl(H5Dget_create_plist(ds), H5Pclose);
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
    if (H5Lvisit(file_.get(), H5_INDEX_NAME, H5_ITER_INC, &CollectDataset, &datasets_) < 0)
      throw InputError(path + ": malformed HDF5 file: cannot list its groups");
    if (datasets_.size() > 100000) throw InputError(path + ": more than 100000 datasets");
  }

  std::vector<VariableInfo> List() override {
    std::vector<VariableInfo> out;
    for (const auto& name : datasets_) {
      VariableInfo info;
      info.name = name;
      Handle ds(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
      if (!ds.ok()) {
        info.type = "unreadable";
        out.push_back(info);
        continue;
      }
      Handle type(H5Dget_type(ds.get()), H5Tclose);
      info.type = type.ok() ? TypeName(type.get()) : "unreadable";
      info.complex = info.type == "compound";
      info.dims = Shape(ds.get());
      const H5T_class_t cls = type.ok() ? H5Tget_class(type.get()) : H5T_NO_CLASS;
      if (cls == H5T_FLOAT || cls == H5T_INTEGER)  // before a range is read from the storage
        CheckStorage(ds.get(), type.get(), ElementCount(info.dims), path_ + ":" + name);
      if ((cls == H5T_FLOAT || cls == H5T_INTEGER) &&
          std::count_if(info.dims.begin(), info.dims.end(), [](auto d) { return d != 1; }) <= 1) {
        info.numeric_vector = true;
        info.length = static_cast<std::uint64_t>(ElementCount(info.dims));
        if (info.length > 0 && ElementCount(info.dims) <= kMaxVariableElements) {
          Eigen::VectorXd v(static_cast<Eigen::Index>(info.length));
          if (H5Dread(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) >= 0)
            SetRange(info, v);
        }
      }
      out.push_back(info);
    }
    return out;
  }

  Eigen::VectorXd Read(const VariableSpec& spec) override {
    const std::string where = path_ + ":" + spec.text;
    const std::string name = spec.name.front() == '/' ? spec.name : "/" + spec.name;
    if (std::find(datasets_.begin(), datasets_.end(), name) == datasets_.end())
      throw InputError(
          fmt::format("{}: no dataset '{}' (datasets: {})", path_, name, JoinList(datasets_)));
    Handle ds(H5Dopen2(file_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
    if (!ds.ok()) throw InputError(where + ": cannot open the dataset (corrupt file)");
    Handle type(H5Dget_type(ds.get()), H5Tclose);
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
    Handle file_space(H5Dget_space(ds.get()), H5Sclose);
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
    Handle mem_space(H5Screate_simple(1, mem_dims, nullptr), H5Sclose);
    if (H5Dread(ds.get(), H5T_NATIVE_DOUBLE, mem_space.get(), file_space.get(), H5P_DEFAULT,
                v.data()) < 0)
      throw InputError(where + ": cannot read the dataset's data (truncated or corrupt file)");
    CheckFinite(v, where);
    return v;
  }

  std::vector<std::string> DefaultColumns() override {
    std::vector<std::string> out;
    for (const auto& v : List()) {
      const std::string bare = v.name.substr(1);
      if (!v.numeric_vector || v.length < 2 || bare.find('/') != std::string::npos) continue;
      out.push_back(bare);
    }
    return out;
  }

 private:
  static hid_t Open(const std::string& path) {
    SilenceHdf5Errors();
    // Refuse external links and keep the library from opening other files on our behalf.
    return H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  }

  static std::vector<std::uint64_t> Shape(hid_t ds) {
    Handle space(H5Dget_space(ds), H5Sclose);
    std::vector<std::uint64_t> dims;
    if (!space.ok()) return dims;
    const int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank == 0) return {1};              // a scalar
    if (rank < 0 || rank > 32) return {0};  // a null dataspace holds nothing
    std::vector<hsize_t> d(static_cast<size_t>(rank));
    H5Sget_simple_extent_dims(space.get(), d.data(), nullptr);
    for (const auto x : d) dims.push_back(x);
    return dims;
  }

  std::string path_;
  Handle file_;
  std::vector<std::string> datasets_;
};

}  // namespace

std::unique_ptr<SignalContainer> OpenHdf5Container(const std::string& path) {
  return std::make_unique<Hdf5Container>(path);
}

}  // namespace sysid::internal
