#include <string>
#include <vector>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/nn.hpp"

namespace sysid {

NeuralDataset MakeNeuralDataset(const Recording& recording,
                                const std::vector<std::string>& input_names,
                                const std::string& output_name) {
  if (input_names.empty()) internal::FailOption("", "inputs", "empty", "at least one input column");
  NeuralDataset d;
  d.input_names = input_names;
  d.output_name = output_name;
  d.source = recording.source;
  d.inputs.resize(recording.rows(), static_cast<Eigen::Index>(input_names.size()));
  for (size_t i = 0; i < input_names.size(); ++i)
    d.inputs.col(static_cast<Eigen::Index>(i)) = recording.column(input_names[i]);
  d.targets = recording.column(output_name);
  if (d.size() == 0) throw InputError(recording.source + ": no data rows");
  return d;
}

NeuralDataset ReadNeuralDataset(const std::string& path,
                                const std::vector<std::string>& input_names,
                                const std::string& output_name, const SourceMapping& mapping) {
  ReadOptions ro;
  ro.mapping = mapping;
  ro.required_columns = input_names;
  ro.required_columns.push_back(output_name);
  ro.any_of_columns = {};
  return MakeNeuralDataset(ReadRecording(path, ro), input_names, output_name);
}

double MeanSquaredError(const NeuralNetwork& net, const NeuralDataset& data) {
  if (data.size() == 0) throw InputError(data.source + ": no data rows");
  return (net.EvaluateBatch(data.inputs) - data.targets).squaredNorm() /
         static_cast<double>(data.size());
}

NeuralDataset SubsampleRows(const NeuralDataset& data, int stride) {
  if (stride <= 1) return data;
  NeuralDataset out = data;
  const Eigen::Index n = (data.size() + stride - 1) / stride;
  out.inputs.resize(n, data.inputs.cols());
  out.targets.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    out.inputs.row(k) = data.inputs.row(k * stride);
    out.targets[k] = data.targets[k * stride];
  }
  return out;
}

}  // namespace sysid
