// Private argument checks of the signal module, phrased like the options' Validate() messages.
#ifndef SYSID_SRC_SIGNAL_CHECKS_HPP_
#define SYSID_SRC_SIGNAL_CHECKS_HPP_

#include <Eigen/Core>
#include <string>

namespace sysid::internal {

/// Throws OptionsError "`where`::dt_s = X s. Violated constraint: dt_s > 0 and finite" (`where`
/// is the options struct or the function the value was given to; its owner()).
void CheckSampleInterval(const char* where, double dt_s);
/// Throws OptionsError unless 0 < cutoff_hz < 0.5 / dt_s.
void CheckCutoff(const char* where, const char* field, double cutoff_hz, double dt_s);
/// Throws OptionsError unless 1 <= order <= kMaxButterworthOrder.
void CheckButterworthOrder(const char* where, const char* field, int order);
/// Throws OptionsError unless window is odd, >= 3, and 0 <= order < window.
void CheckSavitzkyGolay(const char* where, const char* window_field, int window,
                        const char* order_field, int order, int min_order);
/// Throws InputError "`where`: the signal has N samples; `why` needs at least M".
void CheckLength(const char* where, Eigen::Index n, Eigen::Index min_n, const std::string& why);
/// Throws InputError naming the first non-finite sample.
void CheckFinite(const char* where, const Eigen::VectorXd& y);

}  // namespace sysid::internal

#endif  // SYSID_SRC_SIGNAL_CHECKS_HPP_
