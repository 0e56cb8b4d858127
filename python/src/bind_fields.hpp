// The Python attributes of a described struct (sysid/serialize.hpp), after pydrake's
// DefAttributesUsingSerialize: one property per field, in Serialize order, named as the C++
// member (NameValue::member_name: tau_s where a file says "tau"), and the class attribute
// __fields__ (their names), which sysid's repr, equality, to_dict walk. A field added to
// Serialize is in Python with no other edit.
//
// An options struct's properties are read-write (DefFields; it pickles in sysid/__init__.py by
// setting them). A result's are read-only (DefReadOnlyFields), and it pickles here, through the
// same field list: the state is the fields' values, then those of the members Python shows that
// the description leaves out (ReadOnlyFields::Stored, e.g. the traces a file does not hold),
// listed with their reasons in the class attribute __extra_fields__ beside the values computed
// from the others (ReadOnlyFields::Derived, not pickled).
#ifndef SYSID_PYTHON_BIND_FIELDS_HPP_
#define SYSID_PYTHON_BIND_FIELDS_HPP_

#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

#include "sysid/serialize.hpp"

namespace sysid::python {

namespace py = pybind11;

namespace internal {

template <typename V, typename = void>
struct HasToString : std::false_type {};
template <typename V>
struct HasToString<V, std::void_t<decltype(ToString(std::declval<const V&>()))>>
    : std::true_type {};

/// A field's pickled value: an enum as its number (an enum Python does not bind has no Python
/// type to pickle), anything else as Python converts it (a described struct as its bound class,
/// which pickles itself).
template <typename V>
py::object StateOf(const V& value) {
  if constexpr (std::is_enum_v<V>)
    return py::int_(static_cast<std::underlying_type_t<V>>(value));
  else
    return py::cast(value);
}

template <typename V>
void RestoreFrom(py::handle state, V& value) {
  if constexpr (std::is_enum_v<V>)
    value = static_cast<V>(state.cast<std::underlying_type_t<V>>());
  else
    value = state.cast<V>();
}

/// How a pickle reaches one stored field of T.
template <typename T>
struct FieldState {
  std::string name;
  std::function<py::object(const T&)> get;
  std::function<void(T&, py::handle)> set;
};

/// A result's pickled fields, in state order, or its JSON when it carries more than its fields.
template <typename T>
struct PickleState {
  std::vector<FieldState<T>> fields;
  std::function<std::string(const T&)> to_json;
  std::function<T(const std::string&)> from_json;
};

}  // namespace internal

enum class FieldAccess { kReadWrite, kReadOnly };

template <FieldAccess kAccess, typename T, typename... Extra>
class FieldPropertyArchive {
 public:
  FieldPropertyArchive(py::class_<T, Extra...>* cls, const T* probe)
      : cls_(cls), base_(reinterpret_cast<const char*>(probe)) {}

  // A field is found in any instance at its offset in the probe (the members of a standard
  // layout or not, an offset within the object is the same for every object of the type).
  template <typename V>
  void Visit(const NameValue<V>& nv) {
    const std::ptrdiff_t offset = reinterpret_cast<const char*>(nv.value()) - base_;
    // A value Serialize computes (a derived key written beside the fields) lives outside the
    // object and has no offset: bind it by hand, as a Derived extra.
    if (offset < 0 || offset + static_cast<std::ptrdiff_t>(sizeof(V)) >
                          static_cast<std::ptrdiff_t>(sizeof(T)))
      throw std::logic_error(std::string(typeid(T).name()) + ": field '" + nv.name() +
                             "' is not a member, so it cannot be a Python attribute");
    const auto field = [offset](const T& self) -> const V& {
      return *reinterpret_cast<const V*>(reinterpret_cast<const char*>(&self) + offset);
    };
    const auto mutable_field = [offset](T& self) -> V& {
      return *reinterpret_cast<V*>(reinterpret_cast<char*>(&self) + offset);
    };
    const char* name = nv.member_name();
    if constexpr (kAccess == FieldAccess::kReadWrite) {
      cls_->def_property(name, field, [mutable_field](T& self, const V& value) {
        mutable_field(self) = value;
      });
    } else if constexpr (std::is_enum_v<V> && internal::HasToString<V>::value) {
      // An enum Python does not bind reads as its name (a termination's "converged").
      if (py::detail::get_type_info(typeid(V)) != nullptr)
        cls_->def_property_readonly(name, field);
      else
        cls_->def_property_readonly(name, [field](const T& self) { return ToString(field(self)); });
    } else {
      cls_->def_property_readonly(name, field);
    }
    names.emplace_back(name);
    fields.push_back({name, [field](const T& self) { return internal::StateOf(field(self)); },
                      [mutable_field](T& self, py::handle state) {
                        internal::RestoreFrom(state, mutable_field(self));
                      }});
  }

  std::vector<std::string> names;
  std::vector<internal::FieldState<T>> fields;

 private:
  py::class_<T, Extra...>* cls_;
  const char* base_;
};

/// Defines T's fields as read-write properties on `cls` and sets `cls.__fields__`.
template <typename T, typename... Extra>
void DefFields(py::class_<T, Extra...>& cls) {
  const auto probe = std::make_unique<T>();
  FieldPropertyArchive<FieldAccess::kReadWrite, T, Extra...> archive(&cls, probe.get());
  probe->Serialize(&archive);
  cls.attr("__fields__") = py::tuple(py::cast(archive.names));
}

/// A result's read-only attributes and its pickling (DefReadOnlyFields): the described fields,
/// then each attribute the description leaves out, named in `__extra_fields__` with its reason.
template <typename T, typename... Extra>
class ReadOnlyFields {
 public:
  explicit ReadOnlyFields(py::class_<T, Extra...>& cls)
      : cls_(cls), state_(std::make_shared<internal::PickleState<T>>()) {
    // On the heap: gcc 12 misreads a large struct's value-initialised locals as uninitialised.
    const auto probe = std::make_unique<T>();
    FieldPropertyArchive<FieldAccess::kReadOnly, T, Extra...> archive(&cls, probe.get());
    probe->Serialize(&archive);
    cls.attr("__fields__") = py::tuple(py::cast(archive.names));
    cls.attr("__extra_fields__") = py::dict();
    state_->fields = std::move(archive.fields);
    const auto state = state_;
    cls.def(py::pickle(
        [state](const T& self) {
          if (state->to_json) return py::make_tuple(state->to_json(self));
          py::tuple values(state->fields.size());
          for (std::size_t i = 0; i < state->fields.size(); ++i)
            values[i] = state->fields[i].get(self);
          return values;
        },
        [state](const py::tuple& values) {
          if (state->from_json)
            return std::make_unique<T>(state->from_json(values[0].cast<std::string>()));
          if (values.size() != state->fields.size())
            throw py::value_error("pickled state of " + std::to_string(values.size()) +
                                  " values, expected " + std::to_string(state->fields.size()));
          auto out = std::make_unique<T>();
          for (std::size_t i = 0; i < state->fields.size(); ++i)
            state->fields[i].set(*out, values[i]);
          return out;
        }));
  }

  /// A member Python shows that the description leaves out (a trace the file does not hold):
  /// read-only, pickled after the fields.
  template <typename V>
  ReadOnlyFields& Stored(const char* name, V T::*member, const char* reason) {
    cls_.def_readonly(name, member, reason);
    AddExtra(name, reason);
    state_->fields.push_back({name,
                              [member](const T& self) { return internal::StateOf(self.*member); },
                              [member](T& self, py::handle state) {
                                internal::RestoreFrom(state, self.*member);
                              }});
    return *this;
  }

  /// A value computed from the stored ones (not pickled).
  template <typename F>
  ReadOnlyFields& Derived(const char* name, F&& getter, const char* reason) {
    cls_.def_property_readonly(name, std::forward<F>(getter), reason);
    AddExtra(name, reason);
    return *this;
  }

  /// Pickles T as its JSON text, for a result whose JSON carries members Python does not bind.
  ReadOnlyFields& PickleByJson(std::function<std::string(const T&)> to_json,
                               std::function<T(const std::string&)> from_json) {
    state_->to_json = std::move(to_json);
    state_->from_json = std::move(from_json);
    return *this;
  }

 private:
  void AddExtra(const char* name, const char* reason) {
    cls_.attr("__extra_fields__")[name] = reason;
  }
  py::class_<T, Extra...>& cls_;
  std::shared_ptr<internal::PickleState<T>> state_;
};

/// Defines T's fields as read-only properties on `cls`, sets `cls.__fields__` and pickling;
/// the returned builder adds the attributes the description leaves out.
template <typename T, typename... Extra>
ReadOnlyFields<T, Extra...> DefReadOnlyFields(py::class_<T, Extra...>& cls) {
  return ReadOnlyFields<T, Extra...>(cls);
}

}  // namespace sysid::python

#endif  // SYSID_PYTHON_BIND_FIELDS_HPP_
