// SweepHiddenSize: one network per hidden size, trained side by side (nn/sweep_tasks.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "core/option_rule.hpp"
#include "core/task_pool.hpp"
#include "nn/mlp_kernels.hpp"
#include "nn/sweep_tasks.hpp"
#include "sysid/error.hpp"
#include "sysid/nn.hpp"

namespace sysid {

void HiddenSweepOptions::Validate() const {
  if (hidden_sizes.empty())
    internal::FailOption("HiddenSweepOptions", "hidden_sizes", "empty", "at least one size");
  for (size_t i = 0; i < hidden_sizes.size(); ++i)
    if (hidden_sizes[i] < 1)
      internal::FailOption("HiddenSweepOptions", "hidden_sizes[" + std::to_string(i) + "]",
                           hidden_sizes[i], "every size >= 1");
  if (threads < 0) internal::FailOption("HiddenSweepOptions", "threads", threads, "threads >= 0");
  training.Validate();
}

std::vector<int> ParseHiddenSizes(const std::string& spec) {
  auto bad = [&](const std::string& why) {
    return OptionsError("--hidden '" + spec + "': " + why +
                        " (expected FIRST:LAST:STEP such as 16:32:2, or a list such as 16,24)");
  };
  auto to_int = [&](const std::string& s) {
    size_t used = 0;
    int v = 0;
    try {
      v = std::stoi(s, &used);
    } catch (const std::exception&) {
      throw bad("'" + s + "' is not an integer");
    }
    if (used != s.size()) throw bad("'" + s + "' is not an integer");
    if (v < 1) throw bad("sizes must be >= 1");
    if (v > kMaxHiddenUnits) throw bad("sizes must be <= " + std::to_string(kMaxHiddenUnits));
    return v;
  };
  std::vector<int> out;
  if (spec.find(':') != std::string::npos) {
    std::vector<std::string> parts;
    size_t start = 0;
    for (size_t p; (p = spec.find(':', start)) != std::string::npos; start = p + 1)
      parts.push_back(spec.substr(start, p - start));
    parts.push_back(spec.substr(start));
    if (parts.size() != 2 && parts.size() != 3) throw bad("wrong number of fields");
    const int first = to_int(parts[0]), last = to_int(parts[1]);
    const int step = parts.size() == 3 ? to_int(parts[2]) : 1;
    if (last < first) throw bad("LAST < FIRST");
    // Counted before anything is allocated (and without int overflow near INT_MAX).
    const long count = (static_cast<long>(last) - first) / step + 1;
    if (count > 1000) throw bad("more than 1000 sizes (" + std::to_string(count) + ")");
    for (long h = first; h <= last; h += step) out.push_back(static_cast<int>(h));
  } else {
    size_t start = 0;
    for (size_t p; (p = spec.find(',', start)) != std::string::npos; start = p + 1) {
      if (out.size() >= 1000) throw bad("more than 1000 sizes");
      out.push_back(to_int(spec.substr(start, p - start)));
    }
    out.push_back(to_int(spec.substr(start)));
  }
  if (out.size() > 1000) throw bad("more than 1000 sizes");
  return out;
}

namespace internal::nn {

double TrainingCost(const NeuralTrainingOptions& o, int inputs, std::size_t rows) {
  const double P = ParameterCount(inputs, o.hidden);
  return static_cast<double>(o.restarts) * std::max(o.max_epochs, 1) * static_cast<double>(rows) *
         P * P;
}

SweepTasks::SweepTasks(const NeuralDataset& train, const NeuralDataset* validation,
                       const NeuralDataset* test, const HiddenSweepOptions& options)
    : train_(train),
      validation_(validation),
      test_(test),
      options_(options),
      t0_(std::chrono::steady_clock::now()) {
  options.Validate();
  result_.rows.resize(options.hidden_sizes.size());
  result_.runs.resize(options.hidden_sizes.size());
}

void SweepTasks::AddTo(TaskPool* pool) {
  const int inputs = static_cast<int>(train_.input_names.size());
  for (std::size_t k = 0; k < options_.hidden_sizes.size(); ++k) {
    NeuralTrainingOptions o = options_.training;
    o.hidden = options_.hidden_sizes[k];
    pool->Add(TrainingCost(o, inputs, static_cast<std::size_t>(train_.size())),
              [this, k](const ThreadsNow& threads_now) { Train(k, threads_now); });
  }
}

void SweepTasks::Train(std::size_t k, const ThreadsNow& threads_now) {
  NeuralTrainingOptions o = options_.training;
  o.hidden = options_.hidden_sizes[k];
  o.threads_now = threads_now;
  // An initial theta only fits one size: a sweep always initialises from the seed.
  o.initial_parameters.reset();
  o.on_epoch = nullptr;  // networks train side by side: on_network reports
  const auto w0 = std::chrono::steady_clock::now();
  NeuralTrainingResult run = TrainNeuralNetwork(train_, validation_, o);
  HiddenSweepRow& row = result_.rows[k];
  row.hidden = o.hidden;
  row.epochs = run.epochs;
  row.train_mse = run.train_mse;
  row.validation_mse = run.validation_mse;
  row.test_mse =
      test_ ? MeanSquaredError(run.network, *test_) : std::numeric_limits<double>::quiet_NaN();
  row.stop = run.stop;
  row.still_falling = run.still_falling;
  row.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
  result_.runs[k] = std::move(run);
  if (options_.on_network) {
    std::lock_guard<std::mutex> lock(progress_mutex_);
    options_.on_network(row, ++done_, options_.hidden_sizes.size());
  }
}

HiddenSweepResult SweepTasks::Finish() {
  HiddenSweepResult result = std::move(result_);
  const size_t count = result.rows.size();
  auto score = [&](const HiddenSweepRow& r) {
    const double s = validation_ ? r.validation_mse : test_ ? r.test_mse : r.train_mse;
    return std::isfinite(s) ? s : std::numeric_limits<double>::infinity();
  };
  result.rule = validation_ ? "min validation MSE" : test_ ? "min test MSE" : "min training MSE";
  result.chosen = 0;
  for (size_t k = 1; k < count; ++k)
    if (score(result.rows[k]) < score(result.rows[result.chosen]))
      result.chosen = static_cast<int>(k);
  for (const auto& row : result.rows)
    if (row.stop == TrainingStop::kMaxEpochs && options_.training.max_epochs > 0 &&
        row.still_falling)
      result.warnings.push_back("H = " + std::to_string(row.hidden) + " stopped at --max-epochs " +
                                std::to_string(options_.training.max_epochs) +
                                " while its training MSE was still falling; it may be "
                                "under-trained");
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  return result;
}

}  // namespace internal::nn

// Networks run side by side, the largest first (an LM epoch grows with the square of the
// parameter count, and the largest size started last would leave the other threads idle while it
// finishes); each network's passes use the threads the others leave (results do not depend on
// either count).
HiddenSweepResult SweepHiddenSize(const NeuralDataset& train, const NeuralDataset* validation,
                                  const NeuralDataset* test, const HiddenSweepOptions& options) {
  internal::nn::SweepTasks sweep(train, validation, test, options);
  internal::TaskPool pool(options.threads);
  sweep.AddTo(&pool);
  pool.Run();
  return sweep.Finish();
}

}  // namespace sysid
