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
//
// A file whose format predates its struct (the model file: "tau" for tau_s, every key but tau
// required, its ranges checked as each number is read) says so on the field:
//   a->Visit(SYSID_NVP(tau_s).Renamed("tau").Minimum(0).Maximum(1).Unit("s"));
//   a->Visit(SYSID_NVP(a3).Required().ExclusiveMinimum(0).Unit("m/(s^2 V)"));
#ifndef SYSID_SERIALIZE_HPP_
#define SYSID_SERIALIZE_HPP_

#include <limits>
#include <type_traits>
#include <utility>

namespace sysid {

/// How an archive shows a number that may be unbounded. JSON has no infinity: a limit whose
/// default is "none" (an infinity) is written as null, and the reader needs the sign back.
enum class FieldForm {
  kPlain,
  kUpperLimit,  ///< null is +infinity
  kLowerLimit,  ///< null is -infinity
  kNaNAsNull,   ///< a quantity that may not exist (a standard error without dof): NaN is null
};

/// A field's name and address, as an archive visits it.
template <class T>
class NameValue {
 public:
  using value_type = T;
  NameValue(const char* name, T* value) : name_(name), value_(value) {}
  /// `member`: the C++ member's name when the key is another (SYSID_NVP gives both).
  NameValue(const char* name, T* value, const char* member)
      : name_(name), value_(value), member_(member) {}
  /// The key in a file.
  const char* name() const { return name_; }
  /// The member's name, which Python shows (the unit in it: tau_s where a file says "tau"); the
  /// key when the field was named by its key alone.
  const char* member_name() const { return member_ != nullptr ? member_ : name_; }
  T* value() const { return value_; }
  FieldForm form() const { return form_; }
  NameValue UpperLimit() const { return WithForm(FieldForm::kUpperLimit); }
  NameValue LowerLimit() const { return WithForm(FieldForm::kLowerLimit); }
  NameValue NaNAsNull() const { return WithForm(FieldForm::kNaNAsNull); }

  /// The key must be written (a reader refuses a file without it); by default an absent key
  /// keeps the field's value.
  NameValue Required() const {
    NameValue nv = *this;
    nv.required_ = true;
    return nv;
  }
  bool required() const { return required_; }

  /// The range a reader accepts for a number, checked as it is read (JSON Schema's words); by
  /// default any finite number, the rules being Validate()'s.
  NameValue Minimum(double lo) const { return WithLow(lo, false); }
  NameValue ExclusiveMinimum(double lo) const { return WithLow(lo, true); }
  NameValue Maximum(double hi) const {
    NameValue nv = *this;
    nv.hi_ = hi;
    return nv;
  }
  double lo() const { return lo_; }
  double hi() const { return hi_; }
  bool lo_open() const { return lo_open_; }

  /// A described struct's fields written into the enclosing object, not under the name (a
  /// pulse's keys beside its estimate's).
  NameValue Inline() const {
    NameValue nv = *this;
    nv.inline_ = true;
    return nv;
  }
  bool inlined() const { return inline_; }

  /// A list or a text left out of the file when it is empty (a delay curve when no delay was
  /// searched); read back as empty.
  NameValue OmitEmpty() const {
    NameValue nv = *this;
    nv.omit_empty_ = true;
    return nv;
  }
  bool omit_empty() const { return omit_empty_; }

  /// A list of pairs written as objects {first: ..., second: ...} (a cost curve's
  /// {"tau", "cost"}); by default a pair of numbers is an array [first, second].
  NameValue PairKeys(const char* first, const char* second) const {
    NameValue nv = *this;
    nv.first_key_ = first;
    nv.second_key_ = second;
    return nv;
  }
  const char* first_key() const { return first_key_; }
  const char* second_key() const { return second_key_; }

  /// The SI unit a file states beside the value ("1/s"), in the struct's "units" object; null
  /// when the name carries it.
  NameValue Unit(const char* unit) const {
    NameValue nv = *this;
    nv.unit_ = unit;
    return nv;
  }
  const char* unit() const { return unit_; }

  /// The same field under another key (a file whose sections name fields their own way); the
  /// member's name stays.
  NameValue Renamed(const char* key) const {
    NameValue nv = *this;
    nv.name_ = key;
    return nv;
  }

 private:
  NameValue WithLow(double lo, bool open) const {
    NameValue nv = *this;
    nv.lo_ = lo;
    nv.lo_open_ = open;
    return nv;
  }
  NameValue WithForm(FieldForm form) const {
    NameValue nv = *this;
    nv.form_ = form;
    return nv;
  }
  const char* name_;
  T* value_;
  const char* member_ = nullptr;
  FieldForm form_ = FieldForm::kPlain;
  bool required_ = false;
  double lo_ = -std::numeric_limits<double>::infinity();
  double hi_ = std::numeric_limits<double>::infinity();
  bool lo_open_ = false;
  const char* unit_ = nullptr;
  bool inline_ = false;
  bool omit_empty_ = false;
  const char* first_key_ = nullptr;
  const char* second_key_ = nullptr;
};

namespace internal {
/// An archive that visits nothing: the probe of IsDescribed.
struct NullArchive {
  template <class V>
  void Visit(const NameValue<V>&) {}
};
}  // namespace internal

/// `count` of a struct's fields from its `first` (0: the first), for a result that carries a
/// few of another struct's fields (a margins report the PI's gains and rate, not its
/// saturation):
///   FieldSlice<Archive> gains(a, 0, 3);
///   pi.Serialize(&gains);
template <class Archive>
class FieldSlice {
 public:
  FieldSlice(Archive* archive, int first, int count)
      : archive_(archive), first_(first), end_(first + count) {}
  template <class V>
  void Visit(const NameValue<V>& nv) {
    if (index_ >= first_ && index_ < end_) archive_->Visit(nv);
    ++index_;
  }

 private:
  Archive* archive_;
  int first_, end_;
  int index_ = 0;
};

/// Whether T lists its fields in Serialize.
template <class T, class = void>
struct IsDescribed : std::false_type {};
template <class T>
struct IsDescribed<T, std::void_t<decltype(std::declval<T&>().Serialize(
                          std::declval<internal::NullArchive*>()))>> : std::true_type {};

}  // namespace sysid

/// The NameValue of the member `field`, named as it is spelled.
#define SYSID_NVP(field) ::sysid::NameValue<decltype(field)>(#field, &(field), #field)

#endif  // SYSID_SERIALIZE_HPP_
