// Subcommand registry. Each file in apps/commands/ defines a function that adds its subcommand
// to the CLI11 app, and registers it with a static initialiser:
//
//   static const bool kRegistered = sysid::cli::RegisterCommand(50, &AddInfoCommand);
//
// `order` sorts the commands in `sysid --help` (the workflow order: info, simulate, identify…).
#ifndef SYSID_APPS_CLI_REGISTRY_HPP_
#define SYSID_APPS_CLI_REGISTRY_HPP_

#include <CLI/CLI.hpp>

namespace sysid::cli {

using CommandAdder = void (*)(CLI::App& app);

bool RegisterCommand(int order, CommandAdder adder);
/// Adds every registered subcommand to `app`, in order.
void AddRegisteredCommands(CLI::App& app);

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_REGISTRY_HPP_
