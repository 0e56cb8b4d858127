// The fuzzed readers: the CSV reader, the MAT and HDF5 readers, and the three JSON readers
// (model, network, stage). A
// target may reject its input only with sysid::InputError; anything else (another exception,
// a sanitizer report, a crash) is a bug the fuzzers exist to find.
#ifndef SYSID_FUZZ_FUZZ_TARGETS_HPP_
#define SYSID_FUZZ_FUZZ_TARGETS_HPP_

#include <cstddef>
#include <cstdint>
#include <string>

namespace sysid::fuzz {

/// Target names: csv, model, network, stage, mat (MAT v4/v5/v7.3 through matio), hdf5.
bool IsTarget(const std::string& name);

/// Runs `target` on `data`. Returns true when the input was accepted, false when it was
/// rejected with a positioned InputError; throws std::logic_error for anything else (a wrong
/// exception type, or an InputError without "SOURCE:LINE:COL").
bool RunTarget(const std::string& target, const std::uint8_t* data, std::size_t size);

}  // namespace sysid::fuzz

#endif  // SYSID_FUZZ_FUZZ_TARGETS_HPP_
