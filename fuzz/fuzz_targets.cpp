#include "fuzz_targets.hpp"

#include <unistd.h>

#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/model.hpp"
#include "sysid/nn.hpp"
#include "sysid/stage.hpp"

namespace sysid::fuzz {

bool IsTarget(const std::string& name) {
  return name == "csv" || name == "model" || name == "network" || name == "stage" ||
         name == "mat" || name == "hdf5";
}

namespace {

// matio and HDF5 read files, not memory: each input is written to one file per process (in the
// system's temp folder) and read from there.
// Removed when the process ends normally.
struct ScratchFile {
  std::string path;
  ~ScratchFile() {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
};

std::string InputFile(const std::string& target, std::string_view bytes) {
  static const ScratchFile file{
      (std::filesystem::temp_directory_path() /
       ("sysid-fuzz-" + std::to_string(::getpid()) + (target == "mat" ? ".mat" : ".h5")))
          .string()};
  std::ofstream(file.path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<long>(bytes.size()));
  return file.path;
}

// The MAT and HDF5 readers: list the variables, then read the file as a recording both without
// a mapping and with one (a rate, and the first listed variable as u and x).
void ReadContainer(const std::string& path) {
  if (DetectFileFormat(path) == FileFormat::kText) {
    (void)ReadRecording(path);
    return;
  }
  const std::vector<VariableInfo> vars = ListVariables(path);
  try {
    (void)ReadRecording(path);
  } catch (const InputError&) {
  }
  if (vars.empty()) return;
  ReadOptions o;
  o.mapping.variables = {{"u", vars.front().name}, {"x", vars.back().name}};
  o.mapping.rate_hz = 100;
  (void)ReadRecording(path, o);
}

}  // namespace

bool RunTarget(const std::string& target, const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::string source = "fuzz.in";
  try {
    if (target == "mat" || target == "hdf5") {
      source = InputFile(target, text);
      ReadContainer(source);
    } else if (target == "csv") {
      (void)ParseRecording(text, source);
    } else if (target == "model") {
      (void)ParseModel(text, source);
    } else if (target == "network") {
      (void)ParseNeuralNetwork(text, source);
    } else if (target == "stage") {
      (void)ParseStageParameters(text, source);
    } else {
      throw std::logic_error("unknown fuzz target " + target);
    }
    return true;
  } catch (const InputError& e) {
    // Every rejection names the place: "fuzz.in:LINE:COL: ..." (or "fuzz.in: ..." for the
    // CSV reader's whole-file errors such as "no data rows").
    if (std::string_view(e.what()).rfind(source + ":", 0) != 0)
      throw std::logic_error(target + ": InputError without the file name: " + e.what());
    return false;
  } catch (const std::logic_error&) {
    throw;
  } catch (const std::exception& e) {
    throw std::logic_error(target + ": unexpected exception (exit 4 in the CLI): " + e.what());
  }
}

}  // namespace sysid::fuzz
