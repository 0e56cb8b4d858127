// sysid: identification and inverse models of friction-dominated actuators.
// Subcommands live in commands/, one file each; see cli/common.hpp for the conventions.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>

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
               "report progress on stderr even when it is not a terminal");
  app.set_version_flag("--version", "sysid 0.1.0");
  AddRegisteredCommands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return CheckStdout(code == 0 ? kSuccess : kUsage);
  } catch (const sysid::OptionsError& e) {
    std::cerr << "sysid: error: " << e.what() << '\n';
    return kUsage;
  } catch (const sysid::InputError& e) {
    std::cerr << "sysid: error: " << e.what() << '\n';
    return kBadInput;
  } catch (const sysid::NumericalError& e) {
    std::cerr << "sysid: numerical failure: " << e.what() << '\n';
    return kNumerical;
  } catch (const std::exception& e) {
    std::cerr << "sysid: internal error: " << e.what() << '\n';
    return 4;
  }
  return CheckStdout(kSuccess);
}
