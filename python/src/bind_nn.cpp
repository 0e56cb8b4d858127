// Neural inverse models (sysid/nn.hpp): the network and its JSON files, datasets, both trainers
// and the hidden-size sweep.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdint>
#include <string>
#include <vector>

#include "bind_common.hpp"
#include "bind_fields.hpp"
#include "sysid/error.hpp"
#include "sysid/nn.hpp"
#include "sysid/nn_irreducible.hpp"

namespace sysid::python {
namespace {

NeuralTrainer ParseTrainer(const std::string& name) {
  if (name == "lm") return NeuralTrainer::kLevenbergMarquardt;
  if (name == "ceres") return NeuralTrainer::kCeres;
  throw OptionsError("trainer '" + name + "': expected 'lm' or 'ceres'");
}

NeuralInit ParseInit(const std::string& name) {
  if (name == "nguyen-widrow") return NeuralInit::kNguyenWidrow;
  if (name == "uniform") return NeuralInit::kUniform;
  throw OptionsError("init '" + name + "': expected 'nguyen-widrow' or 'uniform'");
}

/// Outputs [output unit] for inputs given as an N x n array, or as a Recording / dict whose
/// columns are named like the network's inputs.
Eigen::VectorXd Predict(const NeuralNetwork& net, const py::object& data) {
  Eigen::MatrixXd X;
  if (py::isinstance<Recording>(data) || py::isinstance<py::dict>(data) ||
      py::hasattr(data, "columns")) {
    const int n = net.input_count();
    for (int i = 0; i < n; ++i) {
      const std::string& name = net.inputs()[static_cast<size_t>(i)].name;
      py::object values;
      try {
        values = data[py::str(name)];
      } catch (const py::error_already_set&) {  // KeyError, or the Recording's DataError
        throw InputError("predict: inputs: no column '" + name + "' (the network's input " +
                         std::to_string(i + 1) + " of " + std::to_string(n) + ")");
      }
      const Eigen::VectorXd column = RealVector(values, "predict: inputs['" + name + "']");
      if (i == 0) X.resize(column.size(), n);
      CheckSameLength("predict", "inputs['" + name + "']", column.size(),
                      "inputs['" + net.inputs()[0].name + "']", X.rows());
      X.col(i) = column;
    }
  } else {
    X = RealMatrix(data, "predict: inputs", net.input_count());
  }
  py::gil_scoped_release release;
  return net.EvaluateBatch(X);
}

}  // namespace

// Long function: a pybind11 registration table, one entry per bound type and field in the
// header's order; split, it would only scatter the table.
void BindNeural(py::module_& m) {
  py::class_<ScaledVariable>(m, "ScaledVariable")
      .def(py::init([](std::string name, std::string unit, double min, double max) {
             return ScaledVariable{std::move(name), std::move(unit), min, max};
           }),
           py::arg("name"), py::arg("unit") = "", py::arg("min") = -1.0, py::arg("max") = 1.0)
      .def_readwrite("name", &ScaledVariable::name)
      .def_readwrite("unit", &ScaledVariable::unit)
      .def_readwrite("min", &ScaledVariable::min)
      .def_readwrite("max", &ScaledVariable::max);

  py::class_<NeuralNetwork>(m, "Network",
                            "A one-hidden-layer tanh network with mapminmax input/output scaling.")
      .def(py::init<>())
      .def(py::init<std::vector<ScaledVariable>, ScaledVariable, int>(), py::arg("inputs"),
           py::arg("output"), py::arg("hidden"))
      .def_property_readonly("inputs", &NeuralNetwork::inputs)
      .def_property_readonly("output", &NeuralNetwork::output)
      .def_property_readonly("input_names", &NeuralNetwork::input_names)
      .def_property_readonly("hidden_size", &NeuralNetwork::hidden_size)
      .def_property_readonly("parameter_count", &NeuralNetwork::parameter_count)
      .def_property_readonly("W1", &NeuralNetwork::W1)
      .def_property_readonly("b1", &NeuralNetwork::b1)
      .def_property_readonly("w2", &NeuralNetwork::w2)
      .def_property_readonly("b2", &NeuralNetwork::b2)
      .def_property("parameters", &NeuralNetwork::parameters,
                    [](NeuralNetwork& n, const py::object& theta) {
                      const Eigen::VectorXd t = RealVector(theta, "parameters", true);
                      CheckSameLength("Network.parameters", "the new vector", t.size(),
                                      "parameter_count", n.parameter_count());
                      n.set_parameters(t);
                    })
      .def_readwrite("note", &NeuralNetwork::note)
      .def("validate", &NeuralNetwork::Validate)
      .def("predict", &Predict, py::arg("inputs"),
           "Outputs for an N x n array (physical units, columns in input order) or for a "
           "Recording / dict / DataFrame with the input columns.")
      .def_static("load", &ReadNeuralNetwork, py::arg("path"), "Reads the CLI's network JSON.")
      .def(
          "save",
          [](const NeuralNetwork& n, const std::string& path, const std::string& extra) {
            WriteNeuralNetwork(path, n, extra);
          },
          py::arg("path"), py::arg("training_json") = "", "Writes the network JSON atomically.")
      .def_static("from_json", &ParseNeuralNetwork, py::arg("text"), py::arg("source") = "json")
      .def("to_json", &NeuralNetworkToJson, py::arg("indent") = 2, py::arg("training_json") = "")
      // Its file is its state (a training result holding one pickles it with its fields).
      .def(py::pickle(
          [](const NeuralNetwork& n) { return py::make_tuple(NeuralNetworkToJson(n, -1)); },
          [](const py::tuple& state) {
            return ParseNeuralNetwork(state[0].cast<std::string>(), "pickle");
          }));

  py::class_<NeuralDataset>(m, "NeuralDataset")
      .def_readonly("input_names", &NeuralDataset::input_names)
      .def_readonly("output_name", &NeuralDataset::output_name)
      .def_readonly("inputs", &NeuralDataset::inputs)
      .def_readonly("targets", &NeuralDataset::targets)
      .def_readonly("source", &NeuralDataset::source)
      .def("__len__", &NeuralDataset::size);
  m.def("make_dataset", &MakeNeuralDataset, py::arg("recording"), py::arg("inputs"),
        py::arg("output"));
  m.def(
      "read_dataset",
      [](const std::string& path, const std::vector<std::string>& inputs,
         const std::string& output) { return ReadNeuralDataset(path, inputs, output); },
      py::arg("path"), py::arg("inputs"), py::arg("output"), ReleaseGil());
  m.def("mean_squared_error", &MeanSquaredError, py::arg("network"), py::arg("data"));

  py::class_<IrreducibleError> irreducible(
      m, "IrreducibleError",
      "An estimate of the least MSE any model of the output on these inputs can reach on the "
      "data (k-NN, biased upward; interval: 95 %, delete-a-group jackknife; docs/neural.md)");
  constexpr const char* kInterval = "the 95 % interval's end; the JSON writes the interval";
  DefReadOnlyFields(irreducible)
      .Stored("mse_low", &IrreducibleError::mse_low, kInterval)
      .Stored("mse_high", &IrreducibleError::mse_high, kInterval)
      .Derived(
          "interval95",
          [](const IrreducibleError& e) { return std::make_pair(e.mse_low, e.mse_high); },
          "(mse_low, mse_high)")
      .Derived("unexplained_share", &IrreducibleError::unexplained_share,
               "mse / output_variance");
  irreducible.def("__repr__", [](const IrreducibleError& e) {
        return fmt::format(
            "IrreducibleError(inputs={}, mse_estimate={:.4g} [{:.4g}, {:.4g}], "
            "output_variance={:.4g}, rows={})",
            fmt::join(e.input_names, ","), e.mse, e.mse_low, e.mse_high, e.output_variance, e.rows);
      });
  m.def(
      "estimate_irreducible_error",
      [](const NeuralDataset& data, int neighbours, std::uint64_t seed, int jackknife_groups) {
        IrreducibleErrorOptions o;
        o.neighbours = neighbours;
        o.seed = seed;
        o.jackknife_groups = jackknife_groups;
        return EstimateIrreducibleError(data, o);
      },
      py::arg("data"), py::arg("neighbours") = 10, py::arg("seed") = 1,
      py::arg("jackknife_groups") = 20, ReleaseGil());

  py::enum_<NeuralTrainer>(m, "Trainer")
      .value("lm", NeuralTrainer::kLevenbergMarquardt)
      .value("ceres", NeuralTrainer::kCeres)
      .def(py::init(&ParseTrainer));
  py::implicitly_convertible<py::str, NeuralTrainer>();
  py::enum_<NeuralInit>(m, "Init")
      .value("nguyen_widrow", NeuralInit::kNguyenWidrow)
      .value("uniform", NeuralInit::kUniform)
      .def(py::init(&ParseInit));
  py::implicitly_convertible<py::str, NeuralInit>();

  py::class_<NeuralTrainingOptions> training(m, "TrainingOptions");
  AddKeywordInit(training);
  AddOptionsJson(training, &NeuralTrainingOptionsFromJson);
  DefFields(training);
  training.def("validate", &NeuralTrainingOptions::Validate);

  py::class_<EpochRecord> epoch(m, "EpochRecord");
  DefReadOnlyFields(epoch);
  constexpr const char* kStopReason = "stop under its file key (the name scripts use)";
  constexpr const char* kStillFalling =
      "whether the validation MSE still fell at the end; the report says it in words";
  py::class_<NeuralTrainingResult> training_result(m, "TrainingResult");
  DefReadOnlyFields(training_result)
      .Stored("network", &NeuralTrainingResult::network,
              "the trained network, a file of its own (Network.to_json)")
      .Stored("still_falling", &NeuralTrainingResult::still_falling, kStillFalling)
      .Derived(
          "stop_reason", [](const NeuralTrainingResult& r) { return ToString(r.stop); },
          kStopReason);
  training_result.def("brief_report", &NeuralTrainingResult::BriefReport);
  m.def("train_dataset", &TrainNeuralNetwork, py::arg("train"), py::arg("validation"),
        py::arg("options"), ReleaseGil());

  py::class_<HiddenSweepOptions> sweep(m, "SweepOptions");
  AddKeywordInit(sweep);
  AddOptionsJson(sweep, &HiddenSweepOptionsFromJson);
  DefFields(sweep);
  sweep.def("validate", &HiddenSweepOptions::Validate);
  py::class_<HiddenSweepRow> sweep_row(m, "SweepRow");
  DefReadOnlyFields(sweep_row)
      .Stored("still_falling", &HiddenSweepRow::still_falling, kStillFalling)
      .Derived(
          "termination",
          [](const HiddenSweepRow& r) { return ToString(TerminationOf(r.stop)); },
          "the termination of the stopping rule")
      .Derived(
          "stop_reason", [](const HiddenSweepRow& r) { return ToString(r.stop); }, kStopReason);
  py::class_<HiddenSweepResult> sweep_result(m, "SweepResult");
  DefReadOnlyFields(sweep_result)
      .Stored("runs", &HiddenSweepResult::runs,
              "the trained networks, one per row; the file holds the rows")
      .Stored("chosen", &HiddenSweepResult::chosen,
              "the chosen row's index; the file names it by its hidden size");
  m.def("sweep_datasets", &SweepHiddenSize, py::arg("train"), py::arg("validation"),
        py::arg("test"), py::arg("options"), ReleaseGil());
  m.def("parse_hidden_sizes", &ParseHiddenSizes, py::arg("spec"));
}

}  // namespace sysid::python
