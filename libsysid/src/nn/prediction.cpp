// A network evaluated on a recording's columns (`sysid predict`): the prediction column, how
// many rows extrapolate, and the MSE against the true output when the recording has it.
#include <algorithm>
#include <string>

#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/nn.hpp"

namespace sysid {

NetworkPrediction PredictColumn(const NeuralNetwork& network, Recording& recording,
                                const std::string& column) {
  NetworkPrediction p;
  p.column = column.empty() ? network.output().name + "_nn" : column;
  // The true output is what the prediction is scored against; a default name never replaces
  // a column the user has (a chosen one may: e.g. re-running predict).
  if (p.column == network.output().name || (column.empty() && recording.has(p.column)))
    throw OptionsError("prediction column '" + p.column + "' would overwrite a column of " +
                           recording.source + "; choose another name",
                       "column");
  Eigen::MatrixXd X(recording.rows(), network.input_count());
  for (int i = 0; i < network.input_count(); ++i) {
    const std::string& name = network.inputs()[static_cast<size_t>(i)].name;
    if (!recording.has(name))
      throw InputError(recording.source + ": no column '" + name + "' (a network input)");
    X.col(i) = recording.column(name);
  }
  const Eigen::VectorXd y = network.EvaluateBatch(X);
  p.rows = recording.rows();
  for (Eigen::Index k = 0; k < X.rows(); ++k)
    for (int i = 0; i < network.input_count(); ++i) {
      const ScaledVariable& in = network.inputs()[static_cast<size_t>(i)];
      if (X(k, i) < in.min || X(k, i) > in.max) {
        ++p.rows_outside_input_range;
        break;
      }
    }
  if (recording.has(network.output().name))
    p.mse = (y - recording.column(network.output().name)).squaredNorm() /
            static_cast<double>(std::max<Eigen::Index>(recording.rows(), 1));
  recording.SetColumn(p.column, y);
  return p;
}

}  // namespace sysid
