#include "fuzz_targets.hpp"

#include <exception>
#include <stdexcept>
#include <string_view>

#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/nn.hpp"
#include "sysid/stage.hpp"

namespace sysid::fuzz {

bool IsTarget(const std::string& name) {
  return name == "csv" || name == "model" || name == "network" || name == "stage";
}

bool RunTarget(const std::string& target, const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::string source = "fuzz.in";
  try {
    if (target == "csv") {
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
