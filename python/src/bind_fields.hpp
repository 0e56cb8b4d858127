// The Python attributes of a described struct (sysid/serialize.hpp), after pydrake's
// DefAttributesUsingSerialize: one read-write property per field, in Serialize order, and the
// class attribute __fields__ (their names), which sysid's repr, equality, to_dict and pickling
// walk. A field added to Serialize is in Python with no other edit.
#ifndef SYSID_PYTHON_BIND_FIELDS_HPP_
#define SYSID_PYTHON_BIND_FIELDS_HPP_

#include <pybind11/pybind11.h>

#include <cstddef>
#include <string>
#include <vector>

#include "sysid/serialize.hpp"

namespace sysid::python {

namespace py = pybind11;

template <typename T, typename... Extra>
class FieldPropertyArchive {
 public:
  FieldPropertyArchive(py::class_<T, Extra...>* cls, const T* probe)
      : cls_(cls), base_(reinterpret_cast<const char*>(probe)) {}

  // A field is found in any instance at its offset in the probe (the members of a standard
  // layout or not, an offset within the object is the same for every object of the type).
  template <typename V>
  void Visit(const NameValue<V>& nv) {
    const std::ptrdiff_t offset = reinterpret_cast<const char*>(nv.value()) - base_;
    cls_->def_property(
        nv.name(),
        [offset](const T& self) -> const V& {
          return *reinterpret_cast<const V*>(reinterpret_cast<const char*>(&self) + offset);
        },
        [offset](T& self, const V& value) {
          *reinterpret_cast<V*>(reinterpret_cast<char*>(&self) + offset) = value;
        });
    names.emplace_back(nv.name());
  }

  std::vector<std::string> names;

 private:
  py::class_<T, Extra...>* cls_;
  const char* base_;
};

/// Defines T's fields as properties on `cls` and sets `cls.__fields__`.
template <typename T, typename... Extra>
void DefFields(py::class_<T, Extra...>& cls) {
  T probe{};
  FieldPropertyArchive<T, Extra...> archive(&cls, &probe);
  probe.Serialize(&archive);
  cls.attr("__fields__") = py::tuple(py::cast(archive.names));
}

}  // namespace sysid::python

#endif  // SYSID_PYTHON_BIND_FIELDS_HPP_
