// FullReport of a training run: BriefReport plus every diagnostic.
#include <fmt/format.h>

#include <map>
#include <string>

#include "sysid/nn.hpp"

namespace sysid {

std::string NeuralTrainingResult::FullReport() const {
  std::string s = BriefReport() + "\n";
  s += fmt::format("  stopping rule: {}; kept restart {} after {} epochs\n", ToString(stop),
                   restart, epochs);
  s += fmt::format("  train MSE {:.6g}, validation MSE {:.6g}\n", train_mse, validation_mse);
  s += fmt::format("  warnings: {}\n", warnings.size());
  for (const auto& w : warnings) s += "    " + w + "\n";
  std::map<int, EpochRecord> last;  // restart -> its last epoch
  for (const auto& e : history) last[e.restart] = e;
  s += fmt::format("  restarts: {} (last epoch: train MSE, validation MSE, mu, gradient norm)\n",
                   last.size());
  for (const auto& [r, e] : last)
    s += fmt::format("    restart {} epoch {}: {:.6g} {:.6g} {:.3g} {:.3g}\n", r, e.epoch,
                     e.train_mse, e.validation_mse, e.mu, e.gradient_norm);
  return s;
}

}  // namespace sysid
