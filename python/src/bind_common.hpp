// Helpers shared by the binding files of the extension module sysid._sysid.
#ifndef SYSID_PYTHON_BIND_COMMON_HPP_
#define SYSID_PYTHON_BIND_COMMON_HPP_

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <string_view>
#include <utility>

#include "sysid/error.hpp"

namespace sysid::python {

namespace py = pybind11;

/// Long calls run with the GIL released, so a thread pool over recordings uses every core.
using ReleaseGil = py::call_guard<py::gil_scoped_release>;

/// A default-constructed T with the keyword arguments applied as attribute assignments, so the
/// defaults are the C++ struct's (one source) and a misspelt keyword is an error, not a no-op.
template <typename T>
T FromKeywords(const py::kwargs& kwargs) {
  py::object object = py::cast(T{});
  for (const auto& item : kwargs) {
    const std::string name = py::str(item.first);
    if (name.empty() || name[0] == '_' || !py::hasattr(object, name.c_str()))
      throw py::type_error(std::string(py::str(py::type::of(object).attr("__name__"))) +
                           ": unknown option '" + name + "'");
    py::object value = py::reinterpret_borrow<py::object>(item.second);
    // A string for an enum field goes through the enum's parser, so a bad name raises the
    // library's OptionsError listing the accepted names (not pybind11's generic TypeError).
    const py::object current = py::getattr(object, name.c_str());
    if (py::isinstance<py::str>(value) && py::hasattr(py::type::of(current), "__members__"))
      value = py::type::of(current)(value);
    py::setattr(object, item.first, value);
  }
  return object.cast<T>();
}

/// Adds the keyword constructor T(**kwargs) and the field list used by repr / to_dict.
template <typename T, typename... Extra>
void AddKeywordInit(py::class_<T, Extra...>& cls) {
  cls.def(py::init([](const py::kwargs& kwargs) { return FromKeywords<T>(kwargs); }));
  cls.def("__copy__", [](const T& self) { return T(self); });
  cls.def("__deepcopy__", [](const T& self, const py::dict&) { return T(self); });
}

/// to_json(indent=2) and the static from_json(text, source="json") of an options struct: the
/// library's ToJson and `read` (XFromJson: every key optional, validated, positioned errors).
template <typename T, typename... Extra>
void AddOptionsJson(py::class_<T, Extra...>& cls,
                    T (*read)(std::string_view, const std::string&)) {
  cls.def("to_json", [](const T& self, int indent) { return ToJson(self, indent); },
          py::arg("indent") = 2);
  cls.def_static("from_json", read, py::arg("text"), py::arg("source") = "json");
}

/// A read-only NumPy view of a vector owned by `owner` (no copy).
inline py::array_t<double> VectorView(const Eigen::VectorXd& v, py::handle owner) {
  return py::array_t<double>({v.size()}, {static_cast<py::ssize_t>(sizeof(double))}, v.data(),
                             owner);
}

// ---- The one conversion of a caller's numbers (every binding that takes an array uses it) ----
// Accepted: anything numpy.asarray turns into real numbers (dtype kind 'f', 'i', 'u', 'b': NumPy
// arrays, lists, tuples, scalars), converted to float64. Refused with sysid.DataError naming the
// argument and what was found: str, bytes, object and complex dtypes (a complex value's
// imaginary part would be silently dropped, "1.5" would be silently parsed), ragged lists, and
// the wrong number of dimensions. NaN and inf pass: the function receiving them decides (a
// recording refuses them as a file's cell would; elementwise functions propagate them).

/// numpy.asarray(value) as float64 with its shape kept, or DataError "NAME: expected ...".
inline py::array_t<double> RealArray(py::handle value, const std::string& name) {
  const auto describe = [](py::handle v) {
    return std::string(py::str(py::type::of(v).attr("__name__")));
  };
  py::object converted;
  try {
    converted = py::module_::import("numpy").attr("asarray")(value);
  } catch (const py::error_already_set&) {  // ragged nesting, objects numpy cannot convert
    throw InputError(name + ": expected an array of real numbers, got a " + describe(value) +
                     " that NumPy cannot convert to one");
  }
  const auto array = py::reinterpret_borrow<py::array>(converted);
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u' && kind != 'b') {
    const std::string dtype = py::str(array.dtype());
    throw InputError(name + ": expected real numbers, got dtype " + dtype +
                     (kind == 'c' ? " (complex: give the real part explicitly)" : ""));
  }
  return py::array_t<double, py::array::forcecast>::ensure(array);
}

/// A 1-D vector of real numbers (a 0-d scalar is refused: a signal has samples); DataError when
/// it has no values unless `allow_empty`.
inline Eigen::VectorXd RealVector(py::handle value, const std::string& name,
                                  bool allow_empty = false) {
  const py::array_t<double> array = RealArray(value, name);
  if (array.ndim() != 1)
    throw InputError(name + ": expected a 1-D array, got " + std::to_string(array.ndim()) +
                     " dimensions");
  if (array.size() == 0 && !allow_empty)
    throw InputError(name + ": empty array; expected at least one value");
  Eigen::VectorXd out(array.size());
  const auto view = array.unchecked<1>();
  for (py::ssize_t i = 0; i < array.size(); ++i) out[i] = view(i);
  return out;
}

/// An N x `columns` matrix of real numbers (rows are samples): a 2-D array, or a 1-D array when
/// `columns` is 1. DataError when it is empty or has another column count.
inline Eigen::MatrixXd RealMatrix(py::handle value, const std::string& name, int columns) {
  const py::array_t<double> array = RealArray(value, name);
  if (array.ndim() == 1 && columns == 1) {
    const Eigen::VectorXd v = RealVector(array, name);
    return v;
  }
  if (array.ndim() != 2)
    throw InputError(name + ": expected an N x " + std::to_string(columns) + " array, got " +
                     std::to_string(array.ndim()) + " dimensions");
  if (array.shape(1) != columns)
    throw InputError(name + ": " + std::to_string(array.shape(1)) + " columns, expected " +
                     std::to_string(columns));
  if (array.shape(0) == 0) throw InputError(name + ": empty array; expected at least one row");
  Eigen::MatrixXd out(array.shape(0), columns);
  const auto view = array.unchecked<2>();
  for (py::ssize_t i = 0; i < array.shape(0); ++i)
    for (py::ssize_t j = 0; j < columns; ++j) out(i, j) = view(i, j);
  return out;
}

/// DataError "WHO: NAME_A has N values, NAME_B has M" unless the two are equally long.
inline void CheckSameLength(const std::string& who, const std::string& name_a, Eigen::Index n_a,
                            const std::string& name_b, Eigen::Index n_b) {
  if (n_a != n_b)
    throw InputError(who + ": " + name_a + " has " + std::to_string(n_a) + " values, " + name_b +
                     " has " + std::to_string(n_b) + "; they must be equally long");
}

/// OptionsError "WHO::dt_s = X. Violated constraint: 0 < dt_s < infinity" (the library's rule
/// and words for a sample interval, as AnalyticInverse) unless dt_s is positive and finite.
inline void CheckTimeStep(const std::string& who, double dt_s) {
  if (!(dt_s > 0) || !std::isfinite(dt_s))
    throw OptionsError(who, "dt_s", std::to_string(dt_s), "0 < dt_s < infinity");
}

/// f applied to every element of RealArray(value, name): a scalar for a scalar, else an array of
/// the same shape.
template <typename F>
py::object RealElementwise(py::handle value, const std::string& name, F f) {
  return py::vectorize([&f](double x) { return f(x); })(RealArray(value, name));
}

void BindIo(py::module_& m);
void BindModel(py::module_& m);
void BindIdentify(py::module_& m);
void BindDominance(py::module_& m);
void BindNeural(py::module_& m);
void BindStage(py::module_& m);
void BindControl(py::module_& m);  // after BindStage: adds to sysid.stage
void BindHysteresis(py::module_& m);
void BindDeploy(py::module_& m);
void BindValidate(py::module_& m);

}  // namespace sysid::python

#endif  // SYSID_PYTHON_BIND_COMMON_HPP_
