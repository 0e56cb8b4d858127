#include "paper/f5_tracking.hpp"

#include "paper/paper_numbers.hpp"

namespace sysid::paper {

bool WithinTrackingFactor(double s, double p) {
  return s <= kTrackingFactor * p && s >= p / kTrackingFactor;
}

bool TrackingOrderMet(double none_m, double analytic_m, double nn_m, double paper_none_m,
                      double paper_analytic_m, double paper_nn_m) {
  return none_m > analytic_m && analytic_m > nn_m && WithinTrackingFactor(none_m, paper_none_m) &&
         WithinTrackingFactor(analytic_m, paper_analytic_m) &&
         WithinTrackingFactor(nn_m, paper_nn_m);
}

TrackingFact CheckTracking(Experiments& experiments) {
  experiments.Track(true);
  const FactsOptions& o = experiments.options();
  TrackingFact f;
  f.met = true;
  for (double hz : o.track_frequencies_hz) {
    TrackingFact::Row row;
    row.frequency_hz = hz;
    row.none_m = experiments.Run(hz, FeedforwardScheme::kNone).max_error_m;
    row.analytic_m = experiments.Run(hz, FeedforwardScheme::kAnalytic).max_error_m;
    row.nn_m = experiments.Run(hz, FeedforwardScheme::kNetwork).max_error_m;
    row.paper_none_m = TrackingMaxErrorM(hz, FeedforwardScheme::kNone);
    row.paper_analytic_m = TrackingMaxErrorM(hz, FeedforwardScheme::kAnalytic);
    row.paper_nn_m = TrackingMaxErrorM(hz, FeedforwardScheme::kNetwork);
    // A frequency the paper did not measure has no table entry: not met.
    f.met = f.met && TrackingOrderMet(row.none_m, row.analytic_m, row.nn_m, row.paper_none_m,
                                      row.paper_analytic_m, row.paper_nn_m);
    f.rows.push_back(row);
  }
  if (o.network_initializations > 1) {
    const auto errors = experiments.NetworkSpread();
    for (std::size_t i = 0; i < errors.size(); ++i) {
      TrackingFact::Spread s{f.rows[i].frequency_hz, errors[i], 0};
      for (double e : errors[i]) s.beats_analytic += e < f.rows[i].analytic_m;
      f.spread.push_back(s);
    }
  }
  return f;
}

}  // namespace sysid::paper
