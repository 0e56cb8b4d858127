// The rule for every "-o DIR" of the CLI: a folder is written whole or not at all, and only a
// new folder, an empty one, or one this toolkit wrote before (it holds the .sysid-output marker)
// is ever replaced, the last only with --force. Inputs are never inside it.
#ifndef SYSID_APPS_CLI_OUTPUT_FOLDER_HPP_
#define SYSID_APPS_CLI_OUTPUT_FOLDER_HPP_

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sysid::cli {

/// Marker file of a folder written by sysid.
inline constexpr const char* kOutputMarker = ".sysid-output";

class OutputFolder {
 public:
  /// Checks `dir` before any work (throws OptionsError, exit 1): trailing slashes are dropped;
  /// `inputs` (files or folders) must not be the folder or inside it; an existing non-empty
  /// folder needs the marker and `force`. `command` names the writer in the marker.
  OutputFolder(const std::string& dir, bool force, const std::vector<std::string>& inputs,
               std::string command);
  /// The final folder (absolute, normalised).
  const std::filesystem::path& path() const { return out_; }
  /// Calls `write(folder)` on a temporary sibling folder holding the marker, then renames it
  /// into place (replacing an empty or marked folder). On any error the temporary folder is
  /// removed and the previous folder is untouched.
  void Write(const std::function<void(const std::filesystem::path&)>& write) const;

 private:
  std::string given_;
  std::string command_;
  std::filesystem::path out_;
  std::filesystem::path tmp_;
};

/// The OutputFolder of an optional "-o DIR": none when `dir` is empty. Entries of `inputs`
/// that are empty or name no existing file or folder (e.g. a preset name) are skipped.
std::optional<OutputFolder> OptionalOutputFolder(const std::string& dir, bool force,
                                                 const std::vector<std::string>& inputs,
                                                 const std::string& command);

/// True when `p` is a folder holding the sysid marker.
bool HasOutputMarker(const std::filesystem::path& p);

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_OUTPUT_FOLDER_HPP_
