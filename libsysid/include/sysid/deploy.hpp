// Export of an inverse model to allocation-free C99 for a real-time target (`sysid export`,
// docs/deploy.md): NAME.h and NAME.c hold the model's streaming inverse (the same arithmetic,
// in the same order, as the library's stepper: sysid/model_stepper.hpp, nn_stepper.hpp,
// hysteresis_stepper.hpp), NAME_vectors.csv the stepper's own outputs on test inputs,
// NAME_check.c a program that replays them through the generated step and fails beyond the
// bound stated in the header, and a README fragment.
//
// Kinds this version exports, in double and float: the analytic friction inverse, the tanh
// network (any number of inputs), the PI inverses (pi, gpi, rdpi; an rdpi whose rate feedback
// leaves float no bound is exported in double only) and the operator-input network's inverse.
// The piezo Bouc–Wen inverse too; the mechanical Bouc–Wen has no inverse.
#ifndef SYSID_DEPLOY_HPP_
#define SYSID_DEPLOY_HPP_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "sysid/hysteresis.hpp"
#include "sysid/hysteresis_bouc_wen.hpp"
#include "sysid/model.hpp"
#include "sysid/nn.hpp"
#include "sysid/nn_operators.hpp"

namespace sysid {

enum class ExportPrecision { kDouble, kFloat };
std::string ToString(ExportPrecision precision);
/// "double" or "float"; OptionsError otherwise.
ExportPrecision ExportPrecisionFromString(const std::string& name);

/// The longest delay line an exported friction inverse holds [samples]: tau / dt + 2 doubles
/// in the caller's state struct (32 KiB); a longer one is refused.
inline constexpr int kMaxExportDelaySamples = 4096;

struct ExportOptions {
  std::string prefix = "sysid_inverse";  ///< C identifier naming the files and symbols
  ExportPrecision precision = ExportPrecision::kDouble;
  /// Throws OptionsError: prefix must be a C identifier of at most 40 characters, not a C99
  /// keyword, not starting with an underscore (reserved names).
  void Validate() const;
};

/// Where the model came from, for the header comment.
struct ExportProvenance {
  std::string model_file;  ///< the file's name as given
  std::string sha256;      ///< hex SHA-256 of its bytes
};

/// The test inputs: one column per input of the exported step, in its argument order.
struct ExportVectors {
  Eigen::MatrixXd inputs;  ///< N x inputs
  std::string source;      ///< "default waveform" or the recording's name
};

/// The generated files' texts, and what the export promises.
struct ExportResult {
  std::string kind;                       ///< "friction", "nn", "pi"
  std::vector<std::string> input_names;   ///< the step's arguments / the CSV's columns
  std::vector<std::string> input_units;   ///< their SI units
  Eigen::VectorXd u_expected_v;           ///< the library stepper's outputs on the vectors [V]
  double bound_v = 0;                     ///< [V] max |u_C - u_expected| the check allows
  std::string bound_reason;               ///< how bound_v follows (one sentence)
  std::string header, source, check, vectors_csv, readme;  ///< NAME.h, .c, _check.c, .csv, .md
};

/// The analytic friction inverse at sample time dt_s [s]. `vectors` columns: v [m/s], a [m/s^2].
ExportResult ExportFrictionInverse(const FrictionModel& model, double dt_s,
                                   const ExportVectors& vectors, const ExportOptions& options,
                                   const ExportProvenance& provenance);
/// The tanh network; `vectors` columns in the network's input order.
ExportResult ExportNetworkInverse(const NeuralNetwork& network, const ExportVectors& vectors,
                                  const ExportOptions& options,
                                  const ExportProvenance& provenance);
/// The operator-input network's inverse; `vectors` column: x_ref [m].
ExportResult ExportOperatorNetworkInverse(const OperatorNetworkModel& model,
                                          const ExportVectors& vectors,
                                          const ExportOptions& options,
                                          const ExportProvenance& provenance);
/// The piezo Bouc–Wen inverse (kind bouc-wen-piezo, rate-independent); `vectors` column:
/// x_ref [m]. NumericalError when the model is not invertible.
ExportResult ExportBoucWenInverse(const PiezoBoucWen& model, const ExportVectors& vectors,
                                  const ExportOptions& options,
                                  const ExportProvenance& provenance);
/// A PI-family inverse at sample time dt_s [s] (pi: the closed form; gpi, rdpi: the stepper's
/// bisection; float: OptionsError when rdpi's rate feedback leaves no bound, docs/deploy.md);
/// `vectors` column: x_ref [m].
ExportResult ExportPiInverse(const PrandtlIshlinskiiModel& model, double dt_s,
                             const ExportVectors& vectors, const ExportOptions& options,
                             const ExportProvenance& provenance);

/// Default test inputs: friction: v, a of three sines (2, 4, 8 periods over the samples; 2 mm/s)
/// with a rest over the middle tenth, so both directions, reversals and v = 0 are in them; nn: each input swept over 1.2x its training range at
/// incommensurate rates; pi: x of the forward model driven by decaying loops over its input
/// range, so every operator reverses (nn-operators: 1.2x the inverse network's x range). 2000
/// samples.
ExportVectors DefaultFrictionVectors(double dt_s);
ExportVectors DefaultNetworkVectors(const NeuralNetwork& network);
ExportVectors DefaultPiVectors(const PrandtlIshlinskiiModel& model, double dt_s);
ExportVectors DefaultOperatorNetworkVectors(const OperatorNetworkModel& model);
/// Bouc–Wen: x of decaying loops over 3 / (beta + gamma) volts times d, about the offset.
ExportVectors DefaultBoucWenVectors(const PiezoBoucWen& model);

/// Writes NAME.h, NAME.c, NAME_check.c, NAME_vectors.csv and NAME_README.md of `result` into
/// the folder `dir` (created when missing), each atomically; returns their paths. The CLI calls
/// it inside its staged -o folder; Python (sysid.export) on the folder it is given.
std::vector<std::string> WriteExportFiles(const ExportResult& result, const std::string& prefix,
                                          const std::string& dir);

/// The lower-case hex SHA-256 (FIPS 180-4) of `bytes`.
std::string Sha256Hex(const std::string& bytes);

}  // namespace sysid

#endif  // SYSID_DEPLOY_HPP_
