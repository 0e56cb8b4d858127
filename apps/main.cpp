// sysid: identification and inverse models of friction-dominated actuators.
// Subcommands live in commands/, one file each; see cli/common.hpp for the conventions.
#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>

#include "cli/common.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"

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
    return code == 0 ? kSuccess : kUsage;
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
  return kSuccess;
}
