// The virtual stage's plant integrated with SUNDIALS CVODE (BDF: the LuGre bristle makes the
// actuator-delay system stiff, eigenvalues up to s0 |v| / g ~ 1e4 1/s while sliding).
//
// The velocity-source model's Karnopp rail is a hybrid system: sliding in direction d = +-1
// (v' = p (v_f(u_d) - v) - d g(|v|)) or stuck (v = 0, v' = 0). CVODE's root finding locates the
// switches exactly: while sliding the root function is v (the stage reaches rest: it sticks
// when |p v_f| <= Fs, else reverses), while stuck it is |p v_f(u_d)| - Fs (breakaway). Each
// switch restarts the integrator, so every integrated piece has a smooth right-hand side.
//
// With frictional memory (rail.memory_time_s = T_m > 0) the third state holds the lagged slip
// speed s, T_m s' = |v| - s, and the sliding friction is g(s) instead of g(|v|): friction that
// lags the velocity (Hess & Soom), a rate-dependent velocity-force loop. While sliding |v| is
// d v, so the right-hand side stays smooth on every integrated piece.
//
// The DAC output is piecewise constant and the transport delay shifts its edges by a fraction
// of a sample, so within each sample the driver input has at most one edge, at t_k + f Ts. The
// integration is restarted (CVodeReInit) at every edge where the input changes: the right-hand
// side is then smooth on each integrated piece, which keeps BDF at full order and accuracy.
//
// Drive hysteresis (velocity source, drive.hysteresis): the piezoceramic's rate-dependent,
// asymmetric hysteresis acts on the clipped DAC value once per control sample, before the
// envelope lag (DriveHysteresis in stage.hpp). On a held input the play operators change only
// at the DAC's edges, so the per-sample update is exact and the lag's input stays piecewise
// constant: the integrated pieces keep their smooth right-hand side and no new root is needed.
// The operator is causal per sample, so a transport delay delays its output as it would its
// input: the history holds the driven values.
//
// Creep (velocity source, drive.creep): the ceramic's relaxation with T_c (DriveCreep in
// stage.hpp). Its input is held per sample, so the relaxation has a closed form on each held
// piece and the lag's input is (1 - k_v) u_pi + q + (z_a - q) e^(-(t - t_a) / T_c), anchored
// where the relaxing target q last changed: the right-hand side stays smooth on the piece (no
// new state, no root), and a held command keeps the same anchor, so the integrator is not
// restarted while the creep settles (a per-sample held u_h would restart it every sample of
// every plateau).
//
// Work per sample is bounded (integrator.max_steps_per_sample: CVODE steps plus switches), so a
// stage that cannot be integrated ends with NumericalError naming the time and the state
// instead of running on.
// Long file: the hybrid plant's modes, roots and restarts share one CVODE state; split, each
// part would reach into the others' internals.
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/cvode_solver.hpp"
#include "core/option_rule.hpp"
#include "core/portable_random.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/stage.hpp"

namespace sysid {
namespace {

enum : int { kX = 0, kV = 1, kZ = 2, kW = 3, kStates = 4 };

// The driver's input on a piece [V]: target + relax e^(-(t - from_s) / T_c); relax = 0
// without creep (then exactly target, as before creep existed).
struct DriveInput {
  double target = 0;  // [V] the value it relaxes to
  double relax = 0;   // [V] the part still relaxing at from_s
  double from_s = 0;  // [s] the anchor t_a on the stage's clock (after the transport delay)
  double At(double t, double time_constant_s) const {
    return relax == 0 ? target : target + relax * std::exp(-(t - from_s) / time_constant_s);
  }
  bool operator!=(const DriveInput& o) const {
    return target != o.target || relax != o.relax || from_s != o.from_s;
  }
};

std::string Num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace

class VirtualStage::Impl {
 public:
  Impl(const StageParameters& p, std::uint64_t seed) : p_(p), noise_(seed) {
    p_.Validate();
    ts_ = 1.0 / p_.rig.sample_rate_hz;
    const double d = p_.driver.transport_delay_s / ts_;
    delay_samples_ = static_cast<long>(std::floor(d + 1e-9));
    delay_fraction_ = d - static_cast<double>(delay_samples_);
    if (delay_fraction_ < 1e-9) delay_fraction_ = 0;
    history_.assign(static_cast<size_t>(delay_samples_) + 2, DriveInput{});
    dac_step_ = 2.0 * p_.rig.dac_range_v / std::ldexp(1.0, p_.rig.dac_bits);
    const double inv_q = 1.0 / p_.rig.encoder_resolution_m;
    // Readings as n / (1/q) when 1/q is an integer: the decimal text of the reading is then
    // short ("0.0123456"), which keeps the bundled CSV files small.
    encoder_divisor_ = std::abs(inv_q - std::round(inv_q)) < 1e-9 * inv_q ? std::round(inv_q) : 0;

    vs_ = std::get_if<VelocitySourcePlant>(&p_.plant);
    ad_ = std::get_if<ActuatorDelayPlant>(&p_.plant);
    if (vs_) {
      hysteresis_ = vs_->hysteresis;
      play_.assign(hysteresis_.thresholds_v.size(), 0.0);
      rate_gain_ = hysteresis_.rate_time_constant_s > 0
                       ? -std::expm1(-ts_ / hysteresis_.rate_time_constant_s)
                       : 1.0;
      rate_limit_ = hysteresis_.SaturationRate();
      creep_time_constant_s_ = vs_->creep.time_constant_s;
    }
    const std::array<double, kStates> y0{p_.rig.initial_position_m, 0.0, 0.0, 0.0};
    cv_.emplace(kStates, internal::CvodeSolver::Method::kBdf, &Impl::Rhs, this, 0.0, y0.data(),
                "virtual stage",
                "try a larger integrator.relative_tolerance or a smaller "
                "friction.bristle_stiffness_per_s2");
    std::array<double, kStates> atol{};
    atol[kX] = p_.integrator.position_tolerance_m;
    atol[kV] = p_.integrator.position_tolerance_m / ts_;
    atol[kZ] =
        vs_ ? p_.integrator.position_tolerance_m / ts_ : 0.1 * p_.integrator.position_tolerance_m;
    atol[kW] = p_.integrator.position_tolerance_m / ts_;
    cv_->SetTolerances(p_.integrator.relative_tolerance, atol.data());
    cv_->SetJacobian(&Impl::Jacobian);
    // One CVode call never takes more than the whole sample's budget (CV_TOO_MUCH_WORK then
    // reads as the budget's error, WorkExceeded).
    cv_->SetMaxNumSteps(p_.integrator.max_steps_per_sample);
    EnableRoots(true);
    reading_ = Measure();
  }

  double Dac(double u) const {
    if (!std::isfinite(u))
      internal::FailOption("VirtualStage::Step", "u_command_v", Num(u), "u_command_v is finite");
    const double levels = std::ldexp(1.0, p_.rig.dac_bits);
    const double code =
        std::clamp(std::round((u + p_.rig.dac_range_v) / dac_step_), 0.0, levels - 1);
    return code * dac_step_ - p_.rig.dac_range_v;
  }

  // Driver input after clipping, dead zone and the static map, for a DAC value u (velocity
  // source: after clipping and the ceramic's hysteresis; its dead zone acts on the lagged
  // voltage through v_f). Called once per sample, in order: the hysteresis and the creep have
  // state.
  DriveInput Drive(double u) {
    const double s = std::clamp(u, -p_.driver.saturation_v, p_.driver.saturation_v);
    if (vs_) {
      const double pi = hysteresis_.enabled() ? Hysteresis(s) : s;
      return vs_->creep.enabled() ? Creep(s, pi) : DriveInput{pi, 0, 0};
    }
    if (std::abs(s) <= ad_->dead_zone_v) return {};
    return {ad_->DriveMap(s > 0 ? s - ad_->dead_zone_v : s + ad_->dead_zone_v), 0, 0};
  }

  // DriveCreep for the clipped command s and the hysteresis' output pi: z relaxes to
  // q = k_v pi + k_l (s - pi), u_h = (1 - k_v) pi + z. A new anchor where q changes (z there
  // from the old anchor's closed form), the old one while q is held.
  DriveInput Creep(double s, double pi) {
    const DriveCreep& c = vs_->creep;
    const double t = static_cast<double>(k_) * ts_;
    const double q = c.voltage_share * pi + c.loop_share * (s - pi);
    if (q != creep_target_) {
      creep_z_ = creep_target_ +
                 (creep_z_ - creep_target_) * std::exp(-(t - creep_from_) / c.time_constant_s);
      creep_target_ = q;
      creep_from_ = t;
    }
    return {(1 - c.voltage_share) * pi + q, creep_z_ - q,
            creep_from_ + p_.driver.transport_delay_s};
  }

  // u_h of DriveHysteresis for the clipped command s: the play operators' states and the
  // filtered rate advance by one sample.
  double Hysteresis(double s) {
    const DriveHysteresis& h = hysteresis_;
    rate_ += rate_gain_ * ((s - last_input_) / ts_ - rate_);
    last_input_ = s;
    const double rho = std::min(std::abs(rate_), rate_limit_);
    double out = s;
    for (size_t i = 0; i < play_.size(); ++i) {
      const double r = h.thresholds_v[i];
      play_[i] = PlayStep(s - h.asymmetry * r, r, play_[i]);
      out -= (h.weights[i] + h.rate_weights_s_per_v[i] * rho) * (s - play_[i]);
    }
    return out;
  }

  double Step(double u_command) {
    const double u = Dac(u_command);
    // history_[j] = driven value of sample k - j after the shift: [0] is this sample.
    std::rotate(history_.rbegin(), history_.rbegin() + 1, history_.rend());
    history_[0] = Drive(u);
    const double t0 = static_cast<double>(k_) * ts_;
    const double t1 = static_cast<double>(k_ + 1) * ts_;
    sample_start_steps_ = cv_->Counters().steps;
    sample_switches_ = 0;
    sample_u_ = u;
    const DriveInput now = history_[static_cast<size_t>(delay_samples_)];
    if (delay_fraction_ > 0) {
      // The delayed input is the older value until t_k + f Ts, then the newer one.
      const DriveInput before = history_[static_cast<size_t>(delay_samples_) + 1];
      Advance(t0 + delay_fraction_ * ts_, before);
      Advance(t1, now);
    } else {
      Advance(t1, now);
    }
    ++k_;
    const double v = cv_->state()[kV];
    if (std::abs(v) > p_.rig.max_velocity_mps && !status_.velocity_limit_exceeded) {
      status_.velocity_limit_exceeded = true;
      status_.first_velocity_exceed_s = time_s();
    }
    reading_ = Measure();
    return reading_;
  }

  double time_s() const { return static_cast<double>(k_) * ts_; }

  StageState State() const {
    const double* y = cv_->state();
    const bool memory = vs_ && vs_->rail.memory_time_s > 0;
    return {y[kX], y[kV], vs_ ? 0.0 : y[kZ], y[kW], vs_ && (stuck_ || stop_ != 0),
            memory ? y[kZ] : (vs_ ? std::abs(y[kV]) : 0.0)};
  }

  StageStatus Status() const {
    StageStatus s = status_;
    s.steps = cv_->Counters().steps;
    return s;
  }

  const StageParameters& parameters() const { return p_; }
  double reading() const { return reading_; }
  long sample_index() const { return k_; }

 private:
  // Integrates to `t_end` with driver input `drive` (after dead zone and map).
  void Advance(double t_end, const DriveInput& drive) {
    double* y = cv_->state();
    const double pull = vs_ ? vs_->NoLoadSpeed(y[kW]) : y[kW];
    if (stop_ != 0 && pull * stop_ < 0) {
      // The drive pulls away from the end stop: free the stage again.
      stop_ = 0;
      stuck_ = true;
      Restart();
      EnableRoots(true);
    }
    if (drive != drive_) {
      drive_ = drive;
      Restart();
    }
    if (vs_ && stop_ == 0 && stuck_ && Breakaway(y[kW]) > 0) BreakAway();
    cv_->SetStopTime(t_end);
    while (t_ < t_end) {
      const int flag = cv_->Advance(t_end, &t_, CV_NORMAL);
      if (flag == CV_TOO_MUCH_WORK) WorkExceeded();
      int which[3] = {0, 0, 0};
      if (flag == CV_ROOT_RETURN) {
        cv_->GetRootInfo(which);
        ++sample_switches_;
        if (cv_->Counters().steps - sample_start_steps_ + sample_switches_ >
            p_.integrator.max_steps_per_sample)
          WorkExceeded();
      }
      if (flag == CV_ROOT_RETURN && vs_ && which[0] == 0 && which[1] == 0) {
        // A stick-slip switch of the rail.
        if (stuck_) {
          // Only a rising crossing of the breakaway margin starts the stage; a falling one
          // (it stuck with the margin just above 0, below) leaves it at rest.
          if (which[2] > 0) BreakAway();
        } else {
          y[kV] = 0;
          const int pull = vs_->NoLoadSpeed(y[kW]) > 0 ? 1 : -1;
          if (Breakaway(y[kW]) <= 0 || pull == direction_) {
            // At rest. A drive that pulls on in the sliding direction with |p v_f| > Fs >= g
            // cannot bring the stage to rest (v' > 0 at v = 0): it reaches v = 0 only where the
            // margin is within rounding of 0 and falling. Sliding on from there found the same
            // root at the same instant again, forever (a hang: 10 kHz loop, 0.5 Hz profile,
            // t = 1.1308 s, margin 7e-5 m/s^2); it sticks, and starts again when the margin
            // rises through 0 or is positive at the next sample's start.
            stuck_ = true;
          } else {
            direction_ = pull;
          }
          Restart();
        }
        cv_->SetStopTime(t_end);
      } else if (flag == CV_ROOT_RETURN) {
        // At an end stop: the stage stops dead and stays until the drive reverses.
        stop_ = y[kX] >= p_.rig.travel_max_m ? 1 : -1;
        y[kX] = stop_ > 0 ? p_.rig.travel_max_m : p_.rig.travel_min_m;
        y[kV] = 0;
        if (!status_.travel_limit_hit) {
          status_.travel_limit_hit = true;
          status_.first_travel_hit_s = t_;
        }
        Restart();
        EnableRoots(false);
        cv_->SetStopTime(t_end);
      } else if (flag < 0) {
        cv_->Throw(flag, "CVode");
      }
    }
  }

  // Velocity source: |p v_f(u_d)| - Fs, > 0 when the fingertips' stall force beats the rail's
  // static friction.
  double Breakaway(double w) const {
    return std::abs(vs_->motor.Thrust(vs_->motor.pole_per_s * vs_->NoLoadSpeed(w))) -
           vs_->rail.static_mps2;
  }

  // The sample needed more than its work budget: the stage cannot be integrated here.
  [[noreturn]] void WorkExceeded() const {
    const double* y = cv_->state();
    std::string state = "x = " + Num(y[kX]) + " m, v = " + Num(y[kV]) + " m/s, " +
                        (vs_ ? "u_d" : "w") + " = " + Num(y[kW]) + " V";
    if (vs_) {
      state += ", " + std::string(stop_ != 0 ? "at an end stop"
                                   : stuck_   ? "stuck"
                                              : (direction_ > 0 ? "sliding forward"
                                                                : "sliding backward"));
      if (vs_->rail.memory_time_s > 0) state += ", slip memory s = " + Num(y[kZ]) + " m/s";
    } else {
      state += ", bristle z = " + Num(y[kZ]) + " m";
    }
    throw NumericalError(
        "virtual stage: the integrator's work in the sample from t = " + Num(time_s()) +
        " s exceeded integrator.max_steps_per_sample = " +
        std::to_string(p_.integrator.max_steps_per_sample) + " (" +
        std::to_string(cv_->Counters().steps - sample_start_steps_) + " CVODE steps, " +
        std::to_string(sample_switches_) + " switches; reached t = " + Num(t_) +
        " s); state: " + state + ", DAC u = " + Num(sample_u_) +
        " V; the stage cannot be integrated at this rate: check its parameters, or try a "
        "larger integrator.relative_tolerance or integrator.position_tolerance_m");
  }

  void BreakAway() {
    stuck_ = false;
    direction_ = vs_->NoLoadSpeed(cv_->state()[kW]) > 0 ? 1 : -1;
    cv_->state()[kV] = 0;
    Restart();
  }

  void Restart() {
    double h = 0;
    CVodeGetLastStep(cv_->mem(), &h);
    cv_->ReInit(t_);
    // Start from the last successful step size instead of CVODE's cautious estimate.
    if (h > 0) cv_->SetInitStep(std::min(h, ts_));
    ++status_.reinitialisations;
  }

  void EnableRoots(bool on) { cv_->SetRoots(on ? (vs_ ? 3 : 2) : 0, &Impl::Roots); }

  double Measure() {
    const double x = cv_->state()[kX] + p_.rig.position_noise_m * noise_.IrwinHallGaussian();
    if (encoder_divisor_ > 0) return std::round(x * encoder_divisor_) / encoder_divisor_;
    return std::round(x / p_.rig.encoder_resolution_m) * p_.rig.encoder_resolution_m;
  }

  const FrictionBranch& Branch(double v) const { return v < 0 ? ad_->backward : ad_->forward; }

  static int Rhs(double t, N_Vector yv, N_Vector ydot, void* data) {
    const Impl& s = *static_cast<const Impl*>(data);
    const double* y = N_VGetArrayPointer(yv);
    double* d = N_VGetArrayPointer(ydot);
    d[kW] = (s.drive_.At(t, s.creep_time_constant_s_) - y[kW]) / s.p_.driver.lag_time_constant_s;
    const double tm = s.vs_ ? s.vs_->rail.memory_time_s : 0.0;
    if (s.stop_ != 0 || (s.vs_ && s.stuck_)) {
      d[kX] = d[kV] = 0;
      d[kZ] = tm > 0 ? -y[kZ] / tm : 0.0;  // at rest the memory fades
      return 0;
    }
    const double v = y[kV];
    if (s.vs_) {
      const double p = s.vs_->motor.pole_per_s;
      const double slip = tm > 0 ? y[kZ] : std::abs(v);
      d[kX] = v;
      d[kV] = s.vs_->motor.Thrust(p * (s.vs_->NoLoadSpeed(y[kW]) - v)) -
              s.direction_ * s.vs_->rail.Sliding(slip);
      d[kZ] = tm > 0 ? (s.direction_ * v - y[kZ]) / tm : 0.0;
      return 0;
    }
    const FrictionBranch& b = s.Branch(v);
    const double r = v / b.stribeck_velocity_mps;
    const double g = b.coulomb_mps2 + (b.static_mps2 - b.coulomb_mps2) * std::exp(-r * r);
    const double s0 = s.ad_->bristle_stiffness_per_s2;
    const double dz = v - s0 * std::abs(v) * y[kZ] / g;
    const double friction = s0 * y[kZ] + s.ad_->bristle_damping_per_s * dz + b.viscous_per_s * v;
    d[kX] = v;
    d[kV] = s.ad_->gain_mps2_per_v * y[kW] - friction;
    d[kZ] = dz;
    return 0;
  }

  // Analytic Jacobian (the finite-difference one struggles with |v| at v = 0).
  static int Jacobian(double, N_Vector yv, N_Vector, SUNMatrix J, void* data, N_Vector, N_Vector,
                      N_Vector) {
    const Impl& s = *static_cast<const Impl*>(data);
    const double* y = N_VGetArrayPointer(yv);
    SUNMatZero(J);
    const double inv_t = 1.0 / s.p_.driver.lag_time_constant_s;
    SM_ELEMENT_D(J, kW, kW) = -inv_t;
    const double tm = s.vs_ ? s.vs_->rail.memory_time_s : 0.0;
    if (tm > 0) SM_ELEMENT_D(J, kZ, kZ) = -1.0 / tm;
    if (s.stop_ != 0 || (s.vs_ && s.stuck_)) return 0;
    if (s.vs_) {
      const double v = y[kV], w = y[kW];
      const double p = s.vs_->motor.pole_per_s;
      const RailFriction& r = s.vs_->rail;
      const double h = 1e-6;  // [V] v_f is piecewise linear: a difference is its slope
      const double slope = (s.vs_->NoLoadSpeed(w + h) - s.vs_->NoLoadSpeed(w - h)) / (2 * h);
      // v' = T(p (v_f - v)) - d g(.): the droop's slope scales both partial derivatives.
      const double dt = s.vs_->motor.ThrustSlope(p * (s.vs_->NoLoadSpeed(w) - v));
      SM_ELEMENT_D(J, kX, kV) = 1.0;
      SM_ELEMENT_D(J, kV, kW) = dt * p * slope;
      if (tm > 0) {
        // v' = T(p (v_f - v)) - d g(s), T_m s' = d v - s.
        SM_ELEMENT_D(J, kV, kV) = -dt * p;
        SM_ELEMENT_D(J, kV, kZ) = -s.direction_ * r.SlidingSlope(y[kZ]);
        SM_ELEMENT_D(J, kZ, kV) = s.direction_ / tm;
        return 0;
      }
      // d/dv of d g(|v|) = d sgn(v) g'(|v|) (= g'(|v|) while v has the sliding direction).
      const double dg = r.SlidingSlope(std::abs(v)) * (v * s.direction_ >= 0 ? 1.0 : -1.0);
      SM_ELEMENT_D(J, kV, kV) = -dt * p - dg;
      return 0;
    }
    const double v = y[kV], z = y[kZ];
    const FrictionBranch& b = s.Branch(v);
    const double vs = b.stribeck_velocity_mps;
    const double r = v / vs;
    const double e = std::exp(-r * r);
    const double g = b.coulomb_mps2 + (b.static_mps2 - b.coulomb_mps2) * e;
    const double dg_dv = (b.static_mps2 - b.coulomb_mps2) * e * (-2.0 * v / (vs * vs));
    const double s0 = s.ad_->bristle_stiffness_per_s2, s1 = s.ad_->bristle_damping_per_s;
    const double sgn = v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
    // dz = v - s0 |v| z / g
    const double ddz_dv = 1.0 - s0 * z * (sgn * g - std::abs(v) * dg_dv) / (g * g);
    const double ddz_dz = -s0 * std::abs(v) / g;
    SM_ELEMENT_D(J, kX, kV) = 1.0;
    SM_ELEMENT_D(J, kZ, kV) = ddz_dv;
    SM_ELEMENT_D(J, kZ, kZ) = ddz_dz;
    // dv = a3 w - s0 z - s1 dz - s2 v
    SM_ELEMENT_D(J, kV, kW) = s.ad_->gain_mps2_per_v;
    SM_ELEMENT_D(J, kV, kV) = -s1 * ddz_dv - b.viscous_per_s;
    SM_ELEMENT_D(J, kV, kZ) = -s0 - s1 * ddz_dz;
    return 0;
  }

  static int Roots(double, N_Vector yv, double* g, void* data) {
    const Impl& s = *static_cast<const Impl*>(data);
    const double x = N_VGetArrayPointer(yv)[kX];
    g[0] = x - s.p_.rig.travel_max_m;
    g[1] = x - s.p_.rig.travel_min_m;
    if (s.vs_) g[2] = s.stuck_ ? s.Breakaway(N_VGetArrayPointer(yv)[kW]) : N_VGetArrayPointer(yv)[kV];
    return 0;
  }

  StageParameters p_;
  internal::PortableRandom noise_;
  double ts_ = 1e-3;
  long delay_samples_ = 0;
  double delay_fraction_ = 0;
  std::vector<DriveInput> history_;
  double dac_step_ = 0;
  double encoder_divisor_ = 0;
  long k_ = 0;
  double t_ = 0;
  DriveInput drive_;
  int stop_ = 0;
  const VelocitySourcePlant* vs_ = nullptr;  // in p_: the velocity-source model, or null
  const ActuatorDelayPlant* ad_ = nullptr;   // in p_: the actuator-delay model, or null
  // [s] T_c of DriveInput::At (its relax is 0 without creep, where T_c is not read)
  double creep_time_constant_s_ = 1.0;
  bool stuck_ = true;      // velocity source: held by the rail's static friction
  int direction_ = 1;      // velocity source: sliding direction d while not stuck
  double reading_ = 0;
  long sample_start_steps_ = 0;  // CVODE steps before this sample
  long sample_switches_ = 0;     // root returns in this sample
  double sample_u_ = 0;          // [V] this sample's DAC output
  StageStatus status_;
  DriveHysteresis hysteresis_;   // velocity source: the ceramic's hysteresis (may be off)
  std::vector<double> play_;     // [V] the play operators' outputs F_i
  double rate_ = 0;              // [V/s] the filtered input rate q
  double rate_gain_ = 1;         // b = 1 - exp(-Ts / tau)
  double rate_limit_ = 0;        // [V/s] rho_sat
  double last_input_ = 0;        // [V] the previous clipped command
  double creep_target_ = 0;      // [V] creep: q of the current anchor
  double creep_z_ = 0;           // [V] creep: z at the anchor (z = 0 at t = 0)
  double creep_from_ = 0;        // [s] creep: the anchor's sample time (before the delay)
  std::optional<internal::CvodeSolver> cv_;  // made once p_ is validated
};

VirtualStage::VirtualStage(const StageParameters& parameters, std::uint64_t seed)
    : impl_(std::make_unique<Impl>(parameters, seed)) {}
VirtualStage::~VirtualStage() = default;
VirtualStage::VirtualStage(VirtualStage&&) noexcept = default;
VirtualStage& VirtualStage::operator=(VirtualStage&&) noexcept = default;

double VirtualStage::Step(double u_command_v) { return impl_->Step(u_command_v); }
double VirtualStage::measured_position_m() const { return impl_->reading(); }
double VirtualStage::time_s() const { return impl_->time_s(); }
long VirtualStage::sample_index() const { return impl_->sample_index(); }
StageState VirtualStage::state() const { return impl_->State(); }
StageStatus VirtualStage::status() const { return impl_->Status(); }
const StageParameters& VirtualStage::parameters() const { return impl_->parameters(); }
double VirtualStage::DacOutput(double u_command_v) const { return impl_->Dac(u_command_v); }

StageRun RunOpenLoop(const StageParameters& parameters, const Eigen::VectorXd& u_v,
                     std::uint64_t seed) {
  VirtualStage stage(parameters, seed);
  const Eigen::Index n = u_v.size();
  StageRun run;
  run.t_s.resize(n);
  run.u_v = u_v;
  run.x_m.resize(n);
  run.x_true_m.resize(n);
  run.v_true_mps.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    run.t_s[k] = static_cast<double>(k) / parameters.rig.sample_rate_hz;
    run.x_m[k] = stage.measured_position_m();
    const StageState s = stage.state();
    run.x_true_m[k] = s.x_m;
    run.v_true_mps[k] = s.v_mps;
    stage.Step(u_v[k]);
  }
  run.status = stage.status();
  return run;
}

}  // namespace sysid
