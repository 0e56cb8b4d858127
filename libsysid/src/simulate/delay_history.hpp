// The simulator's own dense history of v(t) for the delayed term v(t - tau).
//
// Each accepted CVODE step [t_{n-1}, t_n] is stored as its own interpolating polynomial (the
// Nordsieck/Taylor polynomial of order q that CVODE's error control certified for that step), so
// the delayed value keeps the integrator's accuracy at every order; a cubic Hermite fit between
// step ends would lose it at the long steps Adams takes (error ~ (a1 h)^4 / 384). Stuck stretches
// are exact zero pieces. Before t0 the history is a constant.
#ifndef SYSID_SRC_SIMULATE_DELAY_HISTORY_HPP_
#define SYSID_SRC_SIMULATE_DELAY_HISTORY_HPP_

#include <cstddef>
#include <limits>
#include <vector>

namespace sysid::internal {

class DelayHistory {
 public:
  /// v(t) = history_v for t < t0; v(t0) = v0 until the first piece is stored.
  DelayHistory(double t0_s, double history_v_mps, double v0_mps);

  /// Appends v(t) = sum_k c[k] ((t - t_ref) / h)^k on [end(), t_right]. Pieces are contiguous:
  /// the new one starts where the last one ended. Ignored when t_right <= end().
  void AppendPolynomial(double t_right, double t_ref, double h, const double* c, int order);
  /// Appends the constant v(t) = value on [end(), t_right].
  void AppendConstant(double t_right, double value);

  /// Reserves room for `pieces` pieces of average order 6 (avoids regrowth during a run).
  void Reserve(std::size_t pieces) {
    pieces_.reserve(pieces);
    coefficients_.reserve(7 * pieces);
  }

  /// Forgets the pieces that end before `s` (a run that never looks back further: the stepped
  /// plant, at t - tau), so that a long run's history stays bounded. Amortised O(1): it
  /// compacts only once the forgotten pieces outnumber the kept ones.
  void ForgetBefore(double s);

  /// Last time covered.
  double end() const { return end_; }
  /// v(s), right-continuous at piece boundaries; extrapolates the last piece past end() (only
  /// CVODE's initial-step probes and rounding ever look there).
  double Value(double s) const;

 private:
  struct Piece {
    double t_left, t_right, t_ref, inv_h;
    std::size_t offset;
    int order;
  };
  double t0_, history_v_, v0_, end_;
  std::vector<Piece> pieces_;
  std::vector<double> coefficients_;
  mutable std::size_t cursor_ = 0;  // lookups move forward in time: amortised O(1)
  // The last look-up: CVODE evaluates f at one time several times (fixed-point iterations),
  // then the roots at the same time, so most look-ups repeat the previous one exactly.
  // Appending a piece may change values (past end() the last piece is extrapolated): it resets.
  mutable double last_s_ = std::numeric_limits<double>::quiet_NaN();
  mutable double last_value_ = 0;
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_SIMULATE_DELAY_HISTORY_HPP_
