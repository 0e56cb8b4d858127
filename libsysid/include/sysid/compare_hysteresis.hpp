// The hysteresis models behind one door: fit any kind by name, read any model file back
// (`sysid hysteresis`, the benchmark scripts, Python). Kinds: "pi", "gpi", "rdpi"
// (sysid/hysteresis.hpp), "nn-operators" (sysid/nn_operators.hpp), "bouc-wen" and
// "bouc-wen-piezo" (sysid/hysteresis_bouc_wen.hpp).
#ifndef SYSID_COMPARE_HYSTERESIS_HPP_
#define SYSID_COMPARE_HYSTERESIS_HPP_

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sysid/hysteresis.hpp"
#include "sysid/hysteresis_bouc_wen.hpp"
#include "sysid/hysteresis_model.hpp"
#include "sysid/io.hpp"
#include "sysid/nn_operators.hpp"

namespace sysid {

/// Every kind FitHysteresis knows, in the CLI's order.
const std::vector<std::string>& HysteresisKinds();

struct HysteresisFitOptions {
  /// Play operators of the PI family and of the operator-input network (1..kMaxPlayOperators;
  /// 0 allowed for nn-operators: the static dominant-variable network).
  int operators = 10;
  PiFitOptions pi;                  ///< pi, gpi, rdpi (its form and operators are set by kind)
  OperatorNetworkOptions network;   ///< nn-operators (its operators are set from `operators`)
  BoucWenFitOptions bouc_wen;       ///< bouc-wen, bouc-wen-piezo (operators unused)
  /// Throws OptionsError naming the field ("operators"; for nn-operators also `network`'s
  /// fields: "hidden", "max_epochs") and the rule.
  void Validate(const std::string& kind) const;
};

/// Fits a model of `kind` to recordings (columns t [s], u [V], x [m]). Throws OptionsError for
/// an unknown kind or bad options, InputError for unusable recordings.
std::unique_ptr<HysteresisModel> FitHysteresis(const std::string& kind,
                                               const std::vector<Recording>& recordings,
                                               const HysteresisFitOptions& options = {},
                                               HysteresisFitSummary* summary = nullptr);

/// Reads a hysteresis model file of any kind ({"kind": ...}); InputError "FILE:LINE:COL: ..."
/// for anything invalid.
std::unique_ptr<HysteresisModel> HysteresisModelFromJson(std::string_view text,
                                                         const std::string& source);
std::unique_ptr<HysteresisModel> ReadHysteresisModel(const std::string& path);

/// The summary as JSON {kind, samples, fit_time_s, training_rms_m, converged, message,
/// parameters: [{name, unit, value, std_error}]} (NaN as null).
std::string HysteresisFitSummaryJson(const HysteresisFitSummary& summary,
                                     const HysteresisModel& model, int indent = 2);

}  // namespace sysid

#endif  // SYSID_COMPARE_HYSTERESIS_HPP_
