// One pipeline step: announce it to the progress callback, run it, and record its wall time in
// the result's step_seconds (the report's step table). Shared by the stage and stack pipelines.
#ifndef SYSID_PIPELINE_TIMED_STEP_HPP_
#define SYSID_PIPELINE_TIMED_STEP_HPP_

#include <chrono>
#include <string>

#include "sysid/pipeline.hpp"

namespace sysid::internal {

template <typename Body>
void TimedStep(PipelineResult& r, const PipelineProgress& progress, const std::string& name,
               Body&& body) {
  if (progress) progress(name);
  const auto t0 = std::chrono::steady_clock::now();
  body();
  r.step_seconds.emplace_back(
      name, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

}  // namespace sysid::internal

#endif  // SYSID_PIPELINE_TIMED_STEP_HPP_
