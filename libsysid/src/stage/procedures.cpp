// The paper's data-collection procedures on the virtual stage: pulse test, tracking sets
// (P-controlled sinusoid grid, one cycle per pair, concatenated in seeded random order) and the
// excitation / reference signals alone for a real rig.
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "core/option_rule.hpp"
#include "core/portable_random.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/stage.hpp"

namespace sysid {
namespace {

std::string Fmt(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

[[noreturn]] void Violated(const char* owner, const std::string& field, double value,
                           const std::string& rule) {
  internal::FailOption(owner, field, value, rule);
}

// Every signal a procedure makes is sized here, so the sample limit is checked before any
// allocation (a rate of 1e12 Hz or 1e9 cycles is refused, not attempted).
long Samples(double seconds, double rate_hz) {
  const double n = seconds * rate_hz;
  if (!(n <= kMaxSignalSamples))
    internal::FailOption(
        "", "signal length",
        Fmt(n) + " samples (" + Fmt(seconds) + " s at " + Fmt(rate_hz) + " Hz)",
        "at most " + Fmt(kMaxSignalSamples) + " samples per signal (shorten it or lower the rate)");
  return static_cast<long>(std::llround(n));
}

const char* kUnits = "t [s], u [V], x [m], v [m/s], a [m/s^2]";

void AddCommonMetadata(Recording& r, const StageParameters& stage, const std::string& procedure,
                       std::uint64_t seed) {
  r.metadata.emplace_back("stage", stage.name);
  r.metadata.emplace_back("procedure", procedure);
  r.metadata.emplace_back("seed", std::to_string(seed));
  // The recording's own rate; the loop's when it runs faster than the recording.
  r.metadata.emplace_back("sample_rate_hz", Fmt(stage.RecordRateHz()));
  if (stage.RecordStride() > 1)
    r.metadata.emplace_back("control_rate_hz", Fmt(stage.rig.sample_rate_hz));
}

// Every stride-th sample of y from 0 (plain sampling, as a real-time logger's downsampling).
Eigen::VectorXd EveryNth(const Eigen::VectorXd& y, long stride) {
  if (stride == 1) return y;
  const Eigen::Index m = (y.size() + stride - 1) / stride;
  Eigen::VectorXd out(m);
  for (Eigen::Index k = 0; k < m; ++k) out[k] = y[k * stride];
  return out;
}

Eigen::VectorXd Segment(const Eigen::VectorXd& y, long from, long to) {
  return y.segment(from, to - from);
}

}  // namespace

std::uint64_t DeriveSeed(std::uint64_t seed, std::uint64_t index) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (index + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// ---- Pulse test --------------------------------------------------------------------------

void PulseProcedure::Validate() const {
  if (amplitudes_v.empty())
    internal::FailOption("PulseProcedure", "amplitudes_v", "empty", "at least one amplitude");
  for (size_t i = 0; i < amplitudes_v.size(); ++i)
    if (!std::isfinite(amplitudes_v[i]) || std::abs(amplitudes_v[i]) > 10.0)
      Violated("PulseProcedure", "amplitudes_v[" + std::to_string(i) + "]", amplitudes_v[i],
               "|amplitude| <= 10 V and finite");
  if (!(on_s > 0) || !std::isfinite(on_s)) Violated("PulseProcedure", "on_s", on_s, "on_s > 0");
  if (!(rest_s >= 0) || !std::isfinite(rest_s))
    Violated("PulseProcedure", "rest_s", rest_s, "rest_s >= 0");
  if (!(lead_s >= 0) || !std::isfinite(lead_s))
    Violated("PulseProcedure", "lead_s", lead_s, "lead_s >= 0");
}

double PulseProcedure::PulseStart(std::size_t i) const {
  return lead_s + static_cast<double>(i) * (on_s + rest_s);
}

Eigen::VectorXd PulseProcedure::Voltage(double rate) const {
  Validate();
  if (!(rate > 0)) Violated("", "sample_rate_hz", rate, "sample_rate_hz > 0");
  // A pulse shorter than a sample, or a whole test of one sample, is no pulse test (excite
  // --rate 1e-300 wrote a header and no row, --on 1e-300 a file of zeros).
  if (Samples(on_s, rate) < 1)
    Violated("PulseProcedure", "on_s", on_s,
             "on_s >= one sample interval 1 / sample_rate_hz = " + Fmt(1 / rate) + " s");
  const long n = Samples(PulseStart(amplitudes_v.size()), rate);
  if (n < 2)
    Violated("", "sample_rate_hz", rate,
             "at least two samples over the test (" + Fmt(PulseStart(amplitudes_v.size())) + " s)");
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  for (size_t i = 0; i < amplitudes_v.size(); ++i) {
    const long k0 = Samples(PulseStart(i), rate);
    const long k1 = std::min(n, k0 + Samples(on_s, rate));
    u.segment(k0, k1 - k0).setConstant(amplitudes_v[i]);
  }
  return u;
}

Recording PulseExcitation(const PulseProcedure& procedure, double rate) {
  const Eigen::VectorXd u = procedure.Voltage(rate);
  Recording r;
  r.source = "pulses";
  r.names = {"t", "u"};
  r.data.resize(u.size(), 2);
  for (Eigen::Index k = 0; k < u.size(); ++k) r.data(k, 0) = static_cast<double>(k) / rate;
  r.data.col(1) = u;
  r.metadata.emplace_back("procedure", "pulse test excitation");
  r.metadata.emplace_back("units", "t [s], u [V]");
  return r;
}

namespace {

// An open-loop run of `u` as a recording t, u, x, v, a (v and a from the encoder's x by
// `derivative`), with the common metadata; the caller adds its procedure's own and finishes
// with FinishOpenLoopRecording.
Recording OpenLoopRecording(const StageParameters& stage, const Eigen::VectorXd& u,
                            std::uint64_t seed, const DerivativeOptions& derivative,
                            const std::string& source, const std::string& procedure,
                            std::string* limits) {
  // The stage runs at the control rate; the recording keeps every stride-th sample.
  const double rate = stage.RecordRateHz();
  const long stride = stage.RecordStride();
  const StageRun run = RunOpenLoop(stage, u, seed);
  const Eigen::VectorXd x = EveryNth(run.x_m, stride);
  Eigen::VectorXd t(x.size());
  for (Eigen::Index k = 0; k < t.size(); ++k) t[k] = static_cast<double>(k) / rate;
  const Derivatives d = Differentiate(x, 1.0 / rate, derivative);
  Recording r;
  r.source = source;
  r.names = {"t", "u", "x", "v", "a"};
  r.data.resize(x.size(), 5);
  r.data << t, EveryNth(run.u_v, stride), x, d.v_mps, d.a_mps2;
  AddCommonMetadata(r, stage, procedure, seed);
  *limits = run.status.Describe();
  return r;
}

void FinishOpenLoopRecording(const DerivativeOptions& derivative, const std::string& limits,
                             Recording* r) {
  r->metadata.emplace_back("derivative", ToString(derivative.method));
  r->metadata.emplace_back("limits", limits);
  r->metadata.emplace_back("units", kUnits);
}

}  // namespace

Recording RunPulseTest(const StageParameters& stage, const PulseProcedure& procedure,
                       std::uint64_t seed, const DerivativeOptions& derivative) {
  stage.Validate();
  derivative.Validate(1.0 / stage.RecordRateHz());
  std::string limits;
  Recording r = OpenLoopRecording(stage, procedure.Voltage(stage.rig.sample_rate_hz), seed,
                                  derivative, "pulses", "pulse test", &limits);
  std::string amps;
  for (double a : procedure.amplitudes_v) amps += (amps.empty() ? "" : " ") + Fmt(a);
  r.metadata.emplace_back("amplitudes_v", amps);
  r.metadata.emplace_back("pulse_on_s", Fmt(procedure.on_s));
  r.metadata.emplace_back("pulse_rest_s", Fmt(procedure.rest_s));
  r.metadata.emplace_back("pulse_lead_s", Fmt(procedure.lead_s));
  FinishOpenLoopRecording(derivative, limits, &r);
  return r;
}

// ---- Triangle (voltage-velocity loop) ----------------------------------------------------

void TriangleProcedure::Validate() const {
  if (!(period_s > 0) || !std::isfinite(period_s))
    Violated("TriangleProcedure", "period_s", period_s, "period_s > 0");
  if (!(peak_forward_v >= 0) || peak_forward_v > 10)
    Violated("TriangleProcedure", "peak_forward_v", peak_forward_v, "0 <= peak_forward_v <= 10");
  if (!(peak_backward_v >= 0) || peak_backward_v > 10)
    Violated("TriangleProcedure", "peak_backward_v", peak_backward_v, "0 <= peak_backward_v <= 10");
  if (cycles < 1 || cycles > 1000)
    Violated("TriangleProcedure", "cycles", cycles, "1 <= cycles <= 1000");
}

Eigen::VectorXd TriangleProcedure::Voltage(double rate) const {
  Validate();
  if (!(rate > 0)) Violated("", "sample_rate_hz", rate, "sample_rate_hz > 0");
  const long n = Samples(cycles * period_s, rate);
  Eigen::VectorXd u(n);
  for (long k = 0; k < n; ++k) {
    const double phase = std::fmod(static_cast<double>(k) / rate, period_s) / period_s;  // [0, 1)
    // Quarters: 0 -> +peak, +peak -> 0, 0 -> -peak, -peak -> 0.
    if (phase < 0.25)
      u[k] = peak_forward_v * phase / 0.25;
    else if (phase < 0.5)
      u[k] = peak_forward_v * (0.5 - phase) / 0.25;
    else if (phase < 0.75)
      u[k] = -peak_backward_v * (phase - 0.5) / 0.25;
    else
      u[k] = -peak_backward_v * (1.0 - phase) / 0.25;
  }
  return u;
}

Recording RunTriangleTest(const StageParameters& stage, const TriangleProcedure& procedure,
                          std::uint64_t seed, const DerivativeOptions& derivative) {
  stage.Validate();
  derivative.Validate(1.0 / stage.RecordRateHz());
  std::string limits;
  Recording r =
      OpenLoopRecording(stage, procedure.Voltage(stage.rig.sample_rate_hz), seed, derivative,
                        "triangle", "open-loop triangle (voltage-velocity loop)", &limits);
  r.metadata.emplace_back("triangle", "period " + Fmt(procedure.period_s) + " s, peaks +" +
                                          Fmt(procedure.peak_forward_v) + " / -" +
                                          Fmt(procedure.peak_backward_v) + " V, " +
                                          std::to_string(procedure.cycles) + " cycle(s)");
  FinishOpenLoopRecording(derivative, limits, &r);
  return r;
}

// ---- Tracking ----------------------------------------------------------------------------

void TrackingProcedure::Validate(const StageParameters& stage) const {
  if (!(kp_v_per_m > 0) || !std::isfinite(kp_v_per_m))
    Violated("TrackingProcedure", "kp_v_per_m", kp_v_per_m, "kp_v_per_m > 0");
  if (lead_cycles < 0)
    Violated("TrackingProcedure", "lead_cycles", lead_cycles, "lead_cycles >= 0");
  if (kept_cycles < 1)
    Violated("TrackingProcedure", "kept_cycles", kept_cycles, "kept_cycles >= 1");
  if (!(tail_s >= 0) || !std::isfinite(tail_s))
    Violated("TrackingProcedure", "tail_s", tail_s, "tail_s >= 0");
  derivative.Validate(1.0 / stage.RecordRateHz());
}

namespace {

void CheckWaveform(const VelocityWaveform& w, const StageParameters& stage) {
  if (w.terms.empty() || !(w.period_s > 0))
    throw OptionsError("waveform '" + w.name + "': needs at least one term and period_s > 0");
  for (const auto& t : w.terms)
    if (!(t.omega_rad_s > 0))
      Violated("", "waveform '" + w.name + "' omega_rad_s", t.omega_rad_s, "omega_rad_s > 0");
  if (w.PeakVelocity() > stage.rig.max_velocity_mps)
    Violated(
        "", "waveform '" + w.name + "' peak velocity [m/s]", w.PeakVelocity(),
        "peak velocity <= the stage's max_velocity_mps (" + Fmt(stage.rig.max_velocity_mps) + ")");
}

struct Tracked {
  Eigen::VectorXd t, u, x, v, a, x_ref, v_ref;
  StageStatus status;
};

Tracked Track(const StageParameters& stage, const VelocityWaveform& w,
              const TrackingProcedure& procedure, std::uint64_t seed) {
  CheckWaveform(w, stage);
  // The P loop runs at the control rate; the recording keeps every stride-th sample (cut
  // points and derivatives at the record rate).
  const double record_rate = stage.RecordRateHz(), rate = stage.rig.sample_rate_hz;
  const long stride = stage.RecordStride();
  const long c0 = Samples(procedure.lead_cycles * w.period_s, record_rate);
  const long c1 =
      Samples((procedure.lead_cycles + procedure.kept_cycles) * w.period_s, record_rate);
  const long recorded = c1 + Samples(procedure.tail_s, record_rate);
  const long n = Samples(static_cast<double>(recorded) / record_rate, rate);
  VirtualStage plant(stage, seed);
  Eigen::VectorXd x(n), u(n), x_ref(n), v_ref(n);
  for (long k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / rate;
    x_ref[k] = w.Position(t);
    v_ref[k] = w.Velocity(t);
    x[k] = plant.measured_position_m();
    u[k] = std::clamp(procedure.kp_v_per_m * (x_ref[k] - x[k]), -stage.rig.dac_range_v,
                      stage.rig.dac_range_v);
    plant.Step(u[k]);
  }
  // Derivatives over the whole run, then the cut: the filter sees real samples on both sides
  // of the cut, so the kept cycle has no end effects.
  const Eigen::VectorXd xr = EveryNth(x, stride);
  const Derivatives d = Differentiate(xr, 1.0 / record_rate, procedure.derivative);
  Tracked out;
  out.t.resize(c1 - c0);
  for (long k = 0; k < c1 - c0; ++k) out.t[k] = static_cast<double>(k) / record_rate;
  out.u = Segment(EveryNth(u, stride), c0, c1);
  out.x = Segment(xr, c0, c1);
  out.v = Segment(d.v_mps, c0, c1);
  out.a = Segment(d.a_mps2, c0, c1);
  out.x_ref = Segment(EveryNth(x_ref, stride), c0, c1);
  out.v_ref = Segment(EveryNth(v_ref, stride), c0, c1);
  out.status = plant.status();
  return out;
}

}  // namespace

Recording TrackWaveform(const StageParameters& stage, const VelocityWaveform& waveform,
                        const TrackingProcedure& procedure, std::uint64_t seed) {
  stage.Validate();
  procedure.Validate(stage);
  const Tracked tr = Track(stage, waveform, procedure, seed);
  Recording r;
  r.source = waveform.name;
  r.names = {"t", "u", "x", "v", "a", "x_ref", "v_ref"};
  r.data.resize(tr.t.size(), 7);
  r.data << tr.t, tr.u, tr.x, tr.v, tr.a, tr.x_ref, tr.v_ref;
  AddCommonMetadata(r, stage, "tracking (P controller), waveform " + waveform.name, seed);
  r.metadata.emplace_back("kp_v_per_m", Fmt(procedure.kp_v_per_m));
  r.metadata.emplace_back("cycles", std::to_string(procedure.kept_cycles) + " kept after " +
                                        std::to_string(procedure.lead_cycles) + " lead-in");
  r.metadata.emplace_back("period_s", Fmt(waveform.period_s));
  r.metadata.emplace_back("derivative", ToString(procedure.derivative.method));
  r.metadata.emplace_back("limits", tr.status.Describe());
  r.metadata.emplace_back("units", std::string(kUnits) + ", x_ref [m], v_ref [m/s]");
  return r;
}

Recording RunTrackingSet(const StageParameters& stage, const std::vector<VelocityWaveform>& grid,
                         const TrackingProcedure& procedure, std::uint64_t seed,
                         const std::string& set_name) {
  stage.Validate();
  procedure.Validate(stage);
  if (grid.empty()) throw OptionsError("RunTrackingSet: the grid is empty");
  std::vector<Tracked> runs;
  for (size_t i = 0; i < grid.size(); ++i)
    runs.push_back(Track(stage, grid[i], procedure, DeriveSeed(seed, i)));
  // Seeded Fisher-Yates (std::shuffle's use of the engine is implementation-defined).
  std::vector<size_t> order(grid.size());
  std::iota(order.begin(), order.end(), size_t{0});
  internal::PortableRandom rng(DeriveSeed(seed, 0xC0FFEE));
  for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng.Index(i)]);

  Eigen::Index rows = 0;
  for (const auto& r : runs) rows += r.t.size();
  Recording rec;
  rec.source = set_name;
  rec.names = {"t", "u", "x", "v", "a"};
  rec.data.resize(rows, 5);
  Eigen::Index at = 0;
  std::string names, limits;
  for (size_t i : order) {
    const Tracked& r = runs[i];
    const Eigen::Index m = r.t.size();
    for (Eigen::Index k = 0; k < m; ++k)
      rec.data(at + k, 0) = static_cast<double>(at + k) / stage.RecordRateHz();
    rec.data.block(at, 1, m, 1) = r.u;
    rec.data.block(at, 2, m, 1) = r.x;
    rec.data.block(at, 3, m, 1) = r.v;
    rec.data.block(at, 4, m, 1) = r.a;
    at += m;
    names += (names.empty() ? "" : " ") + grid[i].name;
    if (r.status.travel_limit_hit || r.status.velocity_limit_exceeded)
      limits += (limits.empty() ? "" : "; ") + grid[i].name + ": " + r.status.Describe();
  }
  AddCommonMetadata(rec, stage, "tracking set '" + set_name + "' (P controller, sinusoid grid)",
                    seed);
  rec.metadata.emplace_back("kp_v_per_m", Fmt(procedure.kp_v_per_m));
  rec.metadata.emplace_back("segments", names);
  rec.metadata.emplace_back("cycles", std::to_string(procedure.kept_cycles) +
                                          " per segment, after " +
                                          std::to_string(procedure.lead_cycles) + " lead-in");
  rec.metadata.emplace_back("derivative", ToString(procedure.derivative.method));
  rec.metadata.emplace_back("limits", limits.empty() ? "none" : limits);
  rec.metadata.emplace_back("units", kUnits);
  return rec;
}

Recording ReferenceSignals(const std::vector<VelocityWaveform>& waveforms,
                           const TrackingProcedure& procedure, double rate) {
  if (!(rate > 0)) Violated("", "sample_rate_hz", rate, "sample_rate_hz > 0");
  if (procedure.kept_cycles < 1 || procedure.lead_cycles < 0)
    throw OptionsError("ReferenceSignals: need kept_cycles >= 1 and lead_cycles >= 0");
  std::vector<std::array<double, 5>> rows;
  long offset = 0;
  for (size_t i = 0; i < waveforms.size(); ++i) {
    const VelocityWaveform& w = waveforms[i];
    const long n = Samples((procedure.lead_cycles + procedure.kept_cycles) * w.period_s, rate);
    (void)Samples(static_cast<double>(offset + n) / rate, rate);  // the whole set, too
    for (long k = 0; k < n; ++k) {
      const double t = static_cast<double>(k) / rate;
      rows.push_back({static_cast<double>(offset + k) / rate, static_cast<double>(i), w.Position(t),
                      w.Velocity(t), w.Acceleration(t)});
    }
    offset += n;
  }
  Recording r;
  r.source = "references";
  r.names = {"t", "waveform", "x_ref", "v_ref", "a_ref"};
  r.data.resize(static_cast<Eigen::Index>(rows.size()), 5);
  for (size_t k = 0; k < rows.size(); ++k)
    for (int c = 0; c < 5; ++c) r.data(static_cast<Eigen::Index>(k), c) = rows[k][c];
  std::string names;
  for (size_t i = 0; i < waveforms.size(); ++i)
    names += (i ? "; " : "") + std::to_string(i) + " = " + waveforms[i].name;
  r.metadata.emplace_back("procedure", "tracking references (each from x = 0 at rest)");
  r.metadata.emplace_back("waveforms", names);
  r.metadata.emplace_back("units", "t [s], x_ref [m], v_ref [m/s], a_ref [m/s^2]");
  return r;
}

}  // namespace sysid
