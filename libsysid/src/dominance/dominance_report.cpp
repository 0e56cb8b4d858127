// FullReport of a dominance analysis: BriefReport plus every term's statistics.
#include <fmt/format.h>

#include <string>

#include "sysid/dominance.hpp"

namespace sysid {

std::string DominanceResult::FullReport() const {
  std::string s = BriefReport();
  s += "  terms (rms, peak [m/s^2]; rms ratio, ratio bound, ratio max to the top entry):\n";
  for (const auto& t : terms)
    s += fmt::format("    {:<14} rms {:.4g} peak {:.4g} ratio {:.3g} bound {:.3g} max {:.3g}{}\n",
                     t.name, t.rms, t.peak, t.ratio_to_top, t.ratio_bound, t.ratio_max,
                     t.negligible ? " (negligible)" : "");
  s += "  variables by rms:\n";
  for (const auto& t : ranking)
    s += fmt::format("    {:<14} rms {:.4g} peak {:.4g} ratio {:.3g} bound {:.3g} max {:.3g}{}\n",
                     t.name, t.rms, t.peak, t.ratio_to_top, t.ratio_bound, t.ratio_max,
                     t.negligible ? " (negligible)" : "");
  return s;
}

}  // namespace sysid
