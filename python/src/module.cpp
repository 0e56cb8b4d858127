// The extension module sysid._sysid: libsysid's errors as Python exceptions, then the bindings
// of each header (bind_*.cpp). The pure-Python layer (python/sysid/__init__.py) re-exports it.
#include <regex>
#include <string>

#include "bind_common.hpp"
#include "sysid/error.hpp"

namespace sysid::python {
namespace {

/// Raises `type(message)` with file, line and column attributes parsed from a message that
/// starts "FILE:LINE:COLUMN:" or "FILE:LINE:" (None when absent).
void RaiseWithLocation(py::handle type, const char* message) {
  py::object error = type(message);
  py::object file = py::none(), line = py::none(), column = py::none();
  static const std::regex kLocated(R"(^(.+?):(\d+):(?:(\d+):)?\s)");
  std::cmatch match;
  if (std::regex_search(message, match, kLocated)) {
    file = py::str(match[1].str());
    line = py::int_(std::stol(match[2].str()));
    if (match[3].matched) column = py::int_(std::stol(match[3].str()));
  }
  error.attr("file") = file;
  error.attr("line") = line;
  error.attr("column") = column;
  PyErr_SetObject(type.ptr(), error.ptr());
}

}  // namespace

PYBIND11_MODULE(_sysid, m) {
  m.doc() = "libsysid: identification and inverse models of friction-dominated actuators";

  // One hierarchy: sysid.Error is the base of every error the library throws on purpose.
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<InputError> data_error(m, "DataError", error.ptr());
  static py::exception<OptionsError> options_error(m, "OptionsError", error.ptr());
  static py::exception<NumericalError> numerical_error(m, "NumericalError", error.ptr());
  static py::exception<InternalError> internal_error(m, "InternalError", error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      RaiseWithLocation(data_error, e.what());
    } catch (const OptionsError& e) {
      options_error(e.what());
    } catch (const NumericalError& e) {
      numerical_error(e.what());
    } catch (const InternalError& e) {
      internal_error(e.what());
    } catch (const Error& e) {
      error(e.what());
    }
  });

  BindIo(m);
  BindModel(m);
  BindIdentify(m);
  BindDominance(m);
  BindNeural(m);
  BindStage(m);
  BindControl(m);
  BindHysteresis(m);
  BindDeploy(m);
  BindValidate(m);
}

}  // namespace sysid::python
