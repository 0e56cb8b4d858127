// FullReport of the fits by simulation: BriefReport plus every diagnostic (Ceres' pattern).
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "delay/parameter_names.hpp"
#include "sysid/delay.hpp"

namespace sysid {
namespace {

std::string Warnings(const std::vector<std::string>& warnings) {
  std::string s = fmt::format("  warnings: {}\n", warnings.size());
  for (const auto& w : warnings) s += "    " + w + "\n";
  return s;
}

}  // namespace

std::string DelayTuningResult::FullReport() const {
  std::string s = BriefReport();
  s += fmt::format("  model: a1p {:.7g}, a1n {:.7g}, a2p {:.7g}, a2n {:.7g}, a3 {:.7g}, tau {:.6g} s\n",
                   model.a1p, model.a1n, model.a2p, model.a2n, model.a3, model.tau_s);
  s += fmt::format("  samples compared per evaluation: {}\n", samples);
  s += Warnings(warnings);
  s += fmt::format("  cost curve: {} points (tau [s], cost [m^2/s^2])\n", curve.size());
  for (const auto& [tau, cost] : curve) s += fmt::format("    {:.6g} {:.6g}\n", tau, cost);
  return s;
}

std::string RefineResult::FullReport() const {
  std::string s = BriefReport();
  s += "  parameter  initial -> refined (relative standard error)\n";
  for (size_t k = 0; k < names.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    const std::string& n = names[k];
    const double before = internal::ParameterByName(initial, n);
    const double after = internal::ParameterByName(model, n);
    const double rel = i < std_error.size() ? std_error[i] / std::abs(after) : NAN;
    s += fmt::format("    {:<4} {:.7g} -> {:.7g} ({:.2g})\n", n, before, after, rel);
  }
  s += Warnings(warnings);
  return s;
}

}  // namespace sysid
