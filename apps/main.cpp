// sysid: identification and inverse models of friction-dominated actuators.
// Subcommands live in commands/, one file each; see cli/common.hpp for the conventions.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"

namespace {

// A result that did not reach standard output (a full disk, `> /dev/full`, a closed pipe) is a
// failed run: exit 2 with the reason instead of 0.
int CheckStdout(int code) {
  errno = 0;
  std::cout.flush();
  const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) != 0 || !std::cout;
  if (!failed || code != sysid::cli::kSuccess) return code;
  // The failing write may lie behind later calls that reset errno: one more byte (a newline,
  // on an output already cut short) tells the reason.
  if (errno == 0 && ::write(STDOUT_FILENO, "\n", 1) == 1) errno = 0;
  std::cerr << "sysid: error: cannot write to standard output"
            << (errno != 0 ? std::string(": ") + std::strerror(errno) : std::string()) << '\n';
  return sysid::cli::kBadInput;
}

/// `sysid --json identify ...` as `sysid identify --json ...`: --json and --threads N belong to
/// the subcommands (each says what its JSON holds and what its threads do), but a user types
/// them on either side of the subcommand's name. Moves those found before the first subcommand
/// name to just after the subcommand (after `stage facts`, both names); everything else keeps
/// its place.
const CLI::App* FindSubcommand(const CLI::App& app, const std::string& name) {
  for (const CLI::App* sub : app.get_subcommands({}))
    if (sub->check_name(name)) return sub;
  return nullptr;
}

std::vector<char*> MoveGlobalOptionsAfterSubcommand(const CLI::App& app, int argc, char** argv) {
  std::vector<char*> before, moved, out{argv[0]};
  int i = 1;
  const CLI::App* command = nullptr;
  for (; i < argc; ++i) {
    const std::string arg = argv[i];
    command = FindSubcommand(app, arg);
    if (command) break;
    if (arg == "--json" || arg.rfind("--threads=", 0) == 0) {
      moved.push_back(argv[i]);
    } else if (arg == "--threads" && i + 1 < argc) {
      moved.push_back(argv[i]);
      moved.push_back(argv[++i]);
    } else {
      before.push_back(argv[i]);
    }
  }
  if (i == argc) return std::vector<char*>(argv, argv + argc);  // no subcommand: CLI11 says so
  out.insert(out.end(), before.begin(), before.end());
  out.push_back(argv[i]);
  while (i + 1 < argc && (command = FindSubcommand(*command, argv[i + 1])) != nullptr)
    out.push_back(argv[++i]);  // a nested subcommand: `stage facts`
  out.insert(out.end(), moved.begin(), moved.end());
  out.insert(out.end(), argv + i + 1, argv + argc);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace sysid::cli;
  CLI::App app{
      "sysid: identify friction-dominated actuators (piezo ultrasonic-motor stages) from pulse "
      "and tracking recordings, and build their inverse models.\n"
      "Units are SI throughout: t [s], u [V], x [m], v [m/s], a [m/s^2].\n"
      "Exit codes: 0 success, 1 usage error, 2 bad input data, 3 numerical failure.",
      "sysid"};
  app.require_subcommand(1);
  app.add_flag("--progress", Globals().progress,
               "report progress on stderr even when it is not a terminal (before or after the "
               "subcommand)");
  // Subcommands inherit this: an option a subcommand does not know (--progress) is matched
  // against the top level, so `sysid sweep --progress ...` works as `sysid --progress sweep`.
  app.fallthrough();
  app.set_version_flag("--version", "sysid 0.1.0");
  AddRegisteredCommands(app);
  try {
    std::vector<char*> args = MoveGlobalOptionsAfterSubcommand(app, argc, argv);
    app.parse(static_cast<int>(args.size()), args.data());
    PrintNotes();
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return CheckStdout(code == 0 ? kSuccess : kUsage);
  } catch (const sysid::OptionsError& e) {
    std::cerr << "sysid: error: " << ForTerminal(e.what()) << '\n';
    return kUsage;
  } catch (const sysid::InputError& e) {
    std::cerr << "sysid: error: " << ForTerminal(e.what()) << '\n';
    return kBadInput;
  } catch (const sysid::NumericalError& e) {
    std::cerr << "sysid: numerical failure: " << ForTerminal(e.what()) << '\n';
    return kNumerical;
  } catch (const std::exception& e) {
    std::cerr << "sysid: internal error: " << ForTerminal(e.what()) << '\n';
    return 4;
  }
  return CheckStdout(kSuccess);
}
