// The irreducible error of an inverse model's inputs: how much of the output's variance no
// function of the chosen inputs can explain, estimated from the data alone (no network).
//
// For each row, the output's variance among the row's k nearest neighbours in the standardised
// input space (the row itself included, k/(k-1) corrected) estimates Var(y | inputs) there; the
// mean over the rows estimates E[Var(y | inputs)], the least mean squared error any model of y
// on these inputs can reach on this data (the Bayes floor under squared loss). It is the
// nearest-neighbour residual variance of the noise-variance and input-selection literature
// (e.g. the Gamma/delta test); it overestimates where the function varies within a
// neighbourhood (sparse rows, small k keeps that small) and needs no model, so it tells apart
// "the network did not learn it" from "these inputs do not determine it" — the paper's
// dominance question asked of the data: with v alone and with (v, a).
#ifndef SYSID_NN_IRREDUCIBLE_HPP_
#define SYSID_NN_IRREDUCIBLE_HPP_

#include <cstdint>
#include <string>
#include <vector>

#include "sysid/nn.hpp"
#include "sysid/serialize.hpp"

namespace sysid {

struct IrreducibleErrorOptions {
  int neighbours = 10;     ///< k, 2..1000: rows per neighbourhood, the row itself included
  /// Exact ties (a quantised encoder gives many equal v) are broken by a seeded perturbation of
  /// 1e-9 of each standardised input, so that tied rows are neighbours in random, not time,
  /// order (time-adjacent rows share more than their inputs).
  std::uint64_t seed = 1;
  /// Groups of the delete-a-group jackknife behind the 95 % interval, 0 (no interval) or
  /// 5..100: contiguous blocks of rows, each left out in turn (the estimate is recomputed that
  /// many times, so the default leaves it to callers that print the interval: `sysid
  /// irreducible` and Python's irreducible_error use 20).
  int jackknife_groups = 0;
  void Validate() const;  ///< OptionsError naming the field and the rule
};

struct IrreducibleError {
  std::vector<std::string> input_names;
  std::string output_name;
  long rows = 0;
  int neighbours = 0;
  double output_variance = 0;  ///< [output unit^2] Var(y) over the rows
  /// [output unit^2] the estimate of E[Var(y | inputs)]. Biased upward: where the function of
  /// the inputs varies within a neighbourhood its spread adds to the noise's variance, and more
  /// so with more inputs (neighbours lie farther apart), so an estimate for a set may exceed a
  /// subset's although the true floor cannot (EstimateIrreducibleError's caller says so).
  double mse = 0;
  /// [output unit^2] the 95 % interval of `mse` from its jackknife standard error (its spread,
  /// not its bias), clipped at 0; both equal to mse without groups.
  double mse_low = 0, mse_high = 0;
  /// mse / output_variance: the share of the output's variance the inputs leave unexplained.
  double unexplained_share() const { return output_variance > 0 ? mse / output_variance : 0.0; }
  /// The fields of a `sysid irreducible --json` row, in file order (sysid/serialize.hpp); the
  /// interval and the unexplained share are written after them (ToJson).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(input_names).Renamed("inputs"));
    a->Visit(SYSID_NVP(output_name).Renamed("output"));
    a->Visit(SYSID_NVP(rows).Minimum(0));
    a->Visit(SYSID_NVP(neighbours).Minimum(0));
    a->Visit(SYSID_NVP(output_variance).Minimum(0));
    a->Visit(SYSID_NVP(mse).Renamed("irreducible_mse_estimate").Minimum(0));
  }
};

/// The estimate as JSON: its fields (Serialize), "interval95": [mse_low, mse_high] and
/// "unexplained_share".
std::string ToJson(const IrreducibleError& estimate, int indent = 2);

/// The estimate on `data` (its inputs standardised by their own standard deviations; a
/// constant input is left as it is). InputError when the data has fewer rows than neighbours
/// or a non-finite value (naming the source, row and column).
IrreducibleError EstimateIrreducibleError(const NeuralDataset& data,
                                          const IrreducibleErrorOptions& options = {});

}  // namespace sysid

#endif  // SYSID_NN_IRREDUCIBLE_HPP_
