// The reported standard errors of the pulse and trajectory least squares against the spread of
// the estimates over many noise seeds (Monte-Carlo), and the trajectory fit's delta method
// against a finite-difference Jacobian of theta -> (1/theta_0, theta_i/theta_0).
//
// Agreement criterion: the sample standard deviation of N estimates has a relative sampling
// error of about 1/sqrt(2 (N - 1)); the reported standard error (root-mean-square over the
// seeds) must lie within 4 of those sampling errors of the Monte-Carlo spread (N = 400:
// 3.5 % each, so +-15 %). A covariance that is wrong by a factor (raw coefficients instead of the
// delta method: 200-460x; a missing s^2; a wrong degrees-of-freedom count far from n) fails.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "identify/simulated_recording.hpp"
#include "identify/synthetic_motion.hpp"
#include "support/test_support.hpp"
#include "sysid/identify.hpp"

namespace {

constexpr int kSeeds = 400;
// 4 sampling errors of a standard deviation from kSeeds samples.
const double kAgreement = 4.0 / std::sqrt(2.0 * (kSeeds - 1));

struct Spread {
  std::vector<double> sum, sum2, se2;
  explicit Spread(size_t p) : sum(p, 0.0), sum2(p, 0.0), se2(p, 0.0) {}
  void Add(const Eigen::VectorXd& estimate, const Eigen::VectorXd& std_error) {
    for (size_t i = 0; i < sum.size(); ++i) {
      const auto j = static_cast<Eigen::Index>(i);
      sum[i] += estimate[j];
      sum2[i] += estimate[j] * estimate[j];
      se2[i] += std_error[j] * std_error[j];
    }
  }
  double Mean(size_t i, int n) const { return sum[i] / n; }
  double Sd(size_t i, int n) const {
    const double mean = sum[i] / n;
    return std::sqrt(std::max(0.0, (sum2[i] - n * mean * mean) / (n - 1)));
  }
  double ReportedSe(size_t i, int n) const { return std::sqrt(se2[i] / n); }
};

}  // namespace

TEST_CASE("pulse least squares: standard errors match the Monte-Carlo spread over 400 seeds",
          "[identify][pulse][uncertainty]") {
  // The paper's ten pulse amplitudes on the paper's model; each plateau velocity read with
  // noise of about 0.5 mm/s (1 % of the plateaus, a rig's plateau scatter), scaled per direction
  // so that the equation a1 v + a2 = a3 u has the same error variance (0.05 m/s^2)^2 in both:
  // the least squares' own model, one variance pooled over both directions.
  const auto table = sysid::ReadPulseTable(sysid::test::SourcePath("datasets/paper/pulse_table.csv"));
  const auto truth = sysid::test::MakeModel(104.0154, 117.1441, 3.1023, 6.8216, 6.0, 0.0);
  const double sigma_eq = 0.05;  // [m/s^2]
  std::mt19937 rng(2024);
  std::normal_distribution<double> noise(0.0, 1.0);
  Spread s(4);
  for (int seed = 0; seed < kSeeds; ++seed) {
    std::vector<sysid::PulsePoint> pts;
    for (const auto& p : table) {
      const double a1 = p.u_v > 0 ? truth.a1p : truth.a1n;
      pts.push_back({p.u_v, truth.SteadyVelocity(p.u_v) + sigma_eq / a1 * noise(rng), ""});
    }
    const auto r = sysid::FitPulseTable(pts, {truth.a3});
    Eigen::VectorXd est(4);
    est << r.model.a1p, r.model.a2p, r.model.a1n, r.model.a2n;  // theta's order
    s.Add(est, r.fit.std_error);
  }
  const char* names[] = {"a1p", "a2p", "a1n", "a2n"};
  const double truth_values[] = {truth.a1p, truth.a2p, truth.a1n, truth.a2n};
  for (size_t i = 0; i < 4; ++i) {
    INFO(names[i] << ": Monte-Carlo sd " << s.Sd(i, kSeeds) << ", reported "
                  << s.ReportedSe(i, kSeeds) << ", agreement +-" << kAgreement);
    CHECK(s.ReportedSe(i, kSeeds) / s.Sd(i, kSeeds) == Approx(1.0).margin(kAgreement));
    // Unbiased to first order (the errors in v are 3 % of the plateaus' spread): the mean lies
    // within 4 standard errors of the mean of the truth.
    CHECK(std::abs(s.Mean(i, kSeeds) - truth_values[i]) <= 4 * s.Sd(i, kSeeds) / std::sqrt(kSeeds));
  }
}

namespace {

// theta -> (1/theta_0, theta_1/theta_0, ...): u = (1/a3) a + (a1/a3) v(t-tau) + (a2/a3) sgn v,
// so the column coefficients are the physical parameters divided by a3 (written from the model
// equation, not from the library).
Eigen::VectorXd Physical(const Eigen::VectorXd& theta) {
  Eigen::VectorXd p(theta.size());
  p[0] = 1 / theta[0];
  for (Eigen::Index i = 1; i < theta.size(); ++i) p[i] = theta[i] / theta[0];
  return p;
}

}  // namespace

namespace {

// A paper-like stage moved by two sines; 0.1 V voltage noise, far above the filter's
// deterministic misfit (x is exact, unquantised and the same at every seed: only the noise in u
// differs between runs, as ordinary least squares assumes). 4 s at 1 kHz.
struct TrajectoryCase {
  sysid::FrictionModel truth =
      sysid::test::MakeModel(104.0154, 117.1441, 3.1023, 6.8216, 6.0, 0.0035);
  std::vector<sysid::test::Sine> motion{{0.01, 0.8, 0.0}, {0.002, 4.3, 1.0}};
  double sigma_u = 0.1;   // [V]
  double duration = 4.0;  // [s]
  sysid::TrajectoryOptions Options() const {
    sysid::TrajectoryOptions o;
    o.tau_s = truth.tau_s;
    return o;
  }
  sysid::Recording Recording(unsigned seed) const {
    return sysid::test::ClosedFormRecording(truth, motion, duration, 1000.0, 0.0, sigma_u, seed);
  }
};

}  // namespace

TEST_CASE("trajectory least squares: the delta method against a finite-difference Jacobian",
          "[identify][trajectory][uncertainty]") {
  const TrajectoryCase c;
  {
    // The delta method against a central-difference Jacobian of the map: step 1e-6 relative,
    // truncation error ~1e-12 and rounding ~1e-10 relative, so agreement to 1e-7.
    const auto r = sysid::IdentifyFromTrajectory({c.Recording(1)}, c.Options());
    REQUIRE(r.names == std::vector<std::string>{"a3", "a1p", "a1n", "a2p", "a2n"});
    const Eigen::VectorXd& theta = r.fit.theta;
    const Eigen::Index p = theta.size();
    Eigen::MatrixXd J(p, p);
    for (Eigen::Index j = 0; j < p; ++j) {
      const double step = 1e-6 * std::abs(theta[j]);
      Eigen::VectorXd hi = theta, lo = theta;
      hi[j] += step;
      lo[j] -= step;
      J.col(j) = (Physical(hi) - Physical(lo)) / (2 * step);
    }
    const Eigen::MatrixXd cov = J * r.fit.covariance * J.transpose();
    CHECK((Physical(theta) - r.estimate).cwiseAbs().maxCoeff() <=
          1e-12 * r.estimate.cwiseAbs().maxCoeff());  // the same map, rounding only
    for (Eigen::Index i = 0; i < p; ++i) {
      INFO(r.names[static_cast<size_t>(i)]);
      CHECK(r.std_error[i] == Approx(std::sqrt(cov(i, i))).epsilon(1e-7));
      for (Eigen::Index j = 0; j < p; ++j)
        CHECK(r.covariance(i, j) ==
              Approx(cov(i, j)).epsilon(1e-7).margin(1e-7 * std::sqrt(cov(i, i) * cov(j, j))));
    }
  }
}

TEST_CASE("trajectory least squares: delta-method standard errors match the Monte-Carlo spread "
          "over 400 seeds",
          "[identify][trajectory][uncertainty]") {
  const TrajectoryCase c;
  const sysid::FrictionModel& truth = c.truth;
  Spread s(5);
  for (int seed = 0; seed < kSeeds; ++seed) {
    const auto r = sysid::IdentifyFromTrajectory(
        {c.Recording(1000u + static_cast<unsigned>(seed))}, c.Options());
    s.Add(r.estimate, r.std_error);
  }
  const double truth_values[] = {truth.a3, truth.a1p, truth.a1n, truth.a2p, truth.a2n};
  const char* names[] = {"a3", "a1p", "a1n", "a2p", "a2n"};
  for (size_t i = 0; i < 5; ++i) {
    INFO(names[i] << ": Monte-Carlo sd " << s.Sd(i, kSeeds) << ", reported "
                  << s.ReportedSe(i, kSeeds) << ", mean " << s.Mean(i, kSeeds) << ", truth "
                  << truth_values[i] << ", agreement +-" << kAgreement);
    CHECK(s.ReportedSe(i, kSeeds) / s.Sd(i, kSeeds) == Approx(1.0).margin(kAgreement));
  }
}
