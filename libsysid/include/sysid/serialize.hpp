// One description of a struct's fields, after Drake's Serialize(Archive*): the struct lists its
// fields once, in file order,
//   template <class Archive>
//   void Serialize(Archive* a) {
//     a->Visit(SYSID_NVP(tau_min_s));
//     a->Visit(SYSID_NVP(max_speed_mps).UpperLimit());
//   }
// and every reader and writer of the struct visits that list: its JSON (writer, positioned
// reader, allowed keys), its Python attributes (with repr, equality and pickling), and the test
// that walks every described type. The name is the member's, so the unit is in it (`_s`, `_mps`);
// the doc is the member's comment; the rule is the struct's Validate().
#ifndef SYSID_SERIALIZE_HPP_
#define SYSID_SERIALIZE_HPP_

#include <type_traits>
#include <utility>

namespace sysid {

/// How an archive shows a number that may be unbounded. JSON has no infinity: a limit whose
/// default is "none" (an infinity) is written as null, and the reader needs the sign back.
enum class FieldForm {
  kPlain,
  kUpperLimit,  ///< null is +infinity
  kLowerLimit,  ///< null is -infinity
};

/// A field's name and address, as an archive visits it.
template <class T>
class NameValue {
 public:
  using value_type = T;
  NameValue(const char* name, T* value) : name_(name), value_(value) {}
  const char* name() const { return name_; }
  T* value() const { return value_; }
  FieldForm form() const { return form_; }
  NameValue UpperLimit() const { return WithForm(FieldForm::kUpperLimit); }
  NameValue LowerLimit() const { return WithForm(FieldForm::kLowerLimit); }

 private:
  NameValue WithForm(FieldForm form) const {
    NameValue nv = *this;
    nv.form_ = form;
    return nv;
  }
  const char* name_;
  T* value_;
  FieldForm form_ = FieldForm::kPlain;
};

namespace internal {
/// An archive that visits nothing: the probe of IsDescribed.
struct NullArchive {
  template <class V>
  void Visit(const NameValue<V>&) {}
};
}  // namespace internal

/// Whether T lists its fields in Serialize.
template <class T, class = void>
struct IsDescribed : std::false_type {};
template <class T>
struct IsDescribed<T, std::void_t<decltype(std::declval<T&>().Serialize(
                          std::declval<internal::NullArchive*>()))>> : std::true_type {};

}  // namespace sysid

/// The NameValue of the member `field`, named as it is spelled.
#define SYSID_NVP(field) ::sysid::NameValue<decltype(field)>(#field, &(field))

#endif  // SYSID_SERIALIZE_HPP_
