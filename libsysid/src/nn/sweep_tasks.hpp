// Network training as tasks of a caller's TaskPool (core/task_pool.hpp): the hidden-size
// sweep's networks can then train beside other work (the pipeline's typical network) instead
// of before it. SweepHiddenSize runs the same tasks in a pool of its own.
#ifndef SYSID_SRC_NN_SWEEP_TASKS_HPP_
#define SYSID_SRC_NN_SWEEP_TASKS_HPP_

#include <chrono>
#include <cstddef>
#include <mutex>

#include "core/task_pool.hpp"
#include "sysid/nn.hpp"

namespace sysid::internal::nn {

/// A TaskPool cost of training `o` (LM) on `rows` samples of `inputs` inputs: restarts x epochs
/// x rows x P^2, the normal equations' rank updates that dominate an epoch.
double TrainingCost(const NeuralTrainingOptions& o, int inputs, std::size_t rows);

/// One hidden-size sweep: its networks as pool tasks, then the rows and the choice.
class SweepTasks {
 public:
  /// Validates the options. The data sets must outlive the pool's Run().
  SweepTasks(const NeuralDataset& train, const NeuralDataset* validation, const NeuralDataset* test,
             const HiddenSweepOptions& options);
  /// One task per hidden size; each network's passes use the pool's ThreadsNow.
  void AddTo(TaskPool* pool);
  /// The sweep's result once the pool has run every task: the rows in hidden_sizes order, the
  /// chosen size, the under-training warnings; wall_time_s counts from construction.
  HiddenSweepResult Finish();

 private:
  void Train(std::size_t k, const ThreadsNow& threads_now);

  const NeuralDataset& train_;
  const NeuralDataset* validation_;
  const NeuralDataset* test_;
  const HiddenSweepOptions& options_;
  HiddenSweepResult result_;
  std::mutex progress_mutex_;
  std::size_t done_ = 0;  // networks finished, under progress_mutex_
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace sysid::internal::nn

#endif  // SYSID_SRC_NN_SWEEP_TASKS_HPP_
