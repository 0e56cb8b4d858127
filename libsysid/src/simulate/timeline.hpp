// The time bookkeeping of one simulation: where CVODE must stop (StopTimes) and the sign of v
// over the past (SignTimeline, which picks the viscous branch a1 from v(t - tau)).
#ifndef SYSID_SRC_SIMULATE_TIMELINE_HPP_
#define SYSID_SRC_SIMULATE_TIMELINE_HPP_

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <queue>
#include <vector>

#include "sysid/input.hpp"
#include "sysid/simulate.hpp"

namespace sysid::internal {

/// Times closer than this are one instant: CVODE locates roots to ~100 ulp of t, far below it.
inline double TimeEps(double t) { return 1e-12 * std::max(1.0, std::abs(t)); }

/// The times where CVODE must stop. Hard stops (input edges, t_end) are jumps of u: CVODE
/// restarts there. Soft stops (breakpoints t_e + k tau) are kinks of f or of its derivatives:
/// landing a step exactly on them is enough, CVODE's error control handles the rest.
class StopTimes {
 public:
  /// Hard: the input's edges and t_end. Soft: every source of a v' jump known in advance (the
  /// edges and t0) shifted by k tau, k = 1..breakpoint_order; events add theirs as they occur.
  StopTimes(const InputSignal& input, const SimulationOptions& o, double tau)
      : tau_(tau), t_end_(o.t_end_s), order_(o.breakpoint_order) {
    hard_ = input.Edges(o.t0_s, t_end_);
    hard_.push_back(t_end_);
    if (tau > 0) {
      std::vector<double> sources = hard_;
      sources.back() = o.t0_s;
      for (double ts : sources)
        for (int k = 1; k <= order_; ++k)
          if (ts + k * tau < t_end_) soft_.push_back(ts + k * tau);
    }
    std::sort(hard_.begin(), hard_.end());
    std::sort(soft_.begin(), soft_.end());
  }

  /// A jump of v' at te (an event) reappears in v'' at te + tau, v''' at te + 2 tau, ...
  void AddBreakpoints(double te) {
    if (tau_ > 0)
      for (int k = 1; k <= order_; ++k)
        if (te + k * tau_ < t_end_) dynamic_.push(te + k * tau_);
  }
  /// A hard stop at t >= every time reached so far (an input edge decided on the way: the
  /// stepped plant's next sample).
  void AddHardStop(double t) {
    hard_.insert(std::upper_bound(hard_.begin() + static_cast<std::ptrdiff_t>(next_hard_),
                                  hard_.end(), t),
                 t);
  }
  bool IsHard(double t) const { return std::binary_search(hard_.begin(), hard_.end(), t); }
  /// Smallest stop time > t (+inf when none is left).
  double Next(double t) {
    while (next_hard_ < hard_.size() && hard_[next_hard_] <= t) ++next_hard_;
    while (next_soft_ < soft_.size() && soft_[next_soft_] <= t) ++next_soft_;
    while (!dynamic_.empty() && dynamic_.top() <= t) dynamic_.pop();
    double next = std::numeric_limits<double>::infinity();
    if (next_hard_ < hard_.size()) next = hard_[next_hard_];
    if (next_soft_ < soft_.size()) next = std::min(next, soft_[next_soft_]);
    if (!dynamic_.empty()) next = std::min(next, dynamic_.top());
    return next;
  }

 private:
  double tau_, t_end_;
  int order_;
  std::vector<double> hard_, soft_;
  std::size_t next_hard_ = 0, next_soft_ = 0;
  std::priority_queue<double, std::vector<double>, std::greater<>> dynamic_;
};

/// Sign of v on the right of each time: the history's sign before t0, then one entry per mode
/// change. The branch of a1 on a segment is the sign of v(t - tau) just right of its start.
class SignTimeline {
 public:
  explicit SignTimeline(int history_sign)
      : t_{-std::numeric_limits<double>::infinity()}, sign_{history_sign} {}
  void Set(double t, int sign) {
    if (sign == sign_.back()) return;
    t_.push_back(t);
    sign_.push_back(sign);
  }
  /// Sign of v just right of s (entries within TimeEps of s count as reached).
  int RightOf(double s) const {
    const auto it = std::upper_bound(t_.begin(), t_.end(), s + TimeEps(s));
    return sign_[static_cast<std::size_t>(it - t_.begin()) - 1];
  }
  /// True when v = 0 throughout [a, b].
  bool ZeroOn(double a, double b) const {
    const auto first = std::upper_bound(t_.begin(), t_.end(), a + TimeEps(a));
    const auto last = std::upper_bound(t_.begin(), t_.end(), b);
    if (sign_[static_cast<std::size_t>(first - t_.begin()) - 1] != 0) return false;
    for (auto it = first; it != last; ++it)
      if (sign_[static_cast<std::size_t>(it - t_.begin())] != 0) return false;
    return true;
  }

 private:
  std::vector<double> t_;
  std::vector<int> sign_;
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_SIMULATE_TIMELINE_HPP_
