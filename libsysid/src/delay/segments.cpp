#include "delay/segments.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <thread>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/input.hpp"
#include "sysid/signal.hpp"
#include "sysid/simulate.hpp"

namespace sysid {

void SegmentOptions::Validate() const {
  detection.Validate();
  if (!(rest_speed_mps > 0) || !std::isfinite(rest_speed_mps))
    internal::FailOption("SegmentOptions", "rest_speed_mps", rest_speed_mps,
                         "rest_speed_mps > 0 [m/s]");
}

namespace internal {
namespace {

// Same input pattern, start state and sample times relative to the start (to 1e-9 s).
bool SameExperiment(const SimSegment& a, const SimSegment& b) {
  if (a.t_out_s.size() != b.t_out_s.size() || a.u_knot_v != b.u_knot_v || a.v0_mps != b.v0_mps)
    return false;
  const double eps = 1e-9;
  for (size_t k = 0; k < a.u_knot_t_s.size(); ++k)
    if (std::abs((a.u_knot_t_s[k] - a.t0_s) - (b.u_knot_t_s[k] - b.t0_s)) > eps) return false;
  for (size_t k = 0; k < a.t_out_s.size(); ++k)
    if (std::abs((a.t_out_s[k] - a.t0_s) - (b.t_out_s[k] - b.t0_s)) > eps) return false;
  return true;
}

}  // namespace

std::vector<SimSegment> MakeSegments(const std::vector<MotionSignals>& motions,
                                     const SegmentOptions& options, const MotionOptions& motion) {
  options.Validate();
  std::vector<SimSegment> segments;
  Eigen::Index offset = 0;
  for (const MotionSignals& m : motions) {
    const Eigen::Index n = m.t_s.size();
    std::vector<Eigen::Index> cuts{0};
    for (const Pulse& p : DetectPulses(m.t_s, m.u_v, options.detection, m.source)) {
      const Eigen::Index k = p.first_row;
      if (k < 10) continue;
      if (m.v_mps.segment(k - 10, 10).cwiseAbs().mean() < options.rest_speed_mps) cuts.push_back(k);
    }
    cuts.push_back(n);
    for (size_t c = 0; c + 1 < cuts.size(); ++c) {
      const Eigen::Index a = cuts[c], b = cuts[c + 1];
      if (b - a < 2) continue;
      SimSegment s;
      s.source = m.source;
      s.t0_s = m.t_s[a];
      s.t_end_s = m.t_s[b - 1];
      s.t_out_s.assign(m.t_s.data() + a, m.t_s.data() + b);
      s.from_position = m.velocity_from.rfind("x", 0) == 0;
      s.derivative = motion.derivative;
      s.dt_s = m.dt_s;
      s.v_meas_mps = s.from_position
                         ? Differentiate(m.x_m.segment(a, b - a), m.dt_s, motion.derivative).v_mps
                         : Eigen::VectorXd(m.v_mps.segment(a, b - a));
      s.x0_m = m.x_m.size() ? m.x_m[a] : 0.0;
      // A cut is at rest by construction; the record's start is taken at rest unless its first
      // measured velocity says otherwise (an average would include the start's acceleration).
      const double v_start = m.v_mps[a];
      s.v0_mps = (a == 0 && std::abs(v_start) >= options.rest_speed_mps) ? v_start : 0.0;
      for (Eigen::Index k = a; k < b; ++k)
        if (k == a || m.u_v[k] != m.u_v[k - 1]) {
          s.u_knot_t_s.push_back(m.t_s[k]);
          s.u_knot_v.push_back(m.u_v[k]);
        }
      s.offset = offset;
      offset += b - a;
      for (size_t j = 0; options.reuse_identical_segments && j < segments.size() && s.twin_of < 0;
           ++j)
        if (SameExperiment(segments[j], s)) s.twin_of = static_cast<int>(j);
      segments.push_back(std::move(s));
    }
  }
  return segments;
}

Eigen::Index SegmentSamples(const std::vector<SimSegment>& segments) {
  Eigen::Index n = 0;
  for (const auto& s : segments) n += static_cast<Eigen::Index>(s.t_out_s.size());
  return n;
}

bool SegmentResiduals(const FrictionModel& model_in, const std::vector<SimSegment>& segments,
                      const SimulationSettings& settings, Eigen::VectorXd* residuals,
                      std::string* failure, std::atomic<long>* counter) {
  FrictionModel model = model_in;
  if (model.tau_s < kMinSimulatedDelay_s) model.tau_s = 0;
  residuals->resize(SegmentSamples(segments));
  const size_t n = segments.size();
  std::vector<std::string> errors(n);
  std::vector<std::exception_ptr> exceptions(n);
  std::vector<size_t> own;  // segments simulated themselves
  for (size_t i = 0; i < n; ++i)
    if (segments[i].twin_of < 0) own.push_back(i);
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t j = next++; j < own.size(); j = next++) {
      const size_t i = own[j];
      const SimSegment& s = segments[i];
      try {
        PiecewiseConstantInput input(s.u_knot_t_s, s.u_knot_v);
        SimulationOptions o;
        o.t0_s = s.t0_s;
        o.t_end_s = s.t_end_s;
        o.output_times_s = s.t_out_s;
        o.x0_m = s.x0_m;
        o.v0_mps = s.v0_mps;
        o.history_v_mps = s.v0_mps;
        o.rtol = settings.rtol;
        o.atol = settings.atol;
        const SimulationResult r = Simulate(model, input, o);
        if (counter) ++*counter;
        const auto len = static_cast<Eigen::Index>(s.t_out_s.size());
        if (!r.summary.IsSolutionUsable() || r.trajectory.v_mps.size() != len) {
          errors[i] = fmt::format(
              "{}: simulation of t = {:.6g} .. {:.6g} s failed at t = {:.6g} "
              "s: {}",
              s.source, s.t0_s, s.t_end_s, r.summary.failure_time_s, r.summary.message);
          continue;
        }
        residuals->segment(s.offset, len) =
            s.from_position ? Differentiate(r.trajectory.x_m, s.dt_s, s.derivative).v_mps
                            : r.trajectory.v_mps;
      } catch (...) {
        exceptions[i] = std::current_exception();
      }
    }
  };
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const size_t threads = std::min<size_t>(
      own.size(), settings.threads > 0 ? static_cast<size_t>(settings.threads) : hw);
  std::vector<std::thread> pool;
  for (size_t t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  for (const auto& e : exceptions)
    if (e) std::rethrow_exception(e);
  for (const auto& e : errors)
    if (!e.empty()) {
      *failure = e;
      return false;
    }
  // The residual vector holds v_sim so far: copy the twins' simulations, then subtract.
  for (const SimSegment& s : segments) {
    const auto len = static_cast<Eigen::Index>(s.t_out_s.size());
    if (s.twin_of >= 0)
      residuals->segment(s.offset, len) =
          residuals->segment(segments[static_cast<size_t>(s.twin_of)].offset, len);
  }
  for (const SimSegment& s : segments)
    residuals->segment(s.offset, static_cast<Eigen::Index>(s.t_out_s.size())) -= s.v_meas_mps;
  return true;
}

}  // namespace internal
}  // namespace sysid
