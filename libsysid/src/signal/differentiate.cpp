// Differentiate(): the three derivative methods behind one options struct.
#include <fmt/format.h>

#include "signal/checks.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

namespace sysid {

DerivativeMethod ParseDerivativeMethod(const std::string& name) {
  if (name == "central") return DerivativeMethod::kCentral;
  if (name == "butterworth") return DerivativeMethod::kButterworthCentral;
  if (name == "savgol") return DerivativeMethod::kSavitzkyGolay;
  throw OptionsError(fmt::format(
      "derivative method '{}' is unknown; expected one of: central, butterworth, savgol", name));
}

std::string ToString(DerivativeMethod method) {
  switch (method) {
    case DerivativeMethod::kCentral:
      return "central";
    case DerivativeMethod::kButterworthCentral:
      return "butterworth";
    case DerivativeMethod::kSavitzkyGolay:
      return "savgol";
  }
  SYSID_CHECK(false, "unknown DerivativeMethod value");
}

void DerivativeOptions::Validate(double dt_s) const {
  constexpr const char* kWhere = "DerivativeOptions";
  internal::CheckSampleInterval(kWhere, dt_s);
  switch (method) {
    case DerivativeMethod::kCentral:
      break;
    case DerivativeMethod::kButterworthCentral:
      internal::CheckCutoff(kWhere, "cutoff_hz", cutoff_hz, dt_s);
      internal::CheckButterworthOrder(kWhere, "butterworth_order", butterworth_order);
      break;
    case DerivativeMethod::kSavitzkyGolay:
      // Order >= 2: a straight-line fit has no acceleration.
      internal::CheckSavitzkyGolay("DerivativeOptions", "savgol_window", savgol_window,
                                 "savgol_order", savgol_order, 2);
      break;
  }
}

Derivatives Differentiate(const Eigen::VectorXd& x_m, double dt_s,
                          const DerivativeOptions& options) {
  options.Validate(dt_s);
  Derivatives d;
  switch (options.method) {
    case DerivativeMethod::kCentral:
      d.x_m = x_m;
      break;
    case DerivativeMethod::kButterworthCentral:
      d.x_m = ButterworthFiltFilt(x_m, dt_s, options.cutoff_hz, options.butterworth_order);
      break;
    case DerivativeMethod::kSavitzkyGolay:
      d.x_m = SavitzkyGolay(x_m, dt_s, options.savgol_window, options.savgol_order, 0);
      d.v_mps = SavitzkyGolay(x_m, dt_s, options.savgol_window, options.savgol_order, 1);
      d.a_mps2 = SavitzkyGolay(x_m, dt_s, options.savgol_window, options.savgol_order, 2);
      return d;
  }
  d.v_mps = CentralDifference(d.x_m, dt_s);
  d.a_mps2 = CentralDifference(d.v_mps, dt_s);
  return d;
}

}  // namespace sysid
