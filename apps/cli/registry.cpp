#include "cli/registry.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace sysid::cli {
namespace {
// Function-local static: safe to use from other translation units' static initialisers.
std::vector<std::pair<int, CommandAdder>>& Registry() {
  static std::vector<std::pair<int, CommandAdder>> registry;
  return registry;
}
}  // namespace

bool RegisterCommand(int order, CommandAdder adder) {
  Registry().emplace_back(order, adder);
  return true;
}

void AddRegisteredCommands(CLI::App& app) {
  auto commands = Registry();
  std::stable_sort(commands.begin(), commands.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [order, adder] : commands) adder(app);
}

}  // namespace sysid::cli
