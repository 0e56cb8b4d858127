// Private: recordings cut into pieces that are simulated independently and in parallel, and
// the velocity error of a model on them (delay tuning and output-error refinement).
#ifndef SYSID_SRC_DELAY_SEGMENTS_HPP_
#define SYSID_SRC_DELAY_SEGMENTS_HPP_

#include <Eigen/Core>
#include <atomic>
#include <string>
#include <vector>

#include "sysid/delay.hpp"
#include "sysid/identify.hpp"
#include "sysid/model.hpp"

namespace sysid::internal {

/// Delays below this are simulated as 0 [s]: the simulator's step is bounded by tau, so its
/// cost grows as 1/tau, while 50 us is 1/20 of a 1 kHz sample and below any delay that
/// recordings can resolve.
inline constexpr double kMinSimulatedDelay_s = 5e-5;

struct SimSegment {
  std::string source;
  double t0_s = 0;
  double t_end_s = 0;
  std::vector<double> t_out_s;     ///< sample times compared
  std::vector<double> u_knot_t_s;  ///< zero-order-hold knots where u changes
  std::vector<double> u_knot_v;
  Eigen::VectorXd v_meas_mps;  ///< measured velocity at t_out_s
  /// When the measured velocity comes from position, the simulated position goes through the
  /// same derivative filter (on the same piece), so filter lag and smoothing cancel.
  bool from_position = false;
  DerivativeOptions derivative;
  double dt_s = 0;
  double x0_m = 0;
  double v0_mps = 0;
  Eigen::Index offset = 0;  ///< first index in the concatenated residual vector
  /// Index of an earlier segment with the same input, start state and relative sample times
  /// (repeated pulses of a pulse train): the model is time-invariant, so its simulation is
  /// reused. -1 when the segment is simulated itself.
  int twin_of = -1;
};

/// Cuts every recording at pulse starts where the stage rests.
std::vector<SimSegment> MakeSegments(const std::vector<MotionSignals>& motions,
                                     const SegmentOptions& options, const MotionOptions& motion);

/// Total number of compared samples.
Eigen::Index SegmentSamples(const std::vector<SimSegment>& segments);

struct SimulationSettings {
  double rtol = 1e-6;
  double atol = 1e-9;
  int threads = 0;
};

/// Fills `residuals` (v_sim - v_meas, concatenated) for `model`. Returns false and the reason
/// when a simulation fails. Simulations run in parallel; `counter` counts them.
bool SegmentResiduals(const FrictionModel& model, const std::vector<SimSegment>& segments,
                      const SimulationSettings& settings, Eigen::VectorXd* residuals,
                      std::string* failure, std::atomic<long>* counter);

}  // namespace sysid::internal

#endif  // SYSID_SRC_DELAY_SEGMENTS_HPP_
