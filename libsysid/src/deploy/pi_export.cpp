// The PI-family inverses as C: pi's closed form, gpi's and rdpi's bisection.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <string>

#include "c_text.hpp"
#include "core/option_rule.hpp"
#include "sysid/deploy.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis_stepper.hpp"

namespace sysid {

// The C text helpers of c_text.hpp, by their short names.
using namespace internal;

namespace {

// The float bound of a bisection inverse (gpi, rdpi), from the model's conditioning.
// Backward error: the float run is the exact model driven by the float u~ up to an output
// error eta per sample, because (i) a play state's error stays below eps (U + r_i) (the clamp
// to [u - r, u + r] is non-expansive in the state and both ends, so errors never accumulate),
// (ii) one trial output y(u) rounds by at most eta_y = (n + 2m + 10) eps L, L = |c| +
// |q0| rho_max U + sum_j |a_j| U^j + sum_i (w_i + q_i rho_max)(U + r_i), and (iii) the bisection
// ends on adjacent floats bracketing x_ref: eta = 3 eta_y + 2 eps U s_max + eps X (the last:
// x_ref rounded to float), U = max(|lo|, |hi|), X twice the vectors' largest |x|, s_max the
// largest slope of y in u. The exact inverse is Lipschitz in the sup norm: for a classical PI
// with weights >= 0 its inverse's |p0'| + sum |w'_i| = 2/p0 - 1/(p0 + sum w) < 2/p0; here the
// polynomial's least slope s_min on [lo, hi] (on the invertibility check's grid) takes p0's
// place. rdpi: the rate is the inverse's own, so an error D in u moves the rate by up to
// 2D/dt and the output by (|q0| + sum q_i) U 2D/dt, which the inverse passes on at 2/s_min:
// a gain g = 4 sum q U / (dt s_min), and the bound holds for g < 1 (float refused otherwise).
// |du| <= 2 eta / (s_min (1 - g)).
double BisectionFloatBound(const PrandtlIshlinskiiModel& model, const PiInverseStepper& stepper,
                           double dt_s, const ExportVectors& v, std::string* reason) {
  const PiParameters& p = model.pi();
  const bool rate = p.form == PiForm::kRateDependent;
  const double eps = Epsilon(ExportPrecision::kFloat);
  const double lo = stepper.input_min_v(), hi = stepper.input_max_v();
  const double U = std::max(std::abs(lo), std::abs(hi));
  const double rho_max = rate ? (hi - lo) / dt_s : 0.0;
  const double X = 2 * v.inputs.col(0).cwiseAbs().maxCoeff();
  const double q0 = rate ? p.rate_weights[0] : 0.0;
  double level = std::abs(p.offset_m) + std::abs(q0) * rho_max * U, s_max = std::abs(q0) * rho_max;
  double q_sum = std::abs(q0);
  for (size_t j = 0; j < p.polynomial.size(); ++j) {
    level += std::abs(p.polynomial[j]) * std::pow(U, static_cast<double>(j + 1));
    s_max += static_cast<double>(j + 1) * std::abs(p.polynomial[j]) *
             std::pow(U, static_cast<double>(j));
  }
  for (size_t i = 0; i < p.thresholds.size(); ++i) {
    const double q = rate ? p.rate_weights[i + 1] : 0.0;
    level += (p.weights[i] + q * rho_max) * (U + p.thresholds[i]);
    s_max += p.weights[i] + q * rho_max;
    q_sum += q;
  }
  // The least slope of the polynomial on [lo, hi], on the invertibility check's grid.
  double s_min = std::numeric_limits<double>::infinity();
  constexpr int kGrid = 1001;
  for (int g = 0; g < kGrid; ++g) {
    const double u = lo + (hi - lo) * g / (kGrid - 1);
    double slope = 0, power = 1;
    for (size_t j = 0; j < p.polynomial.size(); ++j, power *= u)
      slope += static_cast<double>(j + 1) * p.polynomial[j] * power;
    s_min = std::min(s_min, slope);
  }
  const double gain = rate ? 4 * q_sum * U / (dt_s * s_min) : 0.0;
  if (!(s_min > 0) || !(gain < 1))
    throw OptionsError(
        fmt::format("{}: no float bound: {}; export in double", model.kind(),
                    s_min > 0 ? fmt::format("the rate feedback's float error gain "
                                            "4 (q0 + ... + qn) max|u| / (dt s_min) = {:.3g} >= 1",
                                            gain)
                              : fmt::format("the polynomial's least slope {:.3g} m/V", s_min)),
        "precision");
  const double n = static_cast<double>(p.thresholds.size());
  const double m = static_cast<double>(p.polynomial.size());
  const double eta = 3 * (n + 2 * m + 10) * eps * level + 2 * eps * U * s_max + eps * X;
  *reason = fmt::format(
      "float: 2 eta / (s_min (1 - g)), eta = 3 (n + 2m + 10) eps L + 2 eps U s_max + eps X = "
      "{:.3g} m, s_min = {:.3g} m/V (the polynomial's least slope), g = {:.3g} (the rate "
      "feedback), eps = 2^-24: the inverse's conditioning (docs/deploy.md)",
      eta, s_min, gain);
  return 2 * eta / (s_min * (1 - gain));
}

// Long function: the exported C file, emitted top to bottom in the order it is read (header
// comment, tables, state, init, step); split, the file's text would be scattered over helpers.
// gpi and rdpi: the stepper's bisection on the step's monotone output, in the stepper's
// operations and order (bit-identical in double).
ExportResult ExportPiBisection(const PrandtlIshlinskiiModel& model, double dt_s,
                               const ExportVectors& v, const ExportOptions& o,
                               const ExportProvenance& provenance) {
  PiInverseStepper stepper(model, dt_s);  // not invertible, rdpi's error gain: NumericalError
  CheckVectors(v, 1, model.kind().c_str());
  ExportResult r;
  r.kind = model.kind();
  r.input_names = {"x_ref"};
  r.input_units = {"m"};
  r.u_expected_v.resize(v.inputs.rows());
  for (Eigen::Index k = 0; k < v.inputs.rows(); ++k)
    r.u_expected_v[k] = stepper.Step(v.inputs(k, 0));
  stepper.Reset();  // its state is now the initial one, which the C starts from
  if (o.precision == ExportPrecision::kDouble) {
    r.bound_v = 0;
    r.bound_reason = "the stepper's operations in its order on the same doubles: bit-identical";
  } else {
    r.bound_v = BisectionFloatBound(model, stepper, dt_s, v, &r.bound_reason);
  }
  const PiParameters& p = model.pi();
  const bool rate = p.form == PiForm::kRateDependent;
  const size_t n = p.thresholds.size(), slots = std::max<size_t>(n, 1);
  const ExportPrecision prec = o.precision;
  std::vector<double> r_pad = p.thresholds, w_pad = p.weights, q_pad(slots, 0.0),
                      z_pad = stepper.state();
  r_pad.resize(slots, 0.0);
  w_pad.resize(slots, 0.0);
  z_pad.resize(slots, 0.0);
  for (size_t i = 0; rate && i < n; ++i) q_pad[i] = p.rate_weights[i + 1];
  const std::string comment =
      fmt::format(" * Model: the inverse of a {} Prandtl-Ishlinskii model with {} play operators "
                  "(sysid/hysteresis.hpp):\n"
                  " *   u_k solves y(u_k) = x_ref by bisection to adjacent values on [lo, hi], "
                  "y(u) = c + q0 rho u\n"
                  " *   + sum_j a_j u^j + sum_i (w_i + q_i rho) F_ri[u] (monotone in u); rho = "
                  "|u_(k-1) - u_(k-2)| / dt (rdpi)\n"
                  " * Input (sample k): x_ref [m] the reference position. Output u [V], clamped "
                  "to [lo, hi].\n"
                  " * Sample time: {:g} s{}.\n"
                  " * Fitted range: u in [{:.9g}, {:.9g}] V, accepted widened by {:g} % to "
                  "[{:.9g}, {:.9g}] V;\n *   the vectors span x in {} m.\n",
                  model.kind(), n, dt_s, rate ? " (the rate uses it)" : " (unused: rate-independent)",
                  p.input_min_v, p.input_max_v, 100 * model.range_margin(), stepper.input_min_v(),
                  stepper.input_max_v(), Range(v.inputs.col(0))) +
      internal::Provenance(provenance, prec, r.bound_v, r.bound_reason);
  const std::string state = Fill(R"(#define @P@_OPERATORS @N@
typedef struct {
  @T@ z[@SLOTS@]; /* the play operators' outputs [V] */
  @T@ u1, u2;     /* u_(k-1), u_(k-2) [V] (the rate) */
  int k;          /* samples since init, saturating at 2 */
} @P@_state;
)",
                                 {{"N", std::to_string(n)},
                                  {"SLOTS", std::to_string(slots)},
                                  {"T", CType(prec)}});
  r.header = Fill(Header(o, comment, state, ", " + CType(prec) + " x_ref_m", 1, r.bound_v), {{"P", o.prefix}});
  r.source = Fill(R"(/* @P@.c -- generated by sysid export; see @P@.h. */
#include "@P@.h"

#define @P@_M @M@
static const @T@ @P@_kR[@SLOTS@] = @R@;
static const @T@ @P@_kW[@SLOTS@] = @W@;
static const @T@ @P@_kQ[@SLOTS@] = @Q@;
static const @T@ @P@_kZ0[@SLOTS@] = @Z0@;
static const @T@ @P@_kPoly[@P@_M] = @POLY@;
static const @T@ @P@_kQ0 = @Q0@;
static const @T@ @P@_kOffset = @C@;
static const @T@ @P@_kDt = @DT@;
static const @T@ @P@_kLo = @LO@;
static const @T@ @P@_kHi = @HI@;
static const int @P@_kRate = @RATE@;

void @P@_init(@P@_state* state) {
  int i;
  for (i = 0; i < @SLOTS@; ++i) state->z[i] = @P@_kZ0[i];
  state->u1 = @ZERO@;
  state->u2 = @ZERO@;
  state->k = 0;
}

static @T@ @P@_play(@T@ u, @T@ r, @T@ z) {
  const @T@ lo = u - r, hi = u + r;
  return z < lo ? lo : (z > hi ? hi : z);
}

/* The step's output for a trial input, the states left as they are. */
static @T@ @P@_output(const @P@_state* state, @T@ uk, @T@ rho) {
  @T@ sum = @P@_kOffset + @P@_kQ0 * rho * uk, power = uk;
  int i, j;
  for (j = 0; j < @P@_M; ++j, power *= uk) sum += @P@_kPoly[j] * power;
  for (i = 0; i < @P@_OPERATORS; ++i)
    sum += (@P@_kW[i] + (@P@_kRate ? @P@_kQ[i] * rho : @ZERO@)) *
           @P@_play(uk, @P@_kR[i], state->z[i]);
  return sum;
}

@T@ @P@_step(@P@_state* state, @T@ x_ref_m) {
  const @T@ d = state->u1 - state->u2;
  const @T@ rho = @P@_kRate && state->k >= 2 ? (d < @ZERO@ ? -d : d) / @P@_kDt : @ZERO@;
  const @T@ y = x_ref_m;
  const @T@ y_lo = @P@_output(state, @P@_kLo, rho), y_hi = @P@_output(state, @P@_kHi, rho);
  @T@ a = @P@_kLo, b = @P@_kHi, u;
  int i;
  if (y_lo > y || y_hi < y || !(y == y)) {
    u = !(y_lo > y) ? b : a;
  } else {
    int it;
    @T@ ua, ub;
    for (it = 0; it < 200; ++it) {
      const @T@ mid = @HALF@ * (a + b);
      if (mid <= a || mid >= b) break;
      if (@P@_output(state, mid, rho) < y) a = mid; else b = mid;
    }
    ua = @P@_output(state, a, rho);
    ub = @P@_output(state, b, rho);
    u = (y - ua <= ub - y) ? a : b;
  }
  for (i = 0; i < @P@_OPERATORS; ++i) state->z[i] = @P@_play(u, @P@_kR[i], state->z[i]);
  state->u2 = state->u1;
  state->u1 = u;
  if (state->k < 2) ++state->k;
  return u;
}
)",
                  {{"P", o.prefix},
                   {"M", std::to_string(p.polynomial.size())},
                   {"SLOTS", std::to_string(slots)},
                   {"R", CArray(r_pad, prec)},
                   {"W", CArray(w_pad, prec)},
                   {"Q", CArray(q_pad, prec)},
                   {"Z0", CArray(z_pad, prec)},
                   {"POLY", CArray(p.polynomial, prec)},
                   {"Q0", CLiteral(rate ? p.rate_weights[0] : 0.0, prec)},
                   {"C", CLiteral(p.offset_m, prec)},
                   {"DT", CLiteral(dt_s, prec)},
                   {"LO", CLiteral(stepper.input_min_v(), prec)},
                   {"HI", CLiteral(stepper.input_max_v(), prec)},
                   {"RATE", rate ? "1" : "0"},
                   {"T", CType(prec)},
                   {"ZERO", CLiteral(0.0, prec)},
                   {"HALF", CLiteral(0.5, prec)}});
  Finish(&r, o, v, model.kind() + " inverse", {"x_ref_m"}, fmt::format("{:g} s", dt_s));
  return r;
}

}  // namespace

// Long function: the exported C file, emitted top to bottom in the order it is read (header
// comment, tables, state, init, step); split, the file's text would be scattered over helpers.
ExportResult ExportPiInverse(const PrandtlIshlinskiiModel& model, double dt_s,
                             const ExportVectors& v, const ExportOptions& o,
                             const ExportProvenance& provenance) {
  o.Validate();
  if (!(dt_s > 0) || !std::isfinite(dt_s))
    internal::FailOption("", "dt_s", dt_s, "0 < dt_s < infinity");
  if (model.pi().form != PiForm::kClassical) return ExportPiBisection(model, dt_s, v, o, provenance);
  PiInverseStepper stepper(model, dt_s);  // NumericalError when not invertible
  CheckVectors(v, 1, "pi");
  ExportResult r;
  r.kind = "pi";
  r.input_names = {"x_ref"};
  r.input_units = {"m"};
  r.u_expected_v.resize(v.inputs.rows());
  for (Eigen::Index k = 0; k < v.inputs.rows(); ++k)
    r.u_expected_v[k] = stepper.Step(v.inputs(k, 0));
  stepper.Reset();
  const PiParameters& inv = stepper.stepped_parameters();
  const std::vector<double> z0 = stepper.state();
  const size_t n = inv.thresholds.size();
  const ExportPrecision p = o.precision;
  const double eps = Epsilon(p);
  if (p == ExportPrecision::kDouble) {
    r.bound_v = 0;
    r.bound_reason = "the stepper's operations in its order on the same doubles: bit-identical";
  } else {
    // y' = x - c errs by 3 eps Y (Y = |x| + |c|, x within twice the vectors' largest); the play
    // operators are non-expansive, so each state errs by that plus 2 eps (Y + r'_i) and no error
    // accumulates over samples; the sum rounds (n + 2) times, each constant once:
    // |du| <= 2 (n + 8) eps (|p0'| Y + sum |w'_i| (Y + r'_i)).
    const double Y = 2 * v.inputs.col(0).cwiseAbs().maxCoeff() + std::abs(stepper.offset_m());
    double level = std::abs(inv.polynomial[0]) * Y;
    for (size_t i = 0; i < n; ++i) level += std::abs(inv.weights[i]) * (Y + inv.thresholds[i]);
    r.bound_v = 2.0 * (static_cast<double>(n) + 8) * eps * level;
    r.bound_reason = fmt::format(
        "float: 2 (n + 8) eps (|p0'| Y + sum |w'_i| (Y + r'_i)), eps = 2^-24, Y = {:.3g} m "
        "(|c| + twice the vectors' largest |x|): the inverse's conditioning",
        Y);
  }
  const PiParameters& fwd = model.pi();
  const std::string T = CType(p);
  const std::string comment =
      fmt::format(" * Model: the inverse of a classical Prandtl-Ishlinskii model with {} play "
                  "operators (Kuhnen 2003):\n"
                  " *   u = p0' (x - c) + sum_i w'_i F_r'i[x - c], clamped to the input range "
                  "(sysid/hysteresis_stepper.hpp)\n"
                  " * Input (sample k): x_ref [m] the reference position. Output u [V].\n"
                  " * Sample time: {:g} s (the inverse is rate-independent: any step).\n"
                  " * Fitted range: u in [{:.9g}, {:.9g}] V, accepted widened by {:g} % to "
                  "[{:.9g}, {:.9g}] V;\n *   the vectors span x in {} m.\n",
                  n, dt_s, fwd.input_min_v, fwd.input_max_v, 100 * model.range_margin(),
                  stepper.input_min_v(), stepper.input_max_v(), Range(v.inputs.col(0))) +
      internal::Provenance(provenance, p, r.bound_v, r.bound_reason);
  const size_t slots = std::max<size_t>(n, 1);  // C99 has no empty arrays
  const std::string state = Fill(R"(#define @P@_OPERATORS @N@
typedef struct {
  @T@ z[@SLOTS@]; /* the inverse's play operators' outputs [m] */
} @P@_state;
)",
                                 {{"N", std::to_string(n)},
                                  {"SLOTS", std::to_string(slots)},
                                  {"T", T}});
  std::vector<double> r_pad = inv.thresholds, w_pad = inv.weights, z_pad = z0;
  r_pad.resize(slots, 0.0);
  w_pad.resize(slots, 0.0);
  z_pad.resize(slots, 0.0);
  const std::string args = ", " + T + " x_ref_m";
  r.header = Fill(Header(o, comment, state, args, 1, r.bound_v), {{"P", o.prefix}});
  r.source = Fill(R"(/* @P@.c -- generated by sysid export; see @P@.h. */
#include "@P@.h"

static const @T@ @P@_kR[@SLOTS@] = @R@;
static const @T@ @P@_kW[@SLOTS@] = @W@;
static const @T@ @P@_kZ0[@SLOTS@] = @Z0@;
static const @T@ @P@_kP0 = @P0@;
static const @T@ @P@_kOffset = @C@;
static const @T@ @P@_kLo = @LO@;
static const @T@ @P@_kHi = @HI@;

void @P@_init(@P@_state* state) {
  int i;
  for (i = 0; i < @SLOTS@; ++i) state->z[i] = @P@_kZ0[i];
}

@T@ @P@_step(@P@_state* state, @T@ x_ref_m) {
  const @T@ y = x_ref_m - @P@_kOffset;
  @T@ sum = @P@_kP0 * y;
  int i;
  for (i = 0; i < @P@_OPERATORS; ++i) {
    const @T@ lo = y - @P@_kR[i], hi = y + @P@_kR[i];
    const @T@ z = state->z[i];
    state->z[i] = z < lo ? lo : (z > hi ? hi : z);
    sum += @P@_kW[i] * state->z[i];
  }
  if (!(sum >= @P@_kLo && sum <= @P@_kHi)) sum = sum > @P@_kHi ? @P@_kHi : @P@_kLo;
  return sum;
}
)",
                  {{"P", o.prefix},
                   {"T", T},
                   {"SLOTS", std::to_string(slots)},
                   {"R", CArray(r_pad, p)},
                   {"W", CArray(w_pad, p)},
                   {"Z0", CArray(z_pad, p)},
                   {"P0", CLiteral(inv.polynomial[0], p)},
                   {"C", CLiteral(stepper.offset_m(), p)},
                   {"LO", CLiteral(stepper.input_min_v(), p)},
                   {"HI", CLiteral(stepper.input_max_v(), p)}});
  Finish(&r, o, v, "classical PI inverse", {"x_ref_m"}, fmt::format("{:g} s", dt_s));
  return r;
}

}  // namespace sysid
