// The Bouc–Wen benchmark's generator (Noël & Schoukens 2016, BoucWen_ExampleIntegration.m):
// band-limited upsampling, Newmark average acceleration with the trapezoidal rule on z, and
// MATLAB's decimate(..., 'fir').
#include <fmt/format.h>

#include <cmath>
#include <complex>
#include <unsupported/Eigen/FFT>
#include <vector>

#include "hysteresis/bouc_wen_internal.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

namespace sysid {

namespace internal {

std::vector<int> PrimeFactors(int r) {
  std::vector<int> f;
  for (int p = 2; p * p <= r; ++p)
    while (r % p == 0) {
      f.push_back(p);
      r /= p;
    }
  if (r > 1) f.push_back(r);
  return f;
}

double FftWork(Eigen::Index n) {
  double sum = 0;
  Eigen::Index r = n;
  for (Eigen::Index p = 2; p * p <= r; ++p)
    while (r % p == 0) {
      sum += static_cast<double>(p);
      r /= p;
    }
  if (r > 1) sum += static_cast<double>(r);
  return static_cast<double>(n) * sum;
}

void CheckChainWork(Eigen::Index rows, int upsampling, double periods, const char* kind) {
  const double fine = static_cast<double>(rows) * upsampling;
  if (fine * periods > kMaxSignalSamples)
    throw InputError(fmt::format(
        "{}: the benchmark chain on {} samples x upsampling {}{} = {:.4g} fine samples, more "
        "than the {:.0e} it may integrate (sysid::kMaxSignalSamples); lower the upsampling or "
        "shorten the recording",
        kind, rows, upsampling, periods > 1 ? fmt::format(" x {:g} periods", periods) : "",
        fine * periods, kMaxSignalSamples));
  const double work = FftWork(rows * upsampling);
  if (work > kMaxFftWork)
    throw InputError(fmt::format(
        "{}: the benchmark chain's FFT upsampling of {} samples x upsampling {} = {} fine "
        "samples costs {:.3g} operations (the length times the sum of its prime factors), more "
        "than the {:.0e} allowed (kMaxFftWork); choose an upsampling and a length with small "
        "prime factors (the benchmark: 20 = 2 x 2 x 5)",
        kind, rows, upsampling, rows * upsampling, work, kMaxFftWork));
}

void CheckBandLimitedWork(Eigen::Index rows, const char* kind) {
  const double work = FftWork(rows);
  if (work > kMaxFftWork)
    throw InputError(fmt::format(
        "{}: the band-limited input's FFT of {} samples costs {:.3g} operations (the length "
        "times the sum of its prime factors), more than the {:.0e} allowed (kMaxFftWork); use "
        "the linear or held input, or a length with small prime factors",
        kind, rows, work, kMaxFftWork));
}

void NewmarkAdvance(const MechanicalBoucWenParameters& p, double u1, double h, double y0,
                    double v0, double a0, double z0, double f0, Eigen::Index i, double* y1,
                    double* v1, double* a1, double* z1) {
  NewmarkNewton(p, u1, h, y0, v0, a0, z0, f0, y1, z1);
  *v1 = 2 * (*y1 - y0) / h - v0;
  *a1 = 4 * (*y1 - y0 - h * v0) / (h * h) - a0;
  if (!std::isfinite(*y1) || !std::isfinite(*z1))
    throw NumericalError(fmt::format(
        "bouc-wen: the Newmark step {} diverged (y = {}, z = {}): check the parameters", i, *y1,
        *z1));
}

void NewmarkBoucWen(const MechanicalBoucWenParameters& p, const double* u, Eigen::Index n, double h,
                    NewmarkState* s, double* y_out) {
  if (n < 1) return;
  Eigen::Index k0 = 0;
  if (!s->started) {
    s->a = (u[0] - p.c_n_s_per_m * s->v - p.k_n_per_m * s->y - s->z) / p.m_kg;
    s->started = true;
    y_out[0] = s->y;
    k0 = 1;
  }
  for (Eigen::Index i = k0; i < n; ++i) {
    const double y0 = s->y, v0 = s->v, a0 = s->a, z0 = s->z;
    const double f0 = MechanicalRate(p, v0, z0).f;
    double y1 = 0, v1 = 0, a1 = 0, z1 = 0;
    NewmarkAdvance(p, u[i], h, y0, v0, a0, z0, f0, i, &y1, &v1, &a1, &z1);
    s->y = y1;
    s->v = v1;
    s->a = a1;
    s->z = z1;
    y_out[i] = y1;
  }
}

Eigen::Index FirLookahead(const std::vector<int>& factors) {
  Eigen::Index l = 0, rate = 1;
  for (int r : factors) {
    l += 15 * rate;
    rate *= r;
  }
  return l;
}

Eigen::VectorXd DecimateChain(Eigen::VectorXd y, const std::vector<int>& factors) {
  for (int r : factors) y = DecimateFir(y, r);
  return y;
}

Eigen::VectorXd ChainInput(const Eigen::VectorXd& u, int upsampling) {
  const Eigen::VectorXd uf = UpsampleBandLimited(u, upsampling);
  const Eigen::Index nf = uf.size();
  if (nf == 0) return uf;
  // The benchmark integrated one period more than it kept, for the filter's lookahead: the
  // input continues periodically.
  const Eigen::Index total = nf + FirLookahead(PrimeFactors(upsampling));
  Eigen::VectorXd ufx(total);
  for (Eigen::Index i = 0; i < total; ++i) ufx[i] = uf[i % nf];
  return ufx;
}

Eigen::VectorXd ChainOutput(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& ufx,
                            Eigen::Index n, double dt_s, int upsampling) {
  Eigen::VectorXd yf(ufx.size());
  NewmarkState s;
  NewmarkBoucWen(p, ufx.data(), ufx.size(), dt_s / upsampling, &s, yf.data());
  return DecimateChain(std::move(yf), PrimeFactors(upsampling)).head(n);
}

}  // namespace internal

Eigen::VectorXd UpsampleBandLimited(const Eigen::VectorXd& u, int factor) {
  const Eigen::Index n = u.size();
  if (factor < 1) throw OptionsError("UpsampleBandLimited: factor >= 1 is required", "factor");
  if (n < 1 || factor == 1) return u;
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> in(static_cast<size_t>(n)), spectrum;
  for (Eigen::Index i = 0; i < n; ++i) in[static_cast<size_t>(i)] = u[i];
  fft.fwd(spectrum, in);
  const size_t nn = static_cast<size_t>(n), nf = nn * static_cast<size_t>(factor);
  std::vector<std::complex<double>> wide(nf, 0.0), out;
  const size_t half = (nn - 1) / 2;  // lines 1..half on each side
  wide[0] = spectrum[0];
  for (size_t j = 1; j <= half; ++j) {
    wide[j] = spectrum[j];
    wide[nf - j] = spectrum[nn - j];
  }
  if (nn % 2 == 0) {  // the Nyquist line belongs to both sides of the wider spectrum
    wide[nn / 2] = 0.5 * spectrum[nn / 2];
    wide[nf - nn / 2] = 0.5 * spectrum[nn / 2];
  }
  fft.inv(out, wide);  // Eigen scales by 1/nf
  Eigen::VectorXd y(static_cast<Eigen::Index>(nf));
  for (size_t i = 0; i < nf; ++i) y[static_cast<Eigen::Index>(i)] = out[i].real() * factor;
  return y;
}

Eigen::VectorXd DecimateFir(const Eigen::VectorXd& x, int r) {
  if (r < 1) throw OptionsError("DecimateFir: r >= 1 is required", "r");
  if (r == 1) return x;
  constexpr int kOrder = 30;  // MATLAB's default nfilt for 'fir'
  constexpr int kDelay = kOrder / 2;
  // fir1(30, 1/r): the ideal low-pass (cut-off 1/r of Nyquist) under a Hamming window, scaled
  // to unit gain at DC.
  double b[kOrder + 1];
  double sum = 0;
  const double wc = 1.0 / r;
  for (int k = 0; k <= kOrder; ++k) {
    const double m = k - kDelay;
    const double ideal = m == 0 ? wc : std::sin(M_PI * wc * m) / (M_PI * m);
    const double window = 0.54 - 0.46 * std::cos(2 * M_PI * k / kOrder);
    b[k] = ideal * window;
    sum += b[k];
  }
  for (double& v : b) v /= sum;
  const Eigen::Index n = x.size();
  const Eigen::Index nout = (n + r - 1) / r;
  Eigen::VectorXd y(nout);
  for (Eigen::Index j = 0; j < nout; ++j) {
    // filter(b, 1, x) delayed by kDelay, evaluated at sample i = j r: sum_k b_k x[i + kDelay - k]
    const Eigen::Index i = j * r;
    double acc = 0;
    if (i >= kDelay && i + kDelay < n) {
      // Inside: no tap falls off either end (the same sum in the same order, without the tests
      // that made this loop a seventh of a fit's time).
      const double* xi = x.data() + i + kDelay;
      for (int k = 0; k <= kOrder; ++k) acc += b[k] * xi[-k];
    } else {
      for (int k = 0; k <= kOrder; ++k) {
        const Eigen::Index idx = i + kDelay - k;
        if (idx >= 0 && idx < n) acc += b[k] * x[idx];
      }
    }
    y[j] = acc;
  }
  return y;
}

}  // namespace sysid
