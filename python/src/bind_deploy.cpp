// sysid.export: an inverse model as allocation-free C99 (sysid/deploy.hpp, docs/deploy.md),
// the same files as `sysid export`.
#include <memory>
#include <optional>
#include <string>

#include "bind_common.hpp"
#include "sysid/deploy.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis_model.hpp"
#include "sysid/model.hpp"
#include "sysid/nn.hpp"

namespace sysid::python {

void BindDeploy(py::module_& m) {
  m.def(
      "export",
      [](const py::object& model, const std::string& folder, const std::string& precision,
         const std::string& prefix, std::optional<double> dt_s) {
        ExportOptions options;
        options.prefix = prefix;
        options.precision = ExportPrecisionFromString(precision);
        options.Validate();
        auto need_dt = [&]() {
          if (!dt_s) throw OptionsError("sysid.export: dt_s [s] is needed for this model", "dt_s");
          CheckTimeStep("sysid.export", *dt_s);
          return *dt_s;
        };
        // An object has no file: the provenance is the SHA-256 of its model-file JSON text.
        ExportResult r;
        if (py::isinstance<FrictionModel>(model)) {
          const FrictionModel f = model.cast<FrictionModel>();
          const double dt = need_dt();
          r = ExportFrictionInverse(f, dt, DefaultFrictionVectors(dt), options,
                                    {"a FrictionModel from Python (hash of its JSON)",
                                     Sha256Hex(ModelToJson(f))});
        } else if (py::isinstance<NeuralNetwork>(model)) {
          const NeuralNetwork& net = model.cast<const NeuralNetwork&>();
          r = ExportNetworkInverse(net, DefaultNetworkVectors(net), options,
                                   {"a Network from Python (hash of its JSON)",
                                    Sha256Hex(NeuralNetworkToJson(net))});
        } else if (py::isinstance<HysteresisModel>(model)) {
          const auto h = model.cast<std::shared_ptr<HysteresisModel>>();
          const ExportProvenance prov{"a HysteresisModel from Python (hash of its JSON)",
                                      Sha256Hex(h->ToJson())};
          if (const auto* ops = dynamic_cast<const OperatorNetworkModel*>(h.get())) {
            r = ExportOperatorNetworkInverse(*ops, DefaultOperatorNetworkVectors(*ops), options,
                                             prov);
          } else if (const auto* pi = dynamic_cast<const PrandtlIshlinskiiModel*>(h.get())) {
            const double dt = need_dt();
            r = ExportPiInverse(*pi, dt, DefaultPiVectors(*pi, dt), options, prov);
          } else if (const auto* bw = dynamic_cast<const PiezoBoucWen*>(h.get())) {
            r = ExportBoucWenInverse(*bw, DefaultBoucWenVectors(*bw), options, prov);
          } else {
            throw OptionsError("sysid.export: a " + h->kind() + " model; the PI family, the "
                               "operator-input network and the piezo Bouc-Wen are exported",
                               "model");
          }
        } else {
          throw OptionsError("sysid.export: model must be a FrictionModel, a Network or a "
                             "HysteresisModel",
                             "model");
        }
        py::dict out;
        out["files"] = WriteExportFiles(r, options.prefix, folder);
        out["kind"] = r.kind;
        out["bound_v"] = r.bound_v;
        out["bound_reason"] = r.bound_reason;
        out["inputs"] = r.input_names;
        return out;
      },
      py::arg("model"), py::arg("folder"), py::arg("precision") = "double",
      py::arg("prefix") = ExportOptions{}.prefix, py::arg("dt_s") = py::none(),
      "Writes the model's streaming inverse as C99 into `folder` (NAME.h, NAME.c, NAME_check.c, "
      "NAME_vectors.csv, NAME_README.md; docs/deploy.md); dt_s [s] for a FrictionModel and a "
      "PI model. Returns {files, kind, bound_v, bound_reason, inputs}.");
}

}  // namespace sysid::python
