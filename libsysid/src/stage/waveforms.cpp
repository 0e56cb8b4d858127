// Velocity waveforms of the tracking procedures: the paper's test waveforms and the grids.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sysid/stage.hpp"

namespace sysid {
namespace {
constexpr double kPi = 3.14159265358979323846;

std::string MmName(double amplitude_m, double omega) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "sine_A%gmm_w%grad_s", amplitude_m * 1e3, omega);
  return buf;
}
}  // namespace

double VelocityWaveform::Velocity(double t) const {
  double v = 0;
  for (const Term& c : terms)
    v += c.sin_mps * std::sin(c.omega_rad_s * t) + c.cos_mps * std::cos(c.omega_rad_s * t);
  return v;
}

double VelocityWaveform::Position(double t) const {
  double x = 0;
  for (const Term& c : terms)
    x += (c.sin_mps * (1.0 - std::cos(c.omega_rad_s * t)) +
          c.cos_mps * std::sin(c.omega_rad_s * t)) /
         c.omega_rad_s;
  return x;
}

double VelocityWaveform::Acceleration(double t) const {
  double a = 0;
  for (const Term& c : terms)
    a += c.omega_rad_s *
         (c.sin_mps * std::cos(c.omega_rad_s * t) - c.cos_mps * std::sin(c.omega_rad_s * t));
  return a;
}

double VelocityWaveform::PeakVelocity() const {
  double s = 0;
  for (const Term& c : terms) s += std::abs(c.sin_mps) + std::abs(c.cos_mps);
  return s;
}

VelocityWaveform VelocityWaveform::Sine(double amplitude_m, double omega_rad_s) {
  VelocityWaveform w;
  w.name = MmName(amplitude_m, omega_rad_s);
  w.terms = {{omega_rad_s, amplitude_m * omega_rad_s, 0.0}};
  w.period_s = 2 * kPi / omega_rad_s;
  return w;
}

std::vector<VelocityWaveform> PaperTestWaveforms() {
  std::vector<VelocityWaveform> out;
  const struct {
    const char* name;
    double v, w;
  } sines[] = {{"sine_0.016625_1.9", 0.016625, 1.9},
               {"sine_0.0525_6", 0.0525, 6.0},
               {"sine_0.030875_1.9", 0.030875, 1.9},
               {"sine_0.0975_6", 0.0975, 6.0}};
  for (const auto& s : sines) {
    VelocityWaveform w = VelocityWaveform::Sine(s.v / s.w, s.w);
    w.name = s.name;
    out.push_back(w);
  }
  VelocityWaveform tri;
  tri.name = "triangle";  // v = 0.8/pi^2 [cos 2 pi t + cos(6 pi t)/9]
  const double c = 0.8 / (kPi * kPi);
  tri.terms = {{2 * kPi, 0.0, c}, {6 * kPi, 0.0, c / 9}};
  tri.period_s = 1.0;
  out.push_back(tri);
  VelocityWaveform sq;
  sq.name = "square";  // v = 0.248/pi [cos 6t - cos(18t)/3 + cos(30t)/5]
  const double d = 0.248 / kPi;
  sq.terms = {{6.0, 0.0, d}, {18.0, 0.0, -d / 3}, {30.0, 0.0, d / 5}};
  sq.period_s = 2 * kPi / 6.0;
  out.push_back(sq);
  return out;
}

std::vector<VelocityWaveform> TrainingGrid() {
  std::vector<VelocityWaveform> out;
  for (double a : {0.005, 0.010, 0.020})
    for (double w : {1.5, 3.0, 6.0, 10.0})
      if (a * w <= 0.16 + 1e-12) out.push_back(VelocityWaveform::Sine(a, w));
  return out;
}

std::vector<VelocityWaveform> TestGrid() {
  std::vector<VelocityWaveform> w = PaperTestWaveforms();
  w.resize(4);  // the four sinusoids
  return w;
}

}  // namespace sysid
