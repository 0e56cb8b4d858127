// JSON model files of neural networks (format in sysid/nn.hpp).
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "nn/nn_json.hpp"
#include "nn/mlp_kernels.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/nn.hpp"
#include "sysid/io_output.hpp"

namespace sysid {
namespace {

ScaledVariable ReadVariable(const internal::JsonNode& v) {
  ScaledVariable s;
  internal::ReadFields(v, s);
  v.Get("name").String(/*non_empty=*/true);
  if (!v.Has("unit")) s.unit = DefaultUnit(s.name);
  if (!(s.min < s.max) || !std::isfinite(s.max - s.min))  // the scaling divides by max - min
    v.Get("max").Expected("a number > min (" + nlohmann::json(s.min).dump() +
                          "), max - min finite");
  return s;
}

}  // namespace

NeuralNetwork ParseNeuralNetwork(std::string_view json_text, const std::string& source) {
  const internal::JsonDocument doc(json_text, source);
  return internal::NeuralNetworkFromJson(doc.Root());
}

NeuralNetwork internal::NeuralNetworkFromJson(const JsonNode& root) {
  root.ExpectObject({"type", "inputs", "output", "hidden", "W1", "b1", "W2", "b2", "note",
                     "training"});
  if (root.Has("type") && root.Get("type").json() != "tanh-mlp")
    root.Get("type").Expected("\"tanh-mlp\" (one hidden tanh layer, linear output)");
  const internal::JsonNode jin = root.Get("inputs");
  jin.ExpectArray(0, /*non_empty=*/true);
  std::vector<ScaledVariable> inputs;
  for (size_t i = 0; i < jin.Size(); ++i) inputs.push_back(ReadVariable(jin.Element(i)));
  const ScaledVariable output = ReadVariable(root.Get("output"));
  const int H = static_cast<int>(root.Get("hidden").Integer(1, kMaxHiddenUnits));
  const int n = static_cast<int>(inputs.size());
  const internal::JsonNode jw1 = root.Get("W1");
  jw1.ExpectArray(static_cast<size_t>(H));
  // Sizes are checked before the network is allocated.
  const auto b1 = root.Get("b1").Numbers(static_cast<size_t>(H));
  const auto w2 = root.Get("W2").Numbers(static_cast<size_t>(H));
  const double b2 = root.Get("b2").Number();
  NeuralNetwork net(inputs, output, H);
  Eigen::MatrixXd W1(H, n);
  for (int h = 0; h < H; ++h) {
    // A single-input network may list W1 as plain numbers instead of 1-element rows.
    const internal::JsonNode row = jw1.Element(static_cast<size_t>(h));
    const std::vector<double> w = (n == 1 && row.json().is_number())
                                      ? std::vector<double>{row.Number()}
                                      : row.Numbers(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) W1(h, i) = w[i];
  }
  net.set_parameters(internal::nn::PackParameters(
      W1, Eigen::Map<const Eigen::VectorXd>(b1.data(), H),
      Eigen::Map<const Eigen::VectorXd>(w2.data(), H), b2));
  if (root.Has("note")) net.note = root.Get("note").String();
  return net;
}

NeuralNetwork ReadNeuralNetwork(const std::string& path) {
  return ParseNeuralNetwork(ReadFile(path), path);
}

std::string NeuralNetworkToJson(const NeuralNetwork& net, int indent,
                                const std::string& extra_json) {
  nlohmann::ordered_json j;
  j["type"] = "tanh-mlp";
  j["inputs"] = internal::JsonForm<std::vector<ScaledVariable>>::Write(net.inputs());
  j["output"] = internal::WriteFields(net.output());
  j["hidden"] = net.hidden_size();
  if (!net.note.empty()) j["note"] = net.note;
  j["W1"] = nlohmann::ordered_json::array();
  for (int h = 0; h < net.hidden_size(); ++h) {
    std::vector<double> row(net.W1().cols());
    for (Eigen::Index i = 0; i < net.W1().cols(); ++i) row[i] = net.W1()(h, i);
    j["W1"].push_back(row);
  }
  j["b1"] = std::vector<double>(net.b1().data(), net.b1().data() + net.b1().size());
  j["W2"] = std::vector<double>(net.w2().data(), net.w2().data() + net.w2().size());
  j["b2"] = net.b2();
  if (!extra_json.empty()) j["training"] = nlohmann::ordered_json::parse(extra_json);
  return j.dump(indent) + "\n";
}

void WriteNeuralNetwork(const std::string& path, const NeuralNetwork& net,
                        const std::string& extra_json) {
  // JSON has no inf or NaN (nlohmann writes null) and ReadNeuralNetwork refuses both.
  if (!net.W1().allFinite() || !net.b1().allFinite() || !net.w2().allFinite() ||
      !std::isfinite(net.b2()))
    throw NumericalError(path + ": the network's weights hold inf or NaN: not written (the "
                         "training diverged)");
  WriteFileAtomically(path, WithGeneratorKey(NeuralNetworkToJson(net, 2, extra_json)));
}

}  // namespace sysid
