#include "paper/f4_paper_gains.hpp"

namespace sysid::paper {

bool PaperGainsMet(const PaperGainsFact::Row& row, const FactsOptions& options) {
  return row.ripple_m <= options.ripple_tolerance_m && row.clipped_samples == 0 &&
         row.motion_ripple_m <= options.motion_ripple_tolerance_m;
}

PaperGainsFact CheckPaperGains(Experiments& experiments) {
  experiments.Track(false);
  const FactsOptions& o = experiments.options();
  PaperGainsFact f;
  f.met = true;
  for (double hz : o.track_frequencies_hz) {
    const TrackingRun& run = experiments.Run(hz, FeedforwardScheme::kNone);
    PaperGainsFact::Row row;
    row.frequency_hz = hz;
    row.ripple_m = run.ripple_m;
    row.motion_ripple_m = run.motion_ripple_m;
    row.ringing_hz = run.ringing_hz;
    row.clipped_samples = run.saturated_samples;
    row.max_abs_u_v = run.max_abs_u_v;
    row.quiet = row.motion_ripple_m <= o.motion_ripple_tolerance_m;
    f.met = f.met && PaperGainsMet(row, o);
    f.rows.push_back(row);
  }
  return f;
}

}  // namespace sysid::paper
