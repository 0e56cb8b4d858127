// The piezo Bouc–Wen inverse as C: the stepper's bracket and bisection on the model's exact
// step, with expm1 and log of its own (so every IEEE-754 target computes the same values).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "c_text.hpp"
#include "sysid/deploy.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis_stepper.hpp"

namespace sysid {

// The C text helpers of c_text.hpp, by their short names.
using namespace internal;

namespace {

// log without the platform's libm: x = m 2^e with m in [sqrt(1/2), sqrt(2)) (scaling by 2 is
// exact), log m = 2 atanh(s), s = (m - 1) / (m + 1), |s| <= 0.172: the series' first term left
// out, 2 s^(2n+1) / (2n+1), is below 2^-56 (double, n = 11) or 2^-27 (float, n = 6) of log m.
std::string CLog(const std::string& prefix, ExportPrecision precision) {
  const bool dbl = precision == ExportPrecision::kDouble;
  const int terms = dbl ? 11 : 6;
  std::vector<double> coefficient;
  for (int n = 0; n < terms; ++n) coefficient.push_back(2.0 / (2 * n + 1));
  return Fill(R"(/* log(x), x > 0 and finite, without libm: x = m 2^e (m in [0.707, 1.414)), log m
 * = 2 atanh((m - 1) / (m + 1)) by its series (Horner in s^2), e ln 2 in two parts. */
static const @T@ @P@_kAtanh[@N@] = @COEF@;

static @T@ @P@_log(@T@ x) {
  @T@ m = x, s, s2, sum;
  int e = 0, n;
  while (m >= @SQRT2@ && e < 1100) {
    m *= @HALF@;
    ++e;
  }
  while (m < @SQRTH@ && e > -1100) {
    m *= @TWO@;
    --e;
  }
  s = (m - @ONE@) / (m + @ONE@);
  s2 = s * s;
  sum = @P@_kAtanh[@N@ - 1];
  for (n = @N@ - 2; n >= 0; --n) sum = sum * s2 + @P@_kAtanh[n];
  return (@T@)e * @LN2_HI@ + ((@T@)e * @LN2_LO@ + s * sum);
}

/* expm1(x) without libm: the series on |x| < 0.35, else 2^k (1 + expm1(r)) - 1 with x = k ln 2
 * + r; x below -40 gives -1, above 80 is taken as 80 (the model's steps stay far below). */
static @T@ @P@_expm1(@T@ x) {
  @T@ e, scale = @ONE@;
  int k;
  if (x > -@SMALL@ && x < @SMALL@) return @P@_expm1_series(x);
  if (x < -@FORTY@) return -@ONE@;
  if (x > @EIGHTY@) x = @EIGHTY@;
  k = (int)(x * @INV_LN2@ + (x < @ZERO@ ? -@HALF@ : @HALF@));
  e = @P@_expm1_series((x - (@T@)k * @LN2_HI@) - (@T@)k * @LN2_LO@) + @ONE@;
  for (; k > 0; --k) scale *= @TWO@;
  for (; k < 0; ++k) scale *= @HALF@;
  return e * scale - @ONE@;
}
)",
              {{"P", prefix},
               {"T", CType(precision)},
               {"N", std::to_string(terms)},
               {"COEF", CArray(coefficient, precision)},
               {"SQRT2", CLiteral(std::sqrt(2.0), precision)},
               {"SQRTH", CLiteral(std::sqrt(0.5), precision)},
               {"INV_LN2", CLiteral(1.0 / std::log(2.0), precision)},
               {"LN2_HI", dbl ? "6.93147180369123816490e-01" : "0.693145751953125f"},
               {"LN2_LO", dbl ? "1.90821492927058770002e-10" : "1.42860677e-06f"},
               {"SMALL", CLiteral(0.35, precision)},
               {"FORTY", CLiteral(40.0, precision)},
               {"EIGHTY", CLiteral(80.0, precision)},
               {"ZERO", CLiteral(0.0, precision)},
               {"HALF", CLiteral(0.5, precision)},
               {"ONE", CLiteral(1.0, precision)},
               {"TWO", CLiteral(2.0, precision)}});
}

}  // namespace

ExportVectors DefaultBoucWenVectors(const PiezoBoucWen& model) {
  // Loops of decaying amplitude over 3 / (beta + gamma) volts: h saturates over about
  // 1 / (beta + gamma), so the loops reach saturation and reverse inside it.
  const PiezoBoucWenParameters& p = model.values();
  const double amplitude = 3.0 / (p.beta_per_v + p.gamma_per_v);
  const int n = 2000;
  ExportVectors v;
  v.source = "default waveform";
  v.inputs.resize(n, 1);
  for (int k = 0; k < n; ++k)
    v.inputs(k, 0) = p.offset_m + p.d_m_per_v * amplitude * std::sin(2 * M_PI * k / 400.0) *
                                      (0.6 + 0.4 * std::cos(k / 300.0));
  return v;
}

// Long function: the exported C file, emitted top to bottom in the order it is read (header
// comment, tables, state, init, step); split, the file's text would be scattered over helpers.
ExportResult ExportBoucWenInverse(const PiezoBoucWen& model, const ExportVectors& v,
                                  const ExportOptions& o, const ExportProvenance& provenance) {
  o.Validate();
  BoucWenInverseStepper stepper(model);  // NumericalError when not invertible
  CheckVectors(v, 1, "bouc-wen-piezo");
  const PiezoBoucWenParameters& q = model.values();
  ExportResult r;
  r.kind = "bouc-wen-piezo";
  r.input_names = {"x_ref"};
  r.input_units = {"m"};
  r.u_expected_v.resize(v.inputs.rows());
  for (Eigen::Index k = 0; k < v.inputs.rows(); ++k)
    r.u_expected_v[k] = stepper.Step(v.inputs(k, 0));
  const ExportPrecision p = o.precision;
  const double eps = Epsilon(p);
  // The bound, by backward error as for the PI bisections (docs/deploy.md): one trial output
  // g(u) = d u - h(u) + c - x rounds by eta_g = 8 eps (d U + |c| + H + X) and its expm1 and
  // log (this file's, a few eps from the platform's) move h by 16 eps (|alpha| d + (|beta| +
  // |gamma|) H) W; the bisection ends on adjacent values; eta = 3 eta_g + 2 eps U s_max + eps X.
  // The inverse passes it on at 2 / s_min, s_min = d (1 - alpha) - max(beta - gamma, 0)
  // |alpha| d / (beta + gamma) the model's least slope (its invertibility margin). U, H, X:
  // twice the largest |u|, |h| = |d u + c - x| and |x| over the vectors; W = 2 U.
  double U = 0, H = 0, X = 0;
  for (Eigen::Index k = 0; k < v.inputs.rows(); ++k) {
    const double x = v.inputs(k, 0), u = r.u_expected_v[k];
    U = std::max(U, 2 * std::abs(u));
    X = std::max(X, 2 * std::abs(x));
    H = std::max(H, 2 * std::abs(q.d_m_per_v * u + q.offset_m - x));
  }
  const double d = q.d_m_per_v, a = q.alpha, b = q.beta_per_v, g = q.gamma_per_v;
  const double s_min = d * (1 - a) - std::max(b - g, 0.0) * std::abs(a) * d / (b + g);
  const double s_max = d * (1 + std::abs(a)) + (std::abs(b) + std::abs(g)) * H;
  const double eta_g = 8 * eps * (d * U + std::abs(q.offset_m) + H + X) +
                       16 * eps * (std::abs(a) * d + (std::abs(b) + std::abs(g)) * H) * 2 * U;
  const double eta = 3 * eta_g + 2 * eps * U * s_max + eps * X;
  r.bound_v = 2 * eta / s_min;
  r.bound_reason = fmt::format(
      "{}: 2 eta / s_min, eta = {:.3g} m (a trial output's roundings, this file's expm1 and "
      "log against the platform's, the bisection's last bracket), s_min = {:.3g} m/V the "
      "model's least slope, eps = 2^-{}: the inverse's conditioning (docs/deploy.md)",
      CType(p), eta, s_min, p == ExportPrecision::kDouble ? 53 : 24);
  const std::string T = CType(p);
  const std::string comment =
      fmt::format(
          " * Model: the inverse of the piezo Bouc-Wen model (kind bouc-wen-piezo, "
          "sysid/hysteresis_bouc_wen.hpp):\n"
          " *   y = d u - h + c, dh = alpha d du - beta |du| h - gamma du |h|, "
          "stepped exactly along straight segments of u;\n"
          " *   u_0 = (x_0 - c) / d, then u_k solves y(u_k) = x_ref,k from (u_(k-1), h) "
          "by a doubling bracket and bisection.\n"
          " *   d = {:.9g} m/V, alpha = {:.9g}, beta = {:.9g} 1/V, gamma = {:.9g} 1/V, "
          "c = {:.9g} m\n"
          " * Input (sample k): x_ref [m] the reference position. Output u [V].\n"
          " * Sample time: any (the model is rate-independent).\n"
          " * Range: no fitted range is stored; the vectors span x in {} m.\n",
          d, a, b, g, q.offset_m, Range(v.inputs.col(0))) +
      internal::Provenance(provenance, p, r.bound_v, r.bound_reason);
  const std::string state = Fill(R"(typedef struct {
  @T@ u_prev; /* u_(k-1) [V] */
  @T@ h;      /* the hysteretic state [m] */
  int k;      /* samples since init, saturating at 1 */
} @P@_state;
)",
                                 {{"T", T}});
  r.header =
      Fill(Header(o, comment, state, ", " + T + " x_ref_m", 1, r.bound_v), {{"P", o.prefix}});
  const std::string series = internal::CExpm1Series(o.prefix, p);
  r.source = Fill(R"(/* @P@.c -- generated by sysid export; see @P@.h. */
#include "@P@.h"

static const @T@ @P@_kD = @D@;
static const @T@ @P@_kAlpha = @ALPHA@;
static const @T@ @P@_kBeta = @BETA@;
static const @T@ @P@_kGamma = @GAMMA@;
static const @T@ @P@_kOffset = @C@;
static const @T@ @P@_kStepScale = @STEPSCALE@; /* d max(1 - alpha, 1e-3) */
static const @T@ @P@_kTiny = @TINY@;

@SERIES@
@LOG@
void @P@_init(@P@_state* state) {
  state->u_prev = @ZERO@;
  state->h = @ZERO@;
  state->k = 0;
}

static @T@ @P@_abs(@T@ x) { return x < @ZERO@ ? -x : x; }

/* h after u moves straight from u0 to u1: dh/dw = a - b h along w = |u - u0|, exponential while
 * h keeps its sign; h crosses zero at most once. */
static @T@ @P@_piezo_step(@T@ u0, @T@ u1, @T@ h) {
  const @T@ s = u1 > u0 ? @ONE@ : (u1 < u0 ? -@ONE@ : @ZERO@);
  @T@ a, w;
  int piece;
  if (s == @ZERO@) return h;
  a = s * @P@_kAlpha * @P@_kD;
  w = @P@_abs(u1 - u0);
  for (piece = 0; piece < 3 && w > @ZERO@; ++piece) {
    const @T@ sigma = h > @ZERO@ ? @ONE@ : h < @ZERO@ ? -@ONE@ : a > @ZERO@ ? @ONE@ : a < @ZERO@ ? -@ONE@ : @ZERO@;
    @T@ b, gw, end, end_sign, wstar;
    if (sigma == @ZERO@) return @ZERO@;
    b = @P@_kBeta + s * sigma * @P@_kGamma;
    gw = @P@_abs(b * w) < @P@_kTiny ? w : -@P@_expm1(-b * w) / b;
    end = h + (a - b * h) * gw;
    end_sign = end > @ZERO@ ? @ONE@ : end < @ZERO@ ? -@ONE@ : @ZERO@;
    if (h == @ZERO@ || end_sign == sigma || end_sign == @ZERO@) return end;
    if (@P@_abs(b) < @P@_kTiny) {
      wstar = -h / a;
    } else {
      const @T@ ratio = a / (a - b * h);
      wstar = -@P@_log(ratio) / b;
    }
    wstar = wstar < @ZERO@ ? @ZERO@ : (wstar > w ? w : wstar);
    w -= wstar;
    h = @ZERO@;
  }
  return h;
}

static @T@ @P@_g(@T@ v, @T@ u0, @T@ h, @T@ target) {
  return @P@_kD * v - @P@_piezo_step(u0, v, h) + @P@_kOffset - target;
}

@T@ @P@_step(@P@_state* state, @T@ x_ref_m) {
  const @T@ u0 = state->u_prev, h = state->h;
  @T@ g0, dir, step, far = u0, lo, hi, glo, u;
  int expansions, it;
  if (state->k == 0) {
    state->k = 1;
    state->u_prev = (x_ref_m - @P@_kOffset) / @P@_kD;
    return state->u_prev;
  }
  g0 = @P@_g(u0, u0, h, x_ref_m);
  dir = g0 < @ZERO@ ? @ONE@ : -@ONE@;
  step = @P@_abs(g0) / @P@_kStepScale;
  if (!(step >= @P@_kTiny)) step = @P@_kTiny;
  for (expansions = 0; expansions < 200; ++expansions) {
    far = u0 + dir * step;
    if ((@P@_g(far, u0, h, x_ref_m) < @ZERO@) != (g0 < @ZERO@) ||
        @P@_g(far, u0, h, x_ref_m) == @ZERO@)
      break;
    step *= @TWO@;
  }
  if (expansions == 200) return u0; /* out of the model's reach: u held */
  lo = u0 < far ? u0 : far;
  hi = u0 < far ? far : u0;
  glo = @P@_g(lo, u0, h, x_ref_m);
  for (it = 0; it < 200; ++it) {
    const @T@ mid = @HALF@ * (lo + hi);
    @T@ gm;
    if (mid <= lo || mid >= hi) break;
    gm = @P@_g(mid, u0, h, x_ref_m);
    if (gm == @ZERO@) {
      lo = hi = mid;
      break;
    }
    if ((gm < @ZERO@) == (glo < @ZERO@)) {
      lo = mid;
      glo = gm;
    } else {
      hi = mid;
    }
  }
  u = @P@_abs(@P@_g(lo, u0, h, x_ref_m)) <= @P@_abs(@P@_g(hi, u0, h, x_ref_m)) ? lo : hi;
  state->h = @P@_piezo_step(u0, u, h);
  state->u_prev = u;
  return u;
}
)",
                  {{"SERIES", series},
                   {"LOG", CLog(o.prefix, p)},
                   {"P", o.prefix},
                   {"T", T},
                   {"D", CLiteral(d, p)},
                   {"ALPHA", CLiteral(a, p)},
                   {"BETA", CLiteral(b, p)},
                   {"GAMMA", CLiteral(g, p)},
                   {"C", CLiteral(q.offset_m, p)},
                   {"STEPSCALE", CLiteral(d * std::max(1 - a, 1e-3), p)},
                   {"TINY", CLiteral(p == ExportPrecision::kDouble ? 1e-300 : 1e-37, p)},
                   {"ZERO", CLiteral(0.0, p)},
                   {"HALF", CLiteral(0.5, p)},
                   {"ONE", CLiteral(1.0, p)},
                   {"TWO", CLiteral(2.0, p)}});
  Finish(&r, o, v, "piezo Bouc-Wen inverse", {"x_ref_m"}, "sample, in order");
  return r;
}

}  // namespace sysid
