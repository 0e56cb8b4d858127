#include "cli/output_folder.hpp"

#include <fstream>

#include "sysid/error.hpp"

namespace sysid::cli {
namespace fs = std::filesystem;
namespace {

bool IsEmptyDir(const fs::path& p) { return fs::is_directory(p) && fs::is_empty(p); }

}  // namespace

std::optional<OutputFolder> OptionalOutputFolder(const std::string& dir, bool force,
                                                 const std::vector<std::string>& inputs,
                                                 const std::string& command) {
  if (dir.empty()) return std::nullopt;
  std::vector<std::string> existing;
  for (const auto& path : inputs)
    if (!path.empty() && fs::exists(path)) existing.push_back(path);
  return OutputFolder(dir, force, existing, command);
}

bool HasOutputMarker(const fs::path& p) {
  return fs::is_directory(p) && fs::exists(p / kOutputMarker);
}

OutputFolder::OutputFolder(const std::string& dir, bool force,
                           const std::vector<std::string>& inputs, std::string command)
    : given_(dir), command_(std::move(command)) {
  out_ = fs::absolute(dir).lexically_normal();
  if (out_.filename().empty()) out_ = out_.parent_path();
  const fs::path outc = fs::weakly_canonical(out_);
  for (const auto& input : inputs) {
    const fs::path in = fs::weakly_canonical(fs::absolute(input));
    const std::string ins = in.string() + "/", outs = outc.string() + "/";
    if (ins.rfind(outs, 0) == 0)
      throw OptionsError("-o " + dir + ": the output folder is or contains the input " + input +
                         "; choose another folder");
  }
  if (fs::exists(out_) && !fs::is_directory(out_))
    throw OptionsError("-o " + dir + ": exists and is not a folder; choose a new folder");
  if (fs::exists(out_) && !IsEmptyDir(out_)) {
    if (!HasOutputMarker(out_))
      throw OptionsError("-o " + dir +
                         ": exists and was not written by sysid (no .sysid-output marker); "
                         "refusing to replace it: choose a new or empty folder");
    if (!force)
      throw OptionsError("-o " + dir + ": holds earlier sysid " + command_ +
                         " output; pass --force to replace it");
  }
  tmp_ = out_.parent_path() / ("." + out_.filename().string() + ".tmp");
  if (fs::exists(tmp_) && !IsEmptyDir(tmp_) && !HasOutputMarker(tmp_))
    throw OptionsError(tmp_.string() + ": exists and was not written by sysid; remove it first");
}

void OutputFolder::Write(const std::function<void(const fs::path&)>& write) const {
  fs::remove_all(tmp_);  // checked in the constructor: absent, empty or ours
  try {
    fs::create_directories(tmp_);
    std::ofstream(tmp_ / kOutputMarker) << "written by sysid " << command_ << "\n";
    write(tmp_);
  } catch (...) {
    std::error_code ec;
    fs::remove_all(tmp_, ec);
    throw;
  }
  // Checked again now: the folder may have changed while we worked.
  if (fs::exists(out_)) {
    if (!IsEmptyDir(out_) && !HasOutputMarker(out_)) {
      std::error_code ec;
      fs::remove_all(tmp_, ec);
      throw OptionsError("-o " + given_ + ": was filled by someone else meanwhile; not replaced");
    }
    fs::remove_all(out_);
  }
  fs::rename(tmp_, out_);
}

}  // namespace sysid::cli
