// Butterworth low-pass as second-order sections (bilinear transform with pre-warping) and
// zero-phase forward-backward filtering. Debian ships no maintained C++ IIR design library
// (no libiir/DSPFilters package in bookworm), so the design is written out here and tested
// against the closed-form |H|^2 and SciPy's coefficients.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "signal/checks.hpp"
#include "signal/filters.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

namespace sysid {
namespace internal {

std::vector<Biquad> DesignButterworthLowPass(int order, double normalized_cutoff) {
  SYSID_CHECK(order >= 1 && normalized_cutoff > 0 && normalized_cutoff < 0.5,
              "Butterworth design needs order >= 1 and 0 < f_c/f_s < 0.5");
  const double pi = std::acos(-1.0);
  // Pre-warped analog cut-off for the bilinear map s = (z - 1)/(z + 1): the digital response
  // then equals the analog one at w = 2 atan(K), so |H|^2 = 1/(1 + (tan(w/2)/K)^(2N)).
  const double k_warp = std::tan(pi * normalized_cutoff);
  std::vector<Biquad> sections;
  if (order % 2 == 1) {
    // Real prototype pole at s = -1.
    const double z = (1 - k_warp) / (1 + k_warp);
    Biquad s;
    s.a1 = -z;
    s.b0 = s.b1 = (1 + s.a1) / 2;  // zero at z = -1, unit gain at DC
    sections.push_back(s);
  }
  // Prototype poles p_k = exp(j pi (2k + N + 1) / (2N)), k = 0 .. N/2 - 1 (one of each pair);
  // k = 0 lies nearest the imaginary axis (highest Q), so walk k downwards.
  for (int k = order / 2 - 1; k >= 0; --k) {
    const std::complex<double> p = std::polar(1.0, pi * (2.0 * k + order + 1) / (2.0 * order));
    const std::complex<double> z = (1.0 + k_warp * p) / (1.0 - k_warp * p);
    Biquad s;
    s.a1 = -2 * z.real();
    s.a2 = std::norm(z);
    const double g = (1 + s.a1 + s.a2) / 4;  // double zero at z = -1, unit gain at DC
    s.b0 = g;
    s.b1 = 2 * g;
    s.b2 = g;
    sections.push_back(s);
  }
  return sections;
}

std::complex<double> FrequencyResponse(const std::vector<Biquad>& sections, double omega) {
  const std::complex<double> z1 = std::polar(1.0, -omega);
  const std::complex<double> z2 = z1 * z1;
  std::complex<double> h = 1.0;
  for (const Biquad& s : sections)
    h *= (s.b0 + s.b1 * z1 + s.b2 * z2) / (1.0 + s.a1 * z1 + s.a2 * z2);
  return h;
}

int FiltFiltPadLength(const std::vector<Biquad>& sections) {
  const int first_order = static_cast<int>(std::count_if(
      sections.begin(), sections.end(), [](const Biquad& s) { return s.first_order(); }));
  return 3 * (2 * static_cast<int>(sections.size()) + 1 - first_order);
}

namespace {

// Transposed direct form II, starting from the steady state the cascade would reach after an
// input held at y[0] forever: a signal that starts at a constant level has no start-up
// transient. All sections advance together sample by sample: section j of sample k+1 does not
// wait for section j+1 of sample k, which gives the CPU independent work to overlap.
void FilterInPlace(const std::vector<Biquad>& sections, Eigen::VectorXd& y) {
  const size_t m = sections.size();
  std::vector<double> z1(m), z2(m);
  double level = y.size() > 0 ? y[0] : 0.0;
  for (size_t j = 0; j < m; ++j) {
    const Biquad& s = sections[j];
    const double gain = (s.b0 + s.b1 + s.b2) / (1 + s.a1 + s.a2);
    z1[j] = level * (gain - s.b0);
    z2[j] = level * (s.b2 - s.a2 * gain);
    level *= gain;
  }
  for (Eigen::Index k = 0; k < y.size(); ++k) {
    double x = y[k];
    for (size_t j = 0; j < m; ++j) {
      const Biquad& s = sections[j];
      const double out = s.b0 * x + z1[j];
      z1[j] = s.b1 * x - s.a1 * out + z2[j];
      z2[j] = s.b2 * x - s.a2 * out;
      x = out;
    }
    y[k] = x;
  }
}

}  // namespace

Eigen::VectorXd FiltFilt(const std::vector<Biquad>& sections, const Eigen::VectorXd& y) {
  const Eigen::Index n = y.size();
  const Eigen::Index pad = FiltFiltPadLength(sections);
  SYSID_CHECK(n > pad, "FiltFilt needs more samples than the padding");
  // Odd reflection about the end points keeps value and slope continuous there, so the
  // padding carries the signal's trend instead of a step into the filter.
  Eigen::VectorXd ext(n + 2 * pad);
  for (Eigen::Index i = 0; i < pad; ++i) {
    ext[i] = 2 * y[0] - y[pad - i];
    ext[pad + n + i] = 2 * y[n - 1] - y[n - 2 - i];
  }
  ext.segment(pad, n) = y;
  FilterInPlace(sections, ext);
  ext.reverseInPlace();
  FilterInPlace(sections, ext);
  ext.reverseInPlace();
  return ext.segment(pad, n);
}

}  // namespace internal

Eigen::VectorXd ButterworthFiltFilt(const Eigen::VectorXd& y, double dt_s, double cutoff_hz,
                                    int order) {
  constexpr const char* kWhere = "ButterworthFiltFilt";
  internal::CheckSampleInterval(kWhere, dt_s);
  internal::CheckCutoff(kWhere, "cutoff_hz", cutoff_hz, dt_s);
  internal::CheckButterworthOrder(kWhere, "order", order);
  internal::CheckFinite(kWhere, y);
  const auto sections = internal::DesignButterworthLowPass(order, cutoff_hz * dt_s);
  internal::CheckLength(
      kWhere, y.size(), internal::FiltFiltPadLength(sections) + 1,
      "the order-" + std::to_string(order) + " forward-backward Butterworth (its end padding)");
  Eigen::VectorXd out = internal::FiltFilt(sections, y);
  // A cut-off far below the sample rate (1e-10 Hz at 1 kHz) leaves sections whose poles round
  // to 1 and whose gains underflow: the output is NaN. Said here, with the cure, rather than as
  // a NaN sample in whatever differentiates the output next.
  if (!out.allFinite())
    throw NumericalError(fmt::format(
        "{}: cutoff_hz = {:g} Hz is {:.3g} of the Nyquist frequency {:g} Hz: the order-{} "
        "filter is numerically unstable there (its output is not finite); raise the cut-off",
        kWhere, cutoff_hz, cutoff_hz * 2 * dt_s, 0.5 / dt_s, order));
  return out;
}

}  // namespace sysid
