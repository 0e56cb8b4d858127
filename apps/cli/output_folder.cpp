#include "cli/output_folder.hpp"

#include <fcntl.h>
#include <stdio.h>  // renameat2
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_output.hpp"

namespace sysid::cli {
namespace fs = std::filesystem;
namespace {

bool IsEmptyDir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec) && fs::is_empty(p, ec);
}

std::string ReadMarker(const fs::path& dir) {
  std::ifstream in(dir / kOutputMarker, std::ios::binary);
  std::ostringstream s;
  char buf[4096];
  in.read(buf, sizeof buf);  // a marker is one line: the first 4 KB tell runs apart
  s.write(buf, in.gcount());
  return s.str();
}

// rename(2) that fails with EEXIST/ENOTEMPTY instead of replacing `to` (where the file system
// supports it; otherwise plain rename, which still refuses a non-empty folder).
int RenameNoReplace(const fs::path& from, const fs::path& to) {
#ifdef RENAME_NOREPLACE
  if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return 0;
  if (errno != EINVAL && errno != ENOSYS) return -1;
#endif
  return ::rename(from.c_str(), to.c_str());
}

}  // namespace

std::optional<OutputFolder> OptionalOutputFolder(const std::string& dir, bool force,
                                                 const std::vector<std::string>& inputs,
                                                 const std::string& command) {
  if (dir.empty()) return std::nullopt;
  std::vector<std::string> existing;
  for (const auto& path : inputs) {
    std::error_code ec;
    if (!path.empty() && fs::exists(path, ec)) existing.push_back(path);
  }
  return OutputFolder(dir, force, existing, command);
}

bool HasOutputMarker(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec) && fs::exists(p / kOutputMarker, ec);
}

OutputFolder::State OutputFolder::Observe() const {
  State s;
  struct stat st {};
  if (::lstat(out_.c_str(), &st) != 0) return s;
  s.exists = true;
  s.dev = st.st_dev;
  s.ino = st.st_ino;
  if (S_ISDIR(st.st_mode)) s.marker = ReadMarker(out_);
  return s;
}

OutputFolder::OutputFolder(const std::string& dir, bool force,
                           const std::vector<std::string>& inputs, std::string command)
    : given_(dir), command_(std::move(command)) {
  out_ = fs::absolute(dir).lexically_normal();
  if (out_.filename().empty()) out_ = out_.parent_path();
  std::error_code ec;
  const fs::path outc = fs::weakly_canonical(out_, ec);
  if (ec) throw OptionsError("-o " + dir + ": " + ec.message());
  for (const auto& input : inputs) {
    const fs::path in = fs::weakly_canonical(fs::absolute(input), ec);
    if (ec) continue;  // the reader names the input's own problem
    const std::string ins = in.string() + "/", outs = outc.string() + "/";
    if (ins.rfind(outs, 0) == 0)
      throw OptionsError("-o " + dir + ": the output folder is or contains the input " + input +
                         "; choose another folder");
  }
  const auto status = fs::symlink_status(out_, ec);
  if (fs::exists(status) && !fs::is_directory(status))
    throw OptionsError("-o " + dir + ": exists and is not a folder" +
                       (fs::is_symlink(status) ? " (a symbolic link, never replaced)" : "") +
                       "; choose a new folder");
  if (fs::exists(status) && !IsEmptyDir(out_)) {
    if (!HasOutputMarker(out_))
      throw OptionsError("-o " + dir +
                         ": exists and was not written by sysid (no .sysid-output marker); "
                         "refusing to replace it: choose a new or empty folder");
    if (!force)
      throw OptionsError("-o " + dir + ": holds earlier sysid " + command_ +
                         " output; pass --force to replace it");
  }
  initial_ = Observe();
}

void OutputFolder::Write(const std::function<void(const fs::path&)>& write) const {
  const StagingFolder staging(out_);  // removed on error, Ctrl-C, or left empty once renamed
  WriteFileAtomically((staging.path() / kOutputMarker).string(),
                      "written by sysid " + command_ + " (run " + staging.run_id() + ")\n");
  // An error names the folder the user gave, not the hidden staging folder it was written in.
  const auto named = [&](const std::string& what) {
    std::string text = what;
    const std::string hidden = staging.path().string();
    std::string shown = given_;
    while (shown.size() > 1 && shown.back() == '/') shown.pop_back();
    for (size_t at = text.find(hidden); at != std::string::npos;
         at = text.find(hidden, at + shown.size()))
      text.replace(at, hidden.size(), shown);
    return text;
  };
  try {
    write(staging.path());
  } catch (const InputError& e) {
    throw InputError(named(e.what()));
  } catch (const NumericalError& e) {
    throw NumericalError(named(e.what()));
  } catch (const OptionsError& e) {
    throw e.WithMessage(named(e.what()));
  }
  const auto changed = [&] {
    return InputError("-o " + given_ +
                      ": changed while this run worked (another run or program wrote it); "
                      "this run's results were not published, run it again");
  };
  // Checked again now: another run may have published, or someone filled the folder.
  if (!(Observe() == initial_)) throw changed();
  if (!initial_.exists || IsEmptyDir(out_)) {
    std::error_code ec;
    if (initial_.exists) fs::remove(out_, ec);  // an empty folder (rmdir: fails if filled)
    if (RenameNoReplace(staging.path(), out_) != 0) {
      if (errno == EEXIST || errno == ENOTEMPTY) throw changed();
      throw InputError("-o " + given_ + ": cannot publish: " + std::strerror(errno));
    }
    return;
  }
  // Replace our earlier output: move it aside, check it is still the one we saw, then
  // publish; the old folder is removed last.
  const fs::path old = staging.path().string() + ".old";
  if (::rename(out_.c_str(), old.c_str()) != 0) {
    if (errno == ENOENT) throw changed();  // another run moved it aside first
    throw InputError("-o " + given_ + ": cannot replace: " + std::strerror(errno));
  }
  struct stat st {};
  const bool same = ::lstat(old.c_str(), &st) == 0 && st.st_ino == initial_.ino &&
                    st.st_dev == initial_.dev && ReadMarker(old) == initial_.marker;
  if (!same || RenameNoReplace(staging.path(), out_) != 0) {
    ::rename(old.c_str(), out_.c_str());  // put back what we moved (fails if taken meanwhile)
    throw changed();
  }
  std::error_code ec;
  fs::remove_all(old, ec);
}

}  // namespace sysid::cli
