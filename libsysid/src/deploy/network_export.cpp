// The tanh network (and the operator-input network's inverse) as C, with the bounds of its own
// tanh against the platform's and of float arithmetic.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "c_text.hpp"
#include "sysid/deploy.hpp"
#include "sysid/error.hpp"
#include "sysid/nn_stepper.hpp"

namespace sysid {

// The C text helpers of c_text.hpp, by their short names.
using namespace internal;

namespace {

// Long function: the exported C file, emitted top to bottom in the order it is read (header
// comment, tables, state, init, step); split, the file's text would be scattered over helpers.
// The tanh network's step; with `ops`, the operator-input network's inverse: the inverse side's
// play operators on the clamped x_ref feed the same network code.
ExportResult ExportNetworkCore(const NeuralNetwork& network, const ExportVectors& v,
                               const ExportOptions& o, const ExportProvenance& provenance,
                               const OperatorNetworkModel* ops) {
  o.Validate();
  NetworkStepper stepper(network);  // validates: finite weights, ranges
  const int n = network.input_count(), H = network.hidden_size();
  CheckVectors(v, ops != nullptr ? 1 : n, ops != nullptr ? "nn-operators" : "nn");
  ExportResult r;
  r.kind = ops != nullptr ? "nn-operators" : "nn";
  std::string args, arg_names, inputs_text, copy;
  std::vector<std::string> readme_args;
  for (int i = 0; i < n && ops == nullptr; ++i) {
    const ScaledVariable& in = network.inputs()[static_cast<size_t>(i)];
    for (char c : in.name)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_'))
        throw InputError(fmt::format("network input '{}': expected a name of letters, digits "
                                     "and '_' (it becomes a C parameter and a CSV column)",
                                     in.name));
    if (std::find(r.input_names.begin(), r.input_names.end(), in.name) != r.input_names.end())
      throw InputError(fmt::format("network input '{}' appears twice: each input becomes a C "
                                   "parameter and a CSV column of its own", in.name));
    r.input_names.push_back(in.name);
    r.input_units.push_back(in.unit);
    args += ", " + CType(o.precision) + " in_" + in.name;
    readme_args.push_back("in_" + in.name);
    copy += fmt::format("  x[{}] = in_{};\n", i, in.name);
    inputs_text += fmt::format(" *   {} [{}], fitted range [{:.9g}, {:.9g}]\n", in.name, in.unit,
                               in.min, in.max);
  }
  const size_t m = ops != nullptr ? ops->inverse().thresholds.size() : 0;
  if (ops != nullptr) {
    r.input_names = {"x_ref"};
    r.input_units = {"m"};
    args = ", " + CType(o.precision) + " x_ref_m";
    readme_args = {"x_ref_m"};
    // The stepper's features, in its operations: x clamped to the range, then each operator.
    copy = Fill(R"(  x[0] = x_ref_m >= @P@_kXLo && x_ref_m <= @P@_kXHi ? x_ref_m
                                                  : (x_ref_m > @P@_kXHi ? @P@_kXHi : @P@_kXLo);
  for (i = 0; i < @P@_M; ++i) {
    const @T@ lo = x[0] - @P@_kR[i], hi = x[0] + @P@_kR[i];
    const @T@ zi = state->z[i];
    state->z[i] = zi < lo ? lo : (zi > hi ? hi : zi);
    x[i + 1] = state->z[i];
  }
)",
                {{"M", std::to_string(m)}, {"T", CType(o.precision)}});
    inputs_text = fmt::format(" *   x_ref [m]: the reference position; the network's inputs are "
                              "x_ref and {} play operators of it\n", m);
  }
  r.u_expected_v.resize(v.inputs.rows());
  if (ops != nullptr) {
    OperatorNetworkInverseStepper op_stepper(*ops);
    for (Eigen::Index k = 0; k < v.inputs.rows(); ++k)
      r.u_expected_v[k] = op_stepper.Step(v.inputs(k, 0));
  } else {
    for (Eigen::Index k = 0; k < v.inputs.rows(); ++k) {
      const Eigen::VectorXd row = v.inputs.row(k).transpose();
      r.u_expected_v[k] = stepper.Step(row.data());
    }
  }
  const ExportPrecision p = o.precision;
  const double eps = Epsilon(p);
  const ScaledVariable& out = network.output();
  const double half_span = 0.5 * (out.max - out.min);
  double w2_sum = 0;
  for (int h = 0; h < H; ++h) w2_sum += std::abs(network.w2()[h]);
  const double out_level = std::abs(out.min) + std::abs(out.max);
  if (p == ExportPrecision::kDouble) {
    // The inputs' scaling and the hidden sums are the stepper's operations in its order: equal.
    // Only tanh differs (the export's own within 6.6 eps of tanh at first order, docs/deploy.md;
    // the platform's within 2 ulp = 2 eps, glibc's listed maximum, 1.7 measured: 10 eps apart),
    // and each output sum rounds again: |du| <= half span (sum |w2| 10 eps + 2 (H + 2) eps
    // (|b2| + sum |w2| + 1)) + 4 eps (|u_min| + |u_max|).
    r.bound_v = half_span * (w2_sum * 10 * eps +
                             2.0 * (H + 2) * eps * (std::abs(network.b2()) + w2_sum + 1)) +
                4 * eps * out_level;
    r.bound_reason =
        "double: the same sums in the same order; tanh (this file's and the platform's, 10 eps "
        "apart at most) and the output sum's roundings: (u_max - u_min)/2 (10 eps sum|w2| + "
        "2 (H + 2) eps (|b2| + sum|w2| + 1)) + 4 eps (|u_min| + |u_max|), eps = 2^-53";
  } else {
    // First order in float, at each input of the vectors and of a grid over twice the fitted
    // range (n <= 2): z_i = 2 (x - min) / (max - min) - 1 errs by ds_i <= 6 eps (|z_i| + 2 (|x_i|
    // + |min| + |max|) / (max - min)); a hidden sum by (n + 8) eps (|b1| + sum_i |W1| (|z_i| + 1))
    // plus sum_i |W1| dz_i; tanh passes it on at its slope 1 - t^2 (plus 0.4 ds^2, its
    // curvature) and errs by 8 eps itself (6.6 at first order, docs/deploy.md); the output sum
    // as in double. The largest over the
    // points, doubled, is the bound: saturated units (t near +-1) pass almost nothing on, so a
    // network with large weights is still checked closely where it is used.
    // nn-operators: the network's inputs x, F_r1[x], ... are the play operators' outputs on
    // the clamped x. A play step clamps its state to [x - r, x + r], whose ends round by
    // eps (|x| + r); the clamp is non-expansive in the state and in both ends, so a state's
    // error stays below that at every sample (it never accumulates): input i carries
    // dx_i = 2 eps (X + r_i) more, X = max(|x_lo|, |x_hi|), through dz_i = 2 dx_i / (max - min).
    Eigen::VectorXd dx = Eigen::VectorXd::Zero(n);
    if (ops != nullptr) {
      OperatorNetworkInverseStepper limits(*ops);
      const double X = std::max(std::abs(limits.x_min_m()), std::abs(limits.x_max_m()));
      for (size_t i = 0; i < m; ++i)
        dx[static_cast<Eigen::Index>(i) + 1] = 2 * eps * (X + ops->inverse().thresholds[i]);
    }
    auto at = [&](const Eigen::VectorXd& x) {
      double dy = 2.0 * (H + 2) * eps * (std::abs(network.b2()) + w2_sum + 1);
      for (int h = 0; h < H; ++h) {
        double s = network.b1()[h], level = std::abs(network.b1()[h]), carried = 0;
        for (int i = 0; i < n; ++i) {
          const ScaledVariable& in = network.inputs()[static_cast<size_t>(i)];
          const double z = in.Normalize(x[i]);
          const double dz = 6 * eps * (std::abs(z) + 2 * (std::abs(x[i]) + std::abs(in.min) +
                                                          std::abs(in.max)) / (in.max - in.min)) +
                            2 * dx[i] / (in.max - in.min);
          s += network.W1()(h, i) * z;
          level += std::abs(network.W1()(h, i)) * (std::abs(z) + 1);
          carried += std::abs(network.W1()(h, i)) * dz;
        }
        const double ds = (n + 8) * eps * level + carried;
        const double t = std::tanh(s);
        dy += std::abs(network.w2()[h]) * ((1 - t * t) * ds + 0.4 * ds * ds + 8 * eps);
      }
      return half_span * dy + 4 * eps * out_level;
    };
    double worst = 0;
    if (ops != nullptr) {
      // The network's inputs over the vectors: the stepper's features (clamp, then plays).
      OperatorNetworkInverseStepper limits(*ops);
      std::vector<double> z(m, ops->inverse().initial_input);
      Eigen::VectorXd features(n);
      for (Eigen::Index k = 0; k < v.inputs.rows(); ++k) {
        const double x = std::clamp(v.inputs(k, 0), limits.x_min_m(), limits.x_max_m());
        features[0] = x;
        for (size_t i = 0; i < m; ++i) {
          z[i] = PlayStep(x, ops->inverse().thresholds[i], z[i]);
          features[static_cast<Eigen::Index>(i) + 1] = z[i];
        }
        worst = std::max(worst, at(features));
      }
    } else {
      for (Eigen::Index k = 0; k < v.inputs.rows(); ++k)
        worst = std::max(worst, at(v.inputs.row(k).transpose()));
    }
    if (n <= 2 && ops == nullptr) {
      const int grid = n == 1 ? 4001 : 201;
      Eigen::VectorXd x(n);
      for (int g = 0; g < (n == 1 ? grid : grid * grid); ++g) {
        for (int i = 0; i < n; ++i) {
          const ScaledVariable& in = network.inputs()[static_cast<size_t>(i)];
          const int j = i == 0 ? g % grid : g / grid;
          const double mid = 0.5 * (in.min + in.max), half = in.max - in.min;
          x[i] = mid - half + 2 * half * j / (grid - 1);
        }
        worst = std::max(worst, at(x));
      }
    }
    r.bound_v = 2 * worst;
    r.bound_reason =
        "float: twice the largest first-order propagation of eps = 2^-24 through the scaling, "
        "the hidden sums, tanh (at its slope there) and the output sum, over the vectors and a "
        "grid over twice the fitted range (docs/deploy.md)" +
        std::string(ops != nullptr ? "; the play operators' states add 2 eps (X + r_i) to "
                                     "their inputs, never accumulating"
                                   : "");
  }
  // W1 by input, then unit: the step's inner loop runs over the units, contiguously.
  std::vector<double> w1, in_min, in_max;
  for (int i = 0; i < n; ++i)
    for (int h = 0; h < H; ++h) w1.push_back(network.W1()(h, i));
  for (const auto& in : network.inputs()) {
    in_min.push_back(in.min);
    in_max.push_back(in.max);
  }
  auto vec = [](const Eigen::VectorXd& x) { return std::vector<double>(x.data(), x.data() + x.size()); };
  const std::string T = CType(p);
  const std::string comment =
      (ops != nullptr
           ? fmt::format(" * Model: the operator-input network's inverse (kind nn-operators, "
                         "sysid/nn_operators.hpp): x clamped to [{:.9g}, {:.9g}] m,\n"
                         " *   play operators F_ri[x] (r = {} m, from {:.9g} m), then the "
                         "network below on [x, F_r1, ..., F_rm]\n",
                         ops->inverse().network.inputs()[0].min -
                             0.5 * (ops->inverse().network.inputs()[0].max -
                                    ops->inverse().network.inputs()[0].min),
                         ops->inverse().network.inputs()[0].max +
                             0.5 * (ops->inverse().network.inputs()[0].max -
                                    ops->inverse().network.inputs()[0].min),
                         fmt::join(ops->inverse().thresholds, ", "),
                         ops->inverse().initial_input)
           : std::string()) +
      fmt::format(" * Model: the tanh inverse network, {} input(s), {} hidden units "
                  "(sysid/nn.hpp):\n"
                  " *   z_i = 2 (x_i - min_i) / (max_i - min_i) - 1, y = b2 + sum_h w2_h "
                  "tanh(b1_h + sum_i W1_hi z_i),\n"
                  " *   u = u_min + (y + 1) (u_max - u_min) / 2\n"
                  " * Inputs (sample k), in this order:\n{}"
                  " * Output {} [{}], range [{:.9g}, {:.9g}]. Sample time: any ({}).\n",
                  n, H, inputs_text, out.name, out.unit, out.min, out.max,
                  ops != nullptr ? "rate-independent" : "no state") +
      internal::Provenance(provenance, p, r.bound_v, r.bound_reason);
  const std::string state =
      ops != nullptr
          ? Fill("typedef struct {\n  @T@ z[@S@]; /* the play operators' outputs [m] */\n} "
                 "@P@_state;\n",
                 {{"T", CType(p)}, {"S", std::to_string(std::max<size_t>(m, 1))}})
          : "/* A static map: no state (C99 forbids an empty struct). */\n"
            "typedef struct {\n  int unused;\n} @P@_state;\n";
  r.header = Fill(Header(o, comment, state, args, ops != nullptr ? 1 : n, r.bound_v), {{"P", o.prefix}});
  std::string ops_text = "void @P@_init(@P@_state* state) { state->unused = 0; }\n";
  if (ops != nullptr) {
    OperatorNetworkInverseStepper limits(*ops);
    std::vector<double> r_pad = ops->inverse().thresholds;
    r_pad.resize(std::max<size_t>(m, 1), 0.0);
    ops_text = Fill(R"(#define @P@_M @M@
static const @T@ @P@_kR[@S@] = @R@;
static const @T@ @P@_kZ0 = @Z0@;
static const @T@ @P@_kXLo = @LO@;
static const @T@ @P@_kXHi = @HI@;

void @P@_init(@P@_state* state) {
  int i;
  for (i = 0; i < @S@; ++i) state->z[i] = @P@_kZ0;
}
)",
                    {{"M", std::to_string(m)},
                     {"S", std::to_string(std::max<size_t>(m, 1))},
                     {"T", CType(p)},
                     {"R", CArray(r_pad, p)},
                     {"Z0", CLiteral(ops->inverse().initial_input, p)},
                     {"LO", CLiteral(limits.x_min_m(), p)},
                     {"HI", CLiteral(limits.x_max_m(), p)}});
  }
  r.source = Fill(R"(/* @P@.c -- generated by sysid export; see @P@.h. */
#include "@P@.h"

#define @P@_N @N@
#define @P@_H @H@

static const @T@ @P@_kW1[@P@_N * @P@_H] = @W1@; /* W1[h][i] at [i * H + h] */
static const @T@ @P@_kB1[@P@_H] = @B1@;
static const @T@ @P@_kW2[@P@_H] = @W2@;
static const @T@ @P@_kB2 = @B2@;
static const @T@ @P@_kInMin[@P@_N] = @INMIN@;
static const @T@ @P@_kInMax[@P@_N] = @INMAX@;
static const @T@ @P@_kOutMin = @OUTMIN@;
static const @T@ @P@_kOutMax = @OUTMAX@;

@TANH@
@OPS@
/* Each hidden sum b1_h + W1_h1 z_1 + W1_h2 z_2 + ... and the output sum b2 + w2_1 t_1 + ... are
 * added in the library's order; the loops over the units have no dependence between units
 * (a compiler may vectorise them). The first input's products start the sums (a bare copy of
 * b1 would become a call to memcpy). */
@T@ @P@_step(@P@_state* state@ARGS@) {
  @T@ x[@P@_N], z[@P@_N], s[@P@_H];
  @T@ y = @P@_kB2;
  int h, i;
  (void)state;
@COPY@  for (i = 0; i < @P@_N; ++i)
    z[i] = @TWO@ * (x[i] - @P@_kInMin[i]) / (@P@_kInMax[i] - @P@_kInMin[i]) - @ONE@;
  for (h = 0; h < @P@_H; ++h) s[h] = @P@_kB1[h] + @P@_kW1[h] * z[0];
  for (i = 1; i < @P@_N; ++i)
    for (h = 0; h < @P@_H; ++h) s[h] += @P@_kW1[i * @P@_H + h] * z[i];
  for (h = 0; h < @P@_H; ++h) s[h] = @P@_tanh(s[h]);
  for (h = 0; h < @P@_H; ++h) y += @P@_kW2[h] * s[h];
  return @P@_kOutMin + @HALF@ * (y + @ONE@) * (@P@_kOutMax - @P@_kOutMin);
}
)",
                  {{"TANH", internal::CTanh(o.prefix, p)},
                   {"OPS", ops_text},
                   {"COPY", copy},
                   {"P", o.prefix},
                   {"T", T},
                   {"N", std::to_string(n)},
                   {"H", std::to_string(H)},
                   {"W1", CArray(w1, p)},
                   {"B1", CArray(vec(network.b1()), p)},
                   {"W2", CArray(vec(network.w2()), p)},
                   {"B2", CLiteral(network.b2(), p)},
                   {"INMIN", CArray(in_min, p)},
                   {"INMAX", CArray(in_max, p)},
                   {"OUTMIN", CLiteral(out.min, p)},
                   {"OUTMAX", CLiteral(out.max, p)},
                   {"ARGS", args},
                   {"TWO", CLiteral(2.0, p)},
                   {"ONE", CLiteral(1.0, p)},
                   {"HALF", CLiteral(0.5, p)}});
  Finish(&r, o, v, ops != nullptr ? "operator-input network inverse" : "tanh network",
         readme_args, ops != nullptr ? "sample, in order" : "sample");
  return r;
}

}  // namespace

ExportResult ExportNetworkInverse(const NeuralNetwork& network, const ExportVectors& v,
                                  const ExportOptions& o, const ExportProvenance& provenance) {
  return ExportNetworkCore(network, v, o, provenance, nullptr);
}

ExportResult ExportOperatorNetworkInverse(const OperatorNetworkModel& model,
                                          const ExportVectors& v, const ExportOptions& o,
                                          const ExportProvenance& provenance) {
  return ExportNetworkCore(model.inverse().network, v, o, provenance, &model);
}

}  // namespace sysid
