#include <catch2/catch.hpp>
#include <cmath>

#include "sysid/compare_hysteresis.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/nn_operators.hpp"

namespace {

// A recording of a PI hysteresis (the truth the networks must learn), 200 Hz.
sysid::Recording HysteresisRecording(int n) {
  sysid::PiParameters p;
  p.thresholds = {0.4, 0.8, 1.2};
  p.weights = {3e-6, 2e-6, 1e-6};
  p.polynomial = {2e-6};
  p.input_min_v = 0;
  p.input_max_v = 3.6;
  const sysid::PrandtlIshlinskiiModel m(p);
  Eigen::VectorXd u(n);
  for (int k = 0; k < n; ++k)
    u[k] = 1.8 + 1.6 * std::sin(2 * M_PI * k / 300.0) * (0.55 + 0.45 * std::cos(2 * M_PI * k / n));
  const Eigen::VectorXd x = m.Simulate(u, 5e-3);
  sysid::Recording rec;
  rec.source = "pi.csv";
  rec.names = {"t", "u", "x"};
  rec.data.resize(n, 3);
  for (int k = 0; k < n; ++k) rec.data.row(k) << k * 5e-3, u[k], x[k];
  return rec;
}

double Rms(const Eigen::VectorXd& e) { return std::sqrt(e.squaredNorm() / static_cast<double>(e.size())); }

}  // namespace

TEST_CASE("operator-input network features are the play operators of its input", "[nn]") {
  sysid::OperatorNetworkSide side;
  side.thresholds = {0.5, 1.0};
  side.initial_input = 0.2;
  Eigen::VectorXd u(5);
  u << 0, 1, 2, 1, 0;
  const Eigen::MatrixXd X = side.Features(u);
  CHECK(X.col(0) == u);
  CHECK(Eigen::VectorXd(X.col(1)) == sysid::PlayOperator(u, 0.5, 0.2));
  CHECK(Eigen::VectorXd(X.col(2)) == sysid::PlayOperator(u, 1.0, 0.2));
}

TEST_CASE("play-operator inputs let the network learn a loop the static network cannot",
          "[nn]") {
  const sysid::Recording rec = HysteresisRecording(1500);
  sysid::OperatorNetworkOptions o;
  o.hidden = 6;
  o.max_epochs = 150;
  o.restarts = 1;
  o.operators = 0;
  sysid::HysteresisFitSummary s0, s4;
  const auto flat = sysid::FitOperatorNetwork({rec}, o, &s0);
  o.operators = 4;
  const auto loop = sysid::FitOperatorNetwork({rec}, o, &s4);
  const Eigen::VectorXd u = rec.column("u"), x = rec.column("x");
  const double e0 = Rms(flat->Simulate(u, 5e-3) - x), e4 = Rms(loop->Simulate(u, 5e-3) - x);
  // A static map u -> x cannot follow a loop: its error is at least the loop's half-width
  // (about w * r = 1e-6 m here); the operators carry the memory and cut it by > 5x.
  CHECK(e0 > 5e-7);
  CHECK(e4 < e0 / 5);
  CHECK(s4.training_rms == Approx(e4));
  // The directly identified inverse tracks the recorded input.
  CHECK(Rms(loop->Invert(x, 5e-3) - u) < Rms(flat->Invert(x, 5e-3) - u));
  // The file round-trips.
  const auto back = sysid::OperatorNetworkFromJson(loop->ToJson(), "n.json");
  CHECK((back->Simulate(u, 5e-3) - loop->Simulate(u, 5e-3)).cwiseAbs().maxCoeff() < 1e-18);
  Eigen::VectorXd far = x;
  far[7] = 1.0;  // 1 m, far outside the training range
  CHECK_THROWS_WITH(loop->Invert(far, 5e-3), Catch::Contains("reference sample 7"));
  far[7] = NAN;  // not "outside the range": not a number (Python can pass one)
  CHECK_THROWS_WITH(loop->Invert(far, 5e-3), Catch::Contains("reference sample 7: x = nan: "
                                                             "expected a finite number"));
}

TEST_CASE("operator network options name the field", "[nn]") {
  sysid::OperatorNetworkOptions o;
  o.operators = 201;
  CHECK_THROWS_WITH(o.Validate(), Catch::Contains("operators"));
  o.operators = 2;
  o.hidden = 0;
  CHECK_THROWS_WITH(o.Validate(), Catch::Contains("hidden"));
}

TEST_CASE("an nn-operators fit past the memory limit is refused before it allocates", "[nn]") {
  // Both options within their own bounds, but 200 operators on 1e6 samples need two
  // 1e6 x 201 feature matrices (3.2 GB, the dataset and its normalised copy) plus one being
  // copied in: about 4.8 GB, past kTrainingMemoryLimitBytes (4 GB). It used to end in
  // std::bad_alloc (or take the memory); now it is an OptionsError naming `operators`.
  sysid::Recording rec;
  rec.source = "long.csv";
  rec.names = {"t", "u", "x"};
  rec.data.setZero(1000000, 3);
  sysid::OperatorNetworkOptions o;
  o.operators = sysid::kMaxPlayOperators;
  o.hidden = 1;
  try {
    sysid::FitOperatorNetwork({rec}, o);
    FAIL("expected an OptionsError");
  } catch (const sysid::OptionsError& e) {
    CHECK(e.field() == "operators");
    CHECK_THAT(e.what(), Catch::Contains("OperatorNetworkOptions::operators = 200") &&
                             Catch::Contains("1000000 samples") && Catch::Contains("GB"));
  }
  // 200 hidden units on 201 inputs: 40601 weights a network, so LM's two P x P matrices alone
  // are 16 * 40601^2 B = 26 GB whatever the length; the dominant term names `hidden`.
  rec.data.conservativeResize(50, 3);
  o.hidden = 200;
  try {
    sysid::FitOperatorNetwork({rec}, o);
    FAIL("expected an OptionsError");
  } catch (const sysid::OptionsError& e) {
    CHECK(e.field() == "hidden");
    CHECK_THAT(e.what(), Catch::Contains("40601 weights"));
  }
}

TEST_CASE("HysteresisFitOptions::Validate checks the nn-operators network's fields", "[nn]") {
  // So a caller validating before reading recordings (the CLI) refuses --hidden at once.
  sysid::HysteresisFitOptions o;
  o.network.hidden = 1000000000;
  CHECK_THROWS_WITH(o.Validate("nn-operators"), Catch::Contains("hidden = 1000000000"));
  CHECK_NOTHROW(o.Validate("pi"));  // the PI family ignores the network's options
  o.network.hidden = 10;
  o.operators = 1000000000;
  CHECK_THROWS_WITH(o.Validate("nn-operators"), Catch::Contains("operators = 1000000000"));
}
