// The report's Inputs sentence repeats the recording flags the pipeline read its folder with,
// the time window included (a window alone once left the sentence without a flag).
#include <catch2/catch.hpp>

#include "report/report_sections.hpp"
#include "sysid/pipeline.hpp"

TEST_CASE("the Inputs sentence names --var, --rate, --scale and the window", "[report]") {
  sysid::PipelineInputs in;
  CHECK(sysid::internal::MappingSentence(in).empty());
  in.mapping.t_end_s = 4.5;
  CHECK(sysid::internal::MappingSentence(in) == " Read with `--t-end 4.5`.");
  in.mapping.variables = {{"u", "volts"}};
  in.mapping.scales = {{"x", 1e-6}};
  in.mapping.t_start_s = 0.25;
  CHECK(sysid::internal::MappingSentence(in) ==
        " Read with `--var u=volts --scale x=1e-06 --t-start 0.25 --t-end 4.5`.");
}
