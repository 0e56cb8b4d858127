// MATLAB MAT files (v4, v5, v5 compressed, v7.3) through libmatio. Matio's own failures are
// caught by its log hook and translated into the house's messages ("FILE:VAR: ...").
// Long file: matio's every call and its failure translation in one place, so no matio error
// reaches the user in matio's words.
#include <fmt/format.h>
#include <matio.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "io/container_policy.hpp"
#include "io/containers.hpp"
#include "sysid/error.hpp"

namespace sysid::internal {
namespace {

thread_local std::string g_matio_message;

void MatioLog(int level, char* message) {
  (void)level;
  if (message && g_matio_message.empty()) g_matio_message = message;
}

void InitMatio() {
  static std::once_flag once;
  std::call_once(once, [] { Mat_LogInitFunc("sysid", &MatioLog); });
  SilenceHdf5Errors();
  g_matio_message.clear();
}

std::string MatioDetail() {
  std::string m = g_matio_message;
  g_matio_message.clear();
  return m.empty() ? "" : " (matio: " + m + ")";
}

struct VarFree {
  void operator()(matvar_t* v) const { Mat_VarFree(v); }
};
using VarPtr = std::unique_ptr<matvar_t, VarFree>;

std::string ClassName(const matvar_t* v) {
  switch (v->class_type) {
    case MAT_C_DOUBLE:
      return "double";
    case MAT_C_SINGLE:
      return "single";
    case MAT_C_INT8:
      return "int8";
    case MAT_C_UINT8:
      return v->isLogical ? "logical" : "uint8";
    case MAT_C_INT16:
      return "int16";
    case MAT_C_UINT16:
      return "uint16";
    case MAT_C_INT32:
      return "int32";
    case MAT_C_UINT32:
      return "uint32";
    case MAT_C_INT64:
      return "int64";
    case MAT_C_UINT64:
      return "uint64";
    case MAT_C_CHAR:
      return "char";
    case MAT_C_STRUCT:
      return "struct";
    case MAT_C_CELL:
      return "cell";
    case MAT_C_SPARSE:
      return "sparse";
    case MAT_C_FUNCTION:
      return "function";
    case MAT_C_OBJECT:
      return "object";
    case MAT_C_OPAQUE:
      return "opaque";
    case MAT_C_EMPTY:
      return "empty";
  }
  return "unknown";
}

bool IsNumericClass(const matvar_t* v) {
  switch (v->class_type) {
    case MAT_C_DOUBLE:
    case MAT_C_SINGLE:
    case MAT_C_INT8:
    case MAT_C_UINT8:
    case MAT_C_INT16:
    case MAT_C_UINT16:
    case MAT_C_INT32:
    case MAT_C_UINT32:
    case MAT_C_INT64:
    case MAT_C_UINT64:
      return true;
    default:
      return false;
  }
}

std::vector<std::uint64_t> Dims(const matvar_t* v) {
  std::vector<std::uint64_t> d;
  // Rank 0 is no MATLAB array: in a MAT v7.3 file, an HDF5 scalar or null dataspace, which
  // matio reads as one value it never fills.
  if (v->rank == 0) return {0};
  if (!v->dims || v->rank < 0 || v->rank > 32) return d;
  for (int i = 0; i < v->rank; ++i) d.push_back(v->dims[i]);
  return d;
}

int NonSingleton(const std::vector<std::uint64_t>& dims) {
  return static_cast<int>(std::count_if(dims.begin(), dims.end(), [](auto d) { return d != 1; }));
}

// Elements a variable declares, struct and cell leaves included (bounded before reading data).
double TreeElements(const matvar_t* v, int depth = 0) {
  if (depth > kMaxContainerDepth) return kElementCountCap;
  const double own = ElementCount(Dims(v));
  if (own > kMaxVariableElements) return own;
  if ((v->class_type != MAT_C_STRUCT && v->class_type != MAT_C_CELL) || !v->data) return own;
  double n = 0;
  size_t count = static_cast<size_t>(own);
  if (v->class_type == MAT_C_STRUCT) count *= Mat_VarGetNumberOfFields(const_cast<matvar_t*>(v));
  matvar_t* const* items = static_cast<matvar_t* const*>(v->data);
  if (v->data_size != 0 && v->nbytes / v->data_size < count) return kElementCountCap;  // bad
  for (size_t i = 0; i < count; ++i)
    if (items[i]) n += TreeElements(items[i], depth + 1);
  return n;
}

template <typename T>
void Convert(const void* data, size_t n, Eigen::VectorXd& out) {
  const T* p = static_cast<const T*>(data);
  for (size_t i = 0; i < n; ++i) out[static_cast<Eigen::Index>(i)] = static_cast<double>(p[i]);
}

std::string CharString(const matvar_t* v) {
  if (!v || v->class_type != MAT_C_CHAR || !v->data) return {};
  std::string s;
  const size_t n = static_cast<size_t>(ElementCount(Dims(v)));
  if (v->data_type == MAT_T_UINT16 || v->data_type == MAT_T_UTF16) {
    if (v->nbytes < n * 2) return {};
    const auto* p = static_cast<const std::uint16_t*>(v->data);
    for (size_t i = 0; i < n; ++i) s += p[i] < 128 ? static_cast<char>(p[i]) : '?';
  } else {
    if (v->nbytes < n) return {};
    s.assign(static_cast<const char*>(v->data), n);
  }
  return s;
}

class MatContainer : public SignalContainer {
 public:
  explicit MatContainer(const std::string& path) : path_(path) {
    InitMatio();
    // Before matio: it trusts the declared dims over the stored data (mat_layout.cpp).
    const std::optional<std::size_t> expected = CheckMatLayout(path);
    mat_.reset(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
    if (!mat_)
      throw InputError(path + ": not a readable MAT file (bad header, or truncated)" +
                       MatioDetail());
    Mat_Rewind(mat_.get());
    while (true) {
      matvar_t* v = Mat_VarReadNextInfo(mat_.get());
      if (!v) break;
      infos_.emplace_back(v);
      if (infos_.size() > 100000) throw InputError(path + ": more than 100000 variables");
    }
    if (!g_matio_message.empty())
      throw InputError(path + ": malformed or truncated MAT file" + MatioDetail());
    // Mat_VarReadNextInfo returns NULL both at the end and at an error it does not always log:
    // fewer variables than the file holds means it stopped early (a damaged file), not that
    // the file ends there. A file of no variables, as counted independently, stays legal.
    if (expected && infos_.size() < *expected)
      throw InputError(fmt::format("{}: malformed or truncated MAT file: matio read {} of its "
                                   "{} variables",
                                   path, infos_.size(), *expected));
    for (const auto& v : infos_)
      if (v->class_type == MAT_C_STRUCT && v->name && ControlDeskShape(v.get()))
        controldesk_ = v->name;
  }

  // Every variable, with the ranges of numeric vectors: no more than kMaxRangeValues values
  // read in all; past them a variable is listed without its range.
  std::vector<VariableInfo> List() override {
    std::vector<VariableInfo> out;
    double budget = kMaxRangeValues;
    for (const auto& v : infos_) {
      VariableInfo info = Describe(v.get(), v->name ? v->name : "");
      if (info.numeric_vector && info.length > 0)
        info.min = info.max = std::numeric_limits<double>::quiet_NaN();
      const double n = TreeElements(v.get());
      if (info.numeric_vector && info.length > 0 && n <= kMaxVariableElements && n <= budget) {
        budget -= n;
        g_matio_message.clear();
        VarPtr full(Mat_VarRead(mat_.get(), v->name));
        if (full) {
          Eigen::VectorXd values;
          if (ToDoubles(full.get(), &values)) SetRange(info, values);
        }
        g_matio_message.clear();
      }
      out.push_back(info);
    }
    if (!controldesk_.empty()) {
      const matvar_t* s = ControlDesk();
      const matvar_t* time = Field(Field(s, "X", 0), "Data", 0);
      VariableInfo t_info = Describe(time, "X.Data");
      t_info.type += fmt::format(" ({}.X.Data, the time)", controldesk_);
      Eigen::VectorXd t_values;
      if (time && ToDoubles(time, &t_values)) SetRange(t_info, t_values);
      out.push_back(t_info);
      const matvar_t* y = Field(s, "Y", 0);
      const size_t n = static_cast<size_t>(ElementCount(Dims(y)));
      for (size_t i = 0; i < n; ++i) {
        const matvar_t* d = Field(y, "Data", i);
        VariableInfo info = Describe(d, CharString(Field(y, "Name", i)));
        info.type += fmt::format(" ({}.Y({}).Data)", controldesk_, i + 1);
        Eigen::VectorXd values;
        if (d && ToDoubles(d, &values)) SetRange(info, values);
        out.push_back(info);
      }
    }
    return out;
  }

  Eigen::VectorXd Read(const VariableSpec& spec) override {
    const std::string where = path_ + ":" + spec.text;
    const matvar_t* info = Find(spec.name);
    VarPtr full;
    const matvar_t* var = nullptr;
    if (info) {
      CheckBound(info, where);
      g_matio_message.clear();
      full.reset(Mat_VarRead(mat_.get(), spec.name.c_str()));
      if (!full)
        throw InputError(where + ": cannot read the variable's data (truncated or corrupt file)" +
                         MatioDetail());
      var = full.get();
    } else if (!controldesk_.empty()) {
      var = ControlDeskSignal(spec.name);
    }
    if (!var) {
      std::vector<std::string> names = Names();
      throw InputError(fmt::format(
          "{}: no variable '{}' (variables: {}){}", path_, spec.name, JoinList(names),
          controldesk_.empty() ? ""
                               : "; a ControlDesk signal by its Y(k).Name or Y(k).Data, the "
                                 "time by X.Data"));
    }
    return Pick(var, spec, where);
  }

  std::vector<std::string> DefaultColumns() override {
    std::vector<std::string> out;
    for (const auto& v : infos_) {
      if (!v->name || !IsNumericClass(v.get()) || v->isComplex) continue;
      const auto dims = Dims(v.get());
      if (NonSingleton(dims) != 1 || ElementCount(dims) < 2) continue;
      const std::string name = v->name;
      if (std::all_of(name.begin(), name.end(), [](char c) {
            return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
          }))
        out.push_back(name);
    }
    return out;
  }

  bool ImpliedTime(Eigen::VectorXd* t_s) override {
    if (controldesk_.empty()) return false;
    const matvar_t* x = Field(ControlDesk(), "X", 0);
    const matvar_t* d = Field(x, "Data", 0);
    if (!d) return false;
    VariableSpec spec;
    spec.text = spec.name = "X.Data";
    *t_s = Pick(d, spec, path_ + ":" + controldesk_ + ".X.Data");
    return true;
  }

  std::string MappingRequiredReason() override {
    if (controldesk_.empty()) return {};
    return fmt::format(
        "a dSPACE ControlDesk struct '{}': name its signals with --var u=NAME,x=NAME (signals: "
        "{})",
        controldesk_, JoinList(SignalNames()));
  }

 private:
  static const matvar_t* Field(const matvar_t* s, const char* name, size_t index) {
    if (!s || s->class_type != MAT_C_STRUCT || !s->data) return nullptr;
    if (index >= static_cast<size_t>(ElementCount(Dims(s)))) return nullptr;
    return Mat_VarGetStructFieldByName(const_cast<matvar_t*>(s), name, index);
  }

  static bool ControlDeskShape(const matvar_t* s) {
    const matvar_t* x = Field(s, "X", 0);
    const matvar_t* y = Field(s, "Y", 0);
    return x && y && Field(x, "Data", 0) && Field(y, "Name", 0) && Field(y, "Data", 0);
  }

  const matvar_t* Find(const std::string& name) const {
    for (const auto& v : infos_)
      if (v->name && name == v->name) return v.get();
    return nullptr;
  }

  std::vector<std::string> Names() {
    std::vector<std::string> names;
    for (const auto& v : infos_)
      if (v->name) names.push_back(v->name);
    if (!controldesk_.empty())
      for (const auto& s : SignalNames()) names.push_back(s);
    return names;
  }

  void CheckBound(const matvar_t* info, const std::string& where) const {
    const double n = TreeElements(info);
    if (n > kMaxVariableElements)
      throw InputError(
          fmt::format("{}: declares {} ({:.3g} elements), more than the {:.0f} a "
                      "variable may hold",
                      where, FormatDims(Dims(info)), n, kMaxVariableElements));
  }

  // The whole ControlDesk struct, read once.
  const matvar_t* ControlDesk() {
    if (!controldesk_data_) {
      const std::string where = path_ + ":" + controldesk_;
      CheckBound(Find(controldesk_), where);
      g_matio_message.clear();
      controldesk_data_.reset(Mat_VarRead(mat_.get(), controldesk_.c_str()));
      if (!controldesk_data_ || !ControlDeskShape(controldesk_data_.get()))
        throw InputError(where + ": cannot read the struct's data (truncated or corrupt file)" +
                         MatioDetail());
    }
    return controldesk_data_.get();
  }

  std::vector<std::string> SignalNames() {
    std::vector<std::string> names;
    const matvar_t* y = Field(ControlDesk(), "Y", 0);
    const size_t n = static_cast<size_t>(ElementCount(Dims(y)));
    for (size_t i = 0; i < n; ++i) names.push_back(CharString(Field(y, "Name", i)));
    return names;
  }

  // A ControlDesk name: X.Data (the time) or Y(k).Data (k 1-based, as `sysid info` lists the
  // signals), each also prefixed by the struct's name; else a signal's Y(k).Name as stored, or
  // without its double quotes (ControlDesk writes "Model Root"/"DAC"/"u"/"Out1", the docs and
  // users Model Root/DAC/u/Out1), or without the last component, the block's port (Out1), when
  // only one signal matches so.
  const matvar_t* ControlDeskSignal(const std::string& spec) {
    const matvar_t* s = ControlDesk();
    const matvar_t* y = Field(s, "Y", 0);
    const size_t n = static_cast<size_t>(ElementCount(Dims(y)));
    const auto data = [&](const matvar_t* v, const std::string& element) {
      if (!v)
        throw InputError(fmt::format("{}:{}.{}: missing", path_, controldesk_, element));
      return v;
    };
    const std::string prefix = controldesk_ + ".";
    const std::string bare =
        spec.compare(0, prefix.size(), prefix) == 0 ? spec.substr(prefix.size()) : spec;
    if (bare == "X.Data" || bare == "X(1).Data")
      return data(Field(Field(s, "X", 0), "Data", 0), "X.Data");
    if (bare.size() > 8 && bare.compare(0, 2, "Y(") == 0 &&
        bare.compare(bare.size() - 6, 6, ").Data") == 0) {
      const std::string k = bare.substr(2, bare.size() - 8);
      size_t index = 0;
      const auto [ptr, ec] = std::from_chars(k.data(), k.data() + k.size(), index);
      if (k.empty() || ec != std::errc() || ptr != k.data() + k.size() || index == 0 ||
          index > n)
        throw InputError(fmt::format("{}: {}: expected Y(k).Data with k = 1..{} (1-based, like "
                                     "MATLAB: the struct '{}' holds {} signals)",
                                     path_, spec, n, controldesk_, n));
      return data(Field(y, "Data", index - 1), fmt::format("Y({}).Data", index));
    }
    const auto unquoted = [](std::string text) {
      text.erase(std::remove(text.begin(), text.end(), '"'), text.end());
      return text;
    };
    const std::string want = unquoted(spec);
    std::vector<size_t> exact, without_port;
    for (size_t i = 0; i < n; ++i) {
      const std::string name = CharString(Field(y, "Name", i));
      if (name == spec) return data(Field(y, "Data", i), fmt::format("Y({}).Data", i + 1));
      const std::string plain = unquoted(name);
      if (plain == want) exact.push_back(i);
      if (plain.size() > want.size() + 1 && plain.compare(0, want.size(), want) == 0 &&
          plain[want.size()] == '/' && plain.find('/', want.size() + 1) == std::string::npos)
        without_port.push_back(i);
    }
    const std::vector<size_t>& found = exact.empty() ? without_port : exact;
    if (found.size() > 1) {
      std::vector<std::string> names;
      for (const size_t i : found)
        names.push_back(fmt::format("Y({}).Name {}", i + 1, CharString(Field(y, "Name", i))));
      throw InputError(fmt::format("{}: '{}' names {} signals of '{}' ({}): name one by its "
                                   "Y(k).Data or its whole name",
                                   path_, spec, found.size(), controldesk_, JoinList(names)));
    }
    if (found.empty()) return nullptr;
    return data(Field(y, "Data", found.front()), fmt::format("Y({}).Data", found.front() + 1));
  }

  static VariableInfo Describe(const matvar_t* v, const std::string& name) {
    VariableInfo info;
    info.name = name;
    if (!v) return info;
    info.type = ClassName(v);
    info.dims = Dims(v);
    info.complex = v->isComplex != 0;
    info.sparse = v->class_type == MAT_C_SPARSE;
    info.numeric_vector = IsNumericClass(v) && !info.complex && NonSingleton(info.dims) <= 1;
    if (info.numeric_vector) info.length = static_cast<std::uint64_t>(ElementCount(info.dims));
    return info;
  }

  // All elements of a real numeric variable as doubles (column-major); false when not numeric.
  static bool ToDoubles(const matvar_t* v, Eigen::VectorXd* out) {
    if (!IsNumericClass(v) || v->isComplex || !v->data) return false;
    const size_t n = static_cast<size_t>(ElementCount(Dims(v)));
    const size_t size = Mat_SizeOfClass(v->class_type);
    if (size == 0 || v->nbytes < n * size) return false;
    out->resize(static_cast<Eigen::Index>(n));
    switch (v->class_type) {
      case MAT_C_DOUBLE:
        Convert<double>(v->data, n, *out);
        break;
      case MAT_C_SINGLE:
        Convert<float>(v->data, n, *out);
        break;
      case MAT_C_INT8:
        Convert<std::int8_t>(v->data, n, *out);
        break;
      case MAT_C_UINT8:
        Convert<std::uint8_t>(v->data, n, *out);
        break;
      case MAT_C_INT16:
        Convert<std::int16_t>(v->data, n, *out);
        break;
      case MAT_C_UINT16:
        Convert<std::uint16_t>(v->data, n, *out);
        break;
      case MAT_C_INT32:
        Convert<std::int32_t>(v->data, n, *out);
        break;
      case MAT_C_UINT32:
        Convert<std::uint32_t>(v->data, n, *out);
        break;
      case MAT_C_INT64:
        Convert<std::int64_t>(v->data, n, *out);
        break;
      case MAT_C_UINT64:
        Convert<std::uint64_t>(v->data, n, *out);
        break;
      default:
        return false;
    }
    return true;
  }

  // The vector `spec` picks from the read variable `v`, checked.
  static Eigen::VectorXd Pick(const matvar_t* v, const VariableSpec& spec,
                              const std::string& where) {
    const auto dims = Dims(v);
    const std::string shape = ClassName(v) + " " + FormatDims(dims);
    if (v->isComplex)
      throw InputError(where + ": is complex (" + shape + "); expected real numbers");
    if (v->class_type == MAT_C_SPARSE)
      throw InputError(where + ": is a sparse matrix (" + FormatDims(dims) +
                       "); save it full (full(...)) first");
    if (v->class_type == MAT_C_STRUCT)
      throw InputError(where + ": is a struct (" + FormatDims(dims) +
                       "); expected a numeric vector (a dSPACE ControlDesk export is read by "
                       "naming its signals: --var u=NAME)");
    if (!IsNumericClass(v))
      throw InputError(where + ": is " +
                       (v->class_type == MAT_C_CELL ? "a cell array" : "a " + ClassName(v)) + " (" +
                       FormatDims(dims) + "); expected a real numeric vector");
    if (ElementCount(dims) == 0) throw InputError(where + ": is empty (" + shape + ")");
    Eigen::VectorXd all;
    if (!ToDoubles(v, &all))
      throw InputError(where + ": cannot read the variable's data (truncated or corrupt file)");
    Eigen::VectorXd out;
    const auto n = static_cast<Eigen::Index>(PickedLength(spec, dims, shape, "matrix", where));
    if (spec.pick == VariableSpec::Pick::kWhole) {
      out = std::move(all);
    } else {
      const bool column = spec.pick == VariableSpec::Pick::kColumn;
      const std::uint64_t rows = dims[0], k = spec.index - 1;
      out.resize(n);
      for (Eigen::Index i = 0; i < n; ++i)
        out[i] = column ? all[static_cast<Eigen::Index>(k * rows) + i]
                        : all[static_cast<Eigen::Index>(k + static_cast<std::uint64_t>(i) * rows)];
    }
    CheckFinite(out, where);
    return out;
  }

  std::string path_;
  // Owned by a member, not closed in a destructor: the constructor throws on a malformed file
  // after Mat_Open succeeded, and only members are cleaned up then (a destructor would leak).
  struct MatCloser {
    void operator()(mat_t* m) const { Mat_Close(m); }
  };
  std::unique_ptr<mat_t, MatCloser> mat_;
  std::vector<VarPtr> infos_;
  std::string controldesk_;
  VarPtr controldesk_data_;
};

}  // namespace

std::unique_ptr<SignalContainer> OpenMatContainer(const std::string& path) {
  return std::make_unique<MatContainer>(path);
}

}  // namespace sysid::internal
