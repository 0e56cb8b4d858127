// JSON model files of neural networks (format in sysid/nn.hpp).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "detail/json_text.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/nn.hpp"

namespace sysid {
namespace {

using Json = nlohmann::json;

// Reports errors about one key at the place the key first appears in the text.
struct Reader {
  std::string_view text;
  std::string source;

  [[noreturn]] void Fail(const std::string& key, const std::string& what) const {
    throw InputError(source + ":" + detail::JsonKeyPosition(text, key) + ": " + what);
  }
  const Json& Get(const Json& obj, const std::string& key, const std::string& where) const {
    if (!obj.contains(key)) Fail(where, "missing key '" + key + "' in " + where);
    return obj.at(key);
  }
  double Number(const Json& v, const std::string& key) const {
    if (!v.is_number()) Fail(key, "key '" + key + "': expected a number, found " + v.type_name());
    return v.get<double>();
  }
  std::vector<double> Vector(const Json& v, const std::string& key, size_t size) const {
    if (!v.is_array())
      Fail(key, "key '" + key + "': expected an array of numbers, found " + v.type_name());
    if (size != 0 && v.size() != size)
      Fail(key, "key '" + key + "': expected " + std::to_string(size) + " numbers, found " +
                    std::to_string(v.size()));
    std::vector<double> out;
    for (const auto& e : v) out.push_back(Number(e, key));
    return out;
  }
  ScaledVariable Variable(const Json& v, const std::string& key) const {
    if (!v.is_object()) Fail(key, "key '" + key + "': expected an object {name, unit, min, max}");
    for (const auto& [k, unused] : v.items()) {
      (void)unused;
      if (k != "name" && k != "unit" && k != "min" && k != "max")
        Fail(k, "unknown key '" + k + "' in '" + key + "' (expected name, unit, min, max)");
    }
    ScaledVariable s;
    const Json& name = Get(v, "name", key);
    if (!name.is_string() || name.get<std::string>().empty())
      Fail(key, "key '" + key + "': 'name' must be a non-empty string");
    s.name = name.get<std::string>();
    if (v.contains("unit")) {
      if (!v.at("unit").is_string()) Fail(key, "key '" + key + "': 'unit' must be a string");
      s.unit = v.at("unit").get<std::string>();
    } else {
      s.unit = DefaultUnit(s.name);
    }
    s.min = Number(Get(v, "min", key), key);
    s.max = Number(Get(v, "max", key), key);
    if (!(s.min < s.max))
      Fail(key, "variable '" + s.name + "': min = " + std::to_string(s.min) +
                    ", max = " + std::to_string(s.max) + ". Violated constraint: min < max");
    return s;
  }
};

}  // namespace

NeuralNetwork ParseNeuralNetwork(std::string_view json_text, const std::string& source) {
  const auto j = detail::ParseJsonText(json_text, source);
  const Reader rd{json_text, source};
  if (!j.is_object())
    throw InputError(source +
                     ":1:1: expected a JSON object with keys inputs, output, hidden, "
                     "W1, b1, W2, b2");
  static const char* const kKeys[] = {"type", "inputs", "output", "hidden", "W1",
                                      "b1",   "W2",     "b2",     "note",   "training"};
  for (const auto& [key, unused] : j.items()) {
    (void)unused;
    bool known = !key.empty() && key[0] == '_';
    for (const char* k : kKeys) known = known || key == k;
    if (!known)
      rd.Fail(key, "unknown key '" + key +
                       "' (expected type, inputs, output, hidden, W1, b1, "
                       "W2, b2, note, training)");
  }
  if (j.contains("type") && j.at("type") != "tanh-mlp")
    rd.Fail("type", "key 'type': expected \"tanh-mlp\" (one hidden tanh layer, linear output)");
  const Json& jin = rd.Get(j, "inputs", "the network");
  if (!jin.is_array() || jin.empty())
    rd.Fail("inputs", "key 'inputs': expected a non-empty array of {name, unit, min, max}");
  std::vector<ScaledVariable> inputs;
  for (const auto& e : jin) inputs.push_back(rd.Variable(e, "inputs"));
  const ScaledVariable output = rd.Variable(rd.Get(j, "output", "the network"), "output");
  const Json& jh = rd.Get(j, "hidden", "the network");
  if (!jh.is_number_integer() || jh.get<long>() < 1 || jh.get<long>() > 100000)
    rd.Fail("hidden", "key 'hidden': expected an integer in [1, 100000]");
  const int H = jh.get<int>();
  const int n = static_cast<int>(inputs.size());
  NeuralNetwork net(inputs, output, H);
  Eigen::VectorXd theta(net.parameter_count());
  const Json& jw1 = rd.Get(j, "W1", "the network");
  if (!jw1.is_array() || static_cast<int>(jw1.size()) != H)
    rd.Fail("W1", "key 'W1': expected " + std::to_string(H) + " rows (one per hidden unit) of " +
                      std::to_string(n) + " numbers");
  for (int h = 0; h < H; ++h) {
    // A single-input network may list W1 as plain numbers instead of 1-element rows.
    const Json& row = jw1[h];
    const std::vector<double> w = (n == 1 && row.is_number())
                                      ? std::vector<double>{rd.Number(row, "W1")}
                                      : rd.Vector(row, "W1", n);
    for (int i = 0; i < n; ++i) theta[h * n + i] = w[i];
  }
  const auto b1 = rd.Vector(rd.Get(j, "b1", "the network"), "b1", H);
  const auto w2 = rd.Vector(rd.Get(j, "W2", "the network"), "W2", H);
  for (int h = 0; h < H; ++h) {
    theta[H * n + h] = b1[h];
    theta[H * n + H + h] = w2[h];
  }
  theta[H * n + 2 * H] = rd.Number(rd.Get(j, "b2", "the network"), "b2");
  net.set_parameters(theta);
  if (j.contains("note")) {
    if (!j.at("note").is_string()) rd.Fail("note", "key 'note': expected a string");
    net.note = j.at("note").get<std::string>();
  }
  return net;
}

NeuralNetwork ReadNeuralNetwork(const std::string& path) {
  return ParseNeuralNetwork(ReadFile(path), path);
}

std::string NeuralNetworkToJson(const NeuralNetwork& net, int indent,
                                const std::string& extra_json) {
  nlohmann::ordered_json j;
  j["type"] = "tanh-mlp";
  auto var = [](const ScaledVariable& s) {
    return nlohmann::ordered_json{
        {"name", s.name}, {"unit", s.unit}, {"min", s.min}, {"max", s.max}};
  };
  j["inputs"] = nlohmann::ordered_json::array();
  for (const auto& in : net.inputs()) j["inputs"].push_back(var(in));
  j["output"] = var(net.output());
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
  WriteFileAtomically(path, NeuralNetworkToJson(net, 2, extra_json));
}

}  // namespace sysid
