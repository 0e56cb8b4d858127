#include "simulate/delay_history.hpp"

#include <cstddef>

namespace sysid::internal {

DelayHistory::DelayHistory(double t0_s, double history_v_mps, double v0_mps)
    : t0_(t0_s), history_v_(history_v_mps), v0_(v0_mps), end_(t0_s) {}

void DelayHistory::AppendPolynomial(double t_right, double t_ref, double h, const double* c,
                                    int order) {
  if (!(t_right > end_)) return;
  pieces_.push_back({end_, t_right, t_ref, 1.0 / h, coefficients_.size(), order});
  coefficients_.insert(coefficients_.end(), c, c + order + 1);
  end_ = t_right;
  last_s_ = std::numeric_limits<double>::quiet_NaN();
}

void DelayHistory::AppendConstant(double t_right, double value) {
  AppendPolynomial(t_right, t_right, 1.0, &value, 0);
}

void DelayHistory::ForgetBefore(double s) {
  std::size_t first = 0;  // the first piece to keep
  while (first + 1 < pieces_.size() && pieces_[first].t_right < s) ++first;
  if (first < 1024 || 2 * first < pieces_.size()) return;
  const std::size_t offset = pieces_[first].offset;
  coefficients_.erase(coefficients_.begin(),
                      coefficients_.begin() + static_cast<std::ptrdiff_t>(offset));
  pieces_.erase(pieces_.begin(), pieces_.begin() + static_cast<std::ptrdiff_t>(first));
  for (Piece& p : pieces_) p.offset -= offset;
  cursor_ = cursor_ > first ? cursor_ - first : 0;
}

double DelayHistory::Value(double s) const {
  if (s < t0_) return history_v_;
  if (pieces_.empty()) return v0_;
  if (s == last_s_) return last_value_;
  std::size_t i = cursor_ < pieces_.size() ? cursor_ : pieces_.size() - 1;
  while (i > 0 && s < pieces_[i].t_left) --i;
  while (i + 1 < pieces_.size() && s >= pieces_[i].t_right) ++i;
  cursor_ = i;
  const Piece& p = pieces_[i];
  const double theta = (s - p.t_ref) * p.inv_h;
  const double* c = coefficients_.data() + p.offset;
  double value = c[p.order];
  for (int k = p.order - 1; k >= 0; --k) value = value * theta + c[k];
  last_s_ = s;
  last_value_ = value;
  return value;
}

}  // namespace sysid::internal
