#include "cli/fit_fraction_flag.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iostream>

#include "cli/common.hpp"
#include "sysid/error.hpp"

namespace sysid::cli {

void FitFractionFlag::Add(CLI::App* cmd) {
  cmd->add_option("--fit-fraction", fraction,
                  "fit on the first fraction F of each recording's duration, 0 < F <= 1; the "
                  "rest is not used by the fit (stderr names it: score the model on it with "
                  "--t-start)")
      ->type_name("F")
      ->capture_default_str();
}

std::vector<Recording> FitFractionFlag::FitPart(std::vector<Recording> recordings,
                                                const std::string& command) const {
  if (!(fraction > 0 && fraction <= 1))
    throw OptionsError(fmt::format("--fit-fraction {}: expected 0 < F <= 1", fraction),
                       "--fit-fraction");
  if (fraction == 1) return recordings;
  for (auto& rec : recordings) {
    const auto t = rec.column("t");
    const double first = t[0], last = t[t.size() - 1];
    const double end = first + fraction * (last - first);
    rec = CropRecording(rec, first, end);
    std::cerr << fmt::format(
        "sysid {}: fitting on t = {:.6g} .. {:.6g} s of {} (the first {:g} %, {} samples); the "
        "rest, t > {:.6g} s, is not used: score the model on it with --t-start {:.6g}\n",
        command, first, end, rec.source, 100 * fraction, rec.rows(), end, end);
  }
  return recordings;
}

}  // namespace sysid::cli
