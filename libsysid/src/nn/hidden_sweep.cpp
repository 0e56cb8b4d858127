// SweepHiddenSize: one network per hidden size, trained in parallel threads.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

#include "core/option_rule.hpp"
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

HiddenSweepResult SweepHiddenSize(const NeuralDataset& train, const NeuralDataset* validation,
                                  const NeuralDataset* test, const HiddenSweepOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  options.Validate();
  const size_t count = options.hidden_sizes.size();
  HiddenSweepResult result;
  result.rows.resize(count);
  result.runs.resize(count);
  // Networks run side by side; each one's epoch gets the threads left over (results do not
  // depend on either count).
  const unsigned all = options.threads > 0 ? static_cast<unsigned>(options.threads)
                                           : std::max(1u, std::thread::hardware_concurrency());
  const unsigned threads = std::max(1u, std::min<unsigned>(all, static_cast<unsigned>(count)));
  const int inner = static_cast<int>(std::max(1u, all / threads));
  // Largest networks first: an LM epoch grows with the square of the parameter count, and the
  // largest size started last leaves the other threads idle while it finishes.
  std::vector<size_t> order(count);
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return options.hidden_sizes[a] > options.hidden_sizes[b];
  });
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  std::mutex progress_mutex;
  size_t done = 0;  // networks finished, under progress_mutex
  auto worker = [&] {
    for (size_t i; (i = next++) < count;) {
      const size_t k = order[i];
      try {
        NeuralTrainingOptions o = options.training;
        o.hidden = options.hidden_sizes[k];
        o.threads = inner;
        // An initial theta only fits one size: a sweep always initialises from the seed.
        o.initial_parameters.reset();
        o.on_epoch = nullptr;  // networks train side by side: on_network reports
        const auto w0 = std::chrono::steady_clock::now();
        NeuralTrainingResult run = TrainNeuralNetwork(train, validation, o);
        HiddenSweepRow& row = result.rows[k];
        row.hidden = o.hidden;
        row.epochs = run.epochs;
        row.train_mse = run.train_mse;
        row.validation_mse = run.validation_mse;
        row.test_mse =
            test ? MeanSquaredError(run.network, *test) : std::numeric_limits<double>::quiet_NaN();
        row.stop = run.stop;
        row.still_falling = run.still_falling;
        row.wall_time_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count();
        result.runs[k] = std::move(run);
        if (options.on_network) {
          std::lock_guard<std::mutex> lock(progress_mutex);
          options.on_network(row, ++done, count);
        }
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next = count;  // the first error ends the sweep
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);

  auto score = [&](const HiddenSweepRow& r) {
    const double s = validation ? r.validation_mse : test ? r.test_mse : r.train_mse;
    return std::isfinite(s) ? s : std::numeric_limits<double>::infinity();
  };
  result.rule = validation ? "min validation MSE" : test ? "min test MSE" : "min training MSE";
  result.chosen = 0;
  for (size_t k = 1; k < count; ++k)
    if (score(result.rows[k]) < score(result.rows[result.chosen]))
      result.chosen = static_cast<int>(k);
  for (const auto& row : result.rows)
    if (row.stop == TrainingStop::kMaxEpochs && options.training.max_epochs > 0 &&
        row.still_falling)
      result.warnings.push_back("H = " + std::to_string(row.hidden) + " stopped at --max-epochs " +
                                std::to_string(options.training.max_epochs) +
                                " while its training MSE was still falling; it may be "
                                "under-trained");
  result.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace sysid
