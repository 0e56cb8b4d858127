// The tracking experiment's scheme loop (TrackSchemes) against the loop written out by hand:
// the same plant and noise for every scheme, the feedforward the inverse model's voltages.
#include <catch2/catch.hpp>

#include "sysid/compare.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/model.hpp"
#include "sysid/stage.hpp"

using namespace sysid;

TEST_CASE("feedforward scheme names round-trip, unknown names are refused", "[control]") {
  for (auto s : {FeedforwardScheme::kNone, FeedforwardScheme::kAnalytic,
                 FeedforwardScheme::kNetwork})
    CHECK(ParseFeedforwardScheme(ToString(s)) == s);
  CHECK(ToString(FeedforwardScheme::kNetwork) == "nn");
  CHECK_THROWS_WITH(ParseFeedforwardScheme("pid"),
                    Catch::Contains("'pid' is not one of none, analytic, nn"));
}

TEST_CASE("TrackSchemes equals the hand-written loop, scheme by scheme", "[control][stage]") {
  const StageParameters stage = StageParameters::Default();
  SmoothProfileOptions p;
  p.frequency_hz = 2.0;  // 0.5 s: short
  p.cycles = 1;
  p.sample_rate_hz = stage.rig.sample_rate_hz;
  const PositionReference ref = MakeSmoothProfile(p);
  const FrictionModel model = FrictionModel::Paper();
  const std::uint64_t seed = 3;
  std::vector<FeedforwardScheme> seen;
  const auto runs = TrackSchemes(
      stage, seed, ref, PiOptions{}, {FeedforwardScheme::kNone, FeedforwardScheme::kAnalytic},
      {&model, nullptr}, [&](FeedforwardScheme s, std::size_t i) {
        CHECK(i == seen.size());
        seen.push_back(s);
      });
  REQUIRE(runs.size() == 2);
  CHECK(seen == std::vector<FeedforwardScheme>{FeedforwardScheme::kNone,
                                               FeedforwardScheme::kAnalytic});
  // The reference loop: a fresh stage per scheme, the analytic inverse played back.
  PiOptions pi;
  pi.sample_time_s = stage.sample_time_s();
  VirtualStage plain(stage, seed);
  const TrackingResult none = RunClosedLoop(plain, ref, pi);
  VirtualStage with_ff(stage, seed);
  const TrackingResult analytic = RunClosedLoop(
      with_ff, ref, pi,
      SampledFeedforward(AnalyticInverse(model, stage.sample_time_s(), ref.v_mps, ref.a_mps2)));
  CHECK(runs[0].scheme == FeedforwardScheme::kNone);
  CHECK(runs[0].result.e_m == none.e_m);
  CHECK(runs[0].result.u_v == none.u_v);
  CHECK(runs[0].stage_limits == plain.status().Describe());
  CHECK(runs[1].scheme == FeedforwardScheme::kAnalytic);
  CHECK(runs[1].result.e_m == analytic.e_m);
  CHECK(runs[1].result.u_ff_v == analytic.u_ff_v);
  CHECK(runs[1].result.u_ff_v.cwiseAbs().maxCoeff() > 0);  // the feedforward did play
  // A scheme without its model is an options error, not a crash.
  CHECK_THROWS_AS(TrackSchemes(stage, seed, ref, PiOptions{}, {FeedforwardScheme::kNetwork}, {}),
                  OptionsError);
}
