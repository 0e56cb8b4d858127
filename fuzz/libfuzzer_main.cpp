// libFuzzer entry point (clang -fsanitize=fuzzer): one executable per target, the target name
// compiled in as SYSID_FUZZ_TARGET. scripts/fuzz.sh builds and runs them.
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  sysid::fuzz::RunTarget(SYSID_FUZZ_TARGET, data, size);  // throws (and aborts) on a bug
  return 0;
}
