// A batch chunk reuses one RecordingReader and one DominanceWorkspace over its recordings: the
// results must be those of fresh, one-recording calls, bit for bit, whatever came before
// (longer and shorter recordings, different moving-sample counts, a failing one, candidates).
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "identify/simulated_recording.hpp"
#include "identify/synthetic_motion.hpp"
#include "support/test_support.hpp"
#include "sysid/dominance.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

using sysid::test::ClosedFormRecording;
using sysid::test::MakeModel;

namespace {

void CheckSameStats(const std::vector<sysid::TermStats>& a,
                    const std::vector<sysid::TermStats>& b) {
  REQUIRE(a.size() == b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    INFO(a[i].name);
    CHECK(a[i].name == b[i].name);
    // Exact: the reused path must do the same arithmetic, not merely close arithmetic.
    CHECK(a[i].rms == b[i].rms);
    CHECK(a[i].peak == b[i].peak);
    CHECK(a[i].ratio_to_top == b[i].ratio_to_top);
    CHECK(a[i].ratio_bound == b[i].ratio_bound);
    CHECK(a[i].ratio_max == b[i].ratio_max);
    CHECK(a[i].negligible == b[i].negligible);
  }
}

void CheckSame(const sysid::DominanceResult& a, const sysid::DominanceResult& b) {
  CHECK(a.source == b.source);
  CHECK(a.samples == b.samples);
  CHECK(a.moving_samples == b.moving_samples);
  CHECK(a.dominant == b.dominant);
  CHECK(a.margin == b.margin);
  CHECK(a.peak_ratio == b.peak_ratio);
  CHECK(a.pointwise_ratio_quantile == b.pointwise_ratio_quantile);
  CHECK(a.pointwise_ratio_max == b.pointwise_ratio_max);
  CheckSameStats(a.terms, b.terms);
  CheckSameStats(a.ranking, b.ranking);
}

}  // namespace

TEST_CASE("a reused reader and dominance workspace give the fresh calls' results exactly",
          "[dominance]") {
  const auto m = MakeModel(50.0, 40.0, 2.0, 2.5, 6.0, 0.0007);
  // Lengths and motions vary (long, short, long again, a stage at rest that fails in between):
  // a stale prefix or a kept size would show.
  std::vector<sysid::Recording> recs{
      ClosedFormRecording(m, {{0.01, 0.5, 0.0}}, 4.0, 1000.0, 1e-7, 0.01, 1),
      ClosedFormRecording(m, {{0.001, 20.0, 0.3}, {0.002, 1.0, 0.0}}, 0.5, 2000.0, 1e-7, 0, 2),
      ClosedFormRecording(m, {{0.0, 1.0, 0.0}}, 0.5, 1000.0, 0, 0, 3),  // never moves
      ClosedFormRecording(m, {{0.005, 2.0, 1.0}}, 3.0, 1000.0, 1e-7, 0.01, 4)};
  for (size_t i = 0; i < recs.size(); ++i) recs[i].source = "rec" + std::to_string(i) + ".csv";
  sysid::test::TempDir dir;
  std::vector<std::string> paths;
  for (const auto& r : recs) {
    paths.push_back(dir / r.source);
    sysid::WriteRecording(paths.back(), r);
  }
  paths.insert(paths.begin() + 2, dir / "bad.csv");  // a reader error in between
  sysid::test::WriteText(paths[2], "t,u,x\n0,1,2\n0.001,abc,2\n");

  for (const bool with_candidate : {false, true}) {
    sysid::DominanceOptions o;
    if (with_candidate) o.candidates = {{"drive", "u", 3.0}};
    sysid::RecordingReader reader;
    sysid::DominanceWorkspace workspace;
    for (int pass = 0; pass < 2; ++pass) {
      for (const auto& path : paths) {
        INFO(path << " pass " << pass << " candidate " << with_candidate);
        sysid::Recording fresh;
        try {
          fresh = sysid::ReadRecording(path);
        } catch (const sysid::InputError& e) {
          CHECK_THROWS_WITH(reader.Read(path), e.what());
          continue;
        }
        const sysid::Recording& reused = reader.Read(path);
        CHECK(reused.source == fresh.source);
        CHECK(reused.names == fresh.names);
        CHECK(reused.metadata == fresh.metadata);
        CHECK(reused.data == fresh.data);
        sysid::DominanceResult expected;
        try {
          expected = sysid::AnalyzeDominance(m, fresh, o);
        } catch (const sysid::NumericalError& e) {
          CHECK_THROWS_WITH(sysid::AnalyzeDominance(m, reused, o, &workspace), e.what());
          continue;
        }
        CheckSame(sysid::AnalyzeDominance(m, reused, o, &workspace), expected);
      }
    }
  }
}
