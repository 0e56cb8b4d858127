// Flags that set the fields of a described options struct (sysid/serialize.hpp). A flag names
// the member it sets; the field's name is found in the struct's Serialize list by the member's
// address, so it is never typed twice, and a member the list does not hold fails at
// registration. Each command keeps the record (ExposedOptionsOf), and
// tests/cli/field_flags_test.cpp checks it against every struct's whole field list: a field
// gets a flag or a written reason why not.
//
//   AddFieldOption(cmd, "--tau-min", d, d.tau_min_s, "lower bound of tau [s]")->check(range);
//   BindField(cmd, AddThreadsOption(cmd, d.threads, "..."), d, d.threads);  // a shared helper
#ifndef SYSID_APPS_CLI_FIELD_FLAG_HPP_
#define SYSID_APPS_CLI_FIELD_FLAG_HPP_

#include <CLI/CLI.hpp>
#include <string>
#include <type_traits>
#include <typeinfo>
#include <utility>
#include <vector>

#include "sysid/serialize.hpp"

namespace sysid::cli {

/// A described struct a command's flags set: its fields, and which flag sets which.
struct ExposedOptions {
  std::string type;                 ///< the struct's name without namespace, "DelayTuningOptions"
  const void* address = nullptr;    ///< the instance the command's flags write
  std::vector<std::string> fields;  ///< every field, a nested struct's as "motion.velocity_column"
  std::vector<std::pair<std::string, std::string>> bound;  ///< (flag, field), in binding order
};

/// The name a command's record gives `option`: its first long name ("--tau-min"), else its
/// short one ("-o"), else its positional name ("recordings"); hidden options too (CLI11's
/// get_name() is empty for those).
std::string FlagName(const CLI::Option* option);

/// The described structs whose fields `cmd`'s own flags set, in the order first bound. The
/// record is keyed by the command's address: an app is built once per process (main; a test
/// keeps its app alive), so no freed command's record passes to a new one.
std::vector<ExposedOptions> ExposedOptionsOf(const CLI::App* cmd);

namespace internal {

/// The path of the field at `target` of type F ("plateau.max_speed_mps"), empty when no field
/// of the struct (or of its nested described structs) is that member.
template <class F>
class FieldPathArchive {
 public:
  explicit FieldPathArchive(const F* target) : target_(target) {}
  template <class V>
  void Visit(const NameValue<V>& nv) {
    if (!path.empty()) return;
    // A nested struct shares its address with its first field: the type tells them apart.
    if constexpr (std::is_same_v<V, F>) {
      if (nv.value() == target_) {
        path = prefix_ + nv.name();
        return;
      }
    }
    if constexpr (IsDescribed<V>::value) {
      const std::string outer = prefix_;
      prefix_ += std::string(nv.name()) + ".";
      nv.value()->Serialize(this);
      prefix_ = outer;
    }
  }
  std::string path;

 private:
  const F* target_;
  std::string prefix_;
};

/// Every field path of a struct, nested described structs opened into their own fields.
class FieldLeafArchive {
 public:
  template <class V>
  void Visit(const NameValue<V>& nv) {
    if constexpr (IsDescribed<V>::value) {
      const std::string outer = prefix_;
      prefix_ += std::string(nv.name()) + ".";
      nv.value()->Serialize(this);
      prefix_ = outer;
    } else {
      leaves.push_back(prefix_ + nv.name());
    }
  }
  std::vector<std::string> leaves;

 private:
  std::string prefix_;
};

/// Adds (flag, path) to `cmd`'s record of the struct at `options`. Throws std::logic_error
/// naming the flag and the struct when `path` is empty (the member is no listed field).
void RecordFieldFlag(const CLI::App* cmd, const std::type_info& type, const void* options,
                     std::vector<std::string> fields, const std::string& path,
                     const std::string& flag);

}  // namespace internal

/// Records that `option`, a flag of `cmd`, sets `field`, a member of the described struct
/// `options` (possibly in a nested described struct; possibly through a conversion, e.g. a
/// text flag parsed into an enum when the command runs). Returns `option`.
template <class Options, class V>
CLI::Option* BindField(CLI::App* cmd, CLI::Option* option, Options& options, const V& field) {
  static_assert(IsDescribed<Options>::value, "BindField: the struct has no Serialize list");
  internal::FieldPathArchive<V> find(&field);
  options.Serialize(&find);
  internal::FieldLeafArchive leaves;
  options.Serialize(&leaves);
  internal::RecordFieldFlag(cmd, typeid(Options), &options, std::move(leaves.leaves), find.path,
                            FlagName(option));
  return option;
}

/// The option `flag` of `cmd` reading into `field`, a member of `options`, with the field's
/// value as the help's default (capture_default_str); recorded as BindField does.
template <class Options, class V>
CLI::Option* AddFieldOption(CLI::App* cmd, const std::string& flag, Options& options, V& field,
                            const std::string& doc) {
  return BindField(cmd, cmd->add_option(flag, field, doc)->capture_default_str(), options,
                   field);
}

/// The switch `flag` of `cmd` setting the bool `field` of `options` to true; recorded as
/// BindField does.
template <class Options>
CLI::Option* AddFieldFlag(CLI::App* cmd, const std::string& flag, Options& options, bool& field,
                          const std::string& doc) {
  return BindField(cmd, cmd->add_flag(flag, field, doc), options, field);
}

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_FIELD_FLAG_HPP_
