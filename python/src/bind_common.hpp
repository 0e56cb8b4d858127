// Helpers shared by the binding files of the extension module sysid._sysid.
#ifndef SYSID_PYTHON_BIND_COMMON_HPP_
#define SYSID_PYTHON_BIND_COMMON_HPP_

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <string_view>
#include <utility>

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

void BindIo(py::module_& m);
void BindModel(py::module_& m);
void BindIdentify(py::module_& m);
void BindNeural(py::module_& m);
void BindStage(py::module_& m);
void BindControl(py::module_& m);  // after BindStage: adds to sysid.stage
void BindHysteresis(py::module_& m);

}  // namespace sysid::python

#endif  // SYSID_PYTHON_BIND_COMMON_HPP_
