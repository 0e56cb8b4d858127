// Tasks of unequal cost side by side on a fixed number of threads, the costliest first, each
// told while it runs how many threads its own parallel loops may use.
#ifndef SYSID_SRC_CORE_TASK_POOL_HPP_
#define SYSID_SRC_CORE_TASK_POOL_HPP_

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <numeric>
#include <thread>
#include <utility>
#include <vector>

namespace sysid::internal {

/// The threads a task's inner loops (ParallelFor) may use at the moment it asks.
using ThreadsNow = std::function<int()>;

/// Runs tasks on `threads` threads (0 or less: all hardware threads), the costliest first: a
/// large task started last would run alone at the end while the other threads idle. A task gets
/// a ThreadsNow: the pool's threads over the tasks running when it is called (at least 1), so
/// the tasks still running when the others have finished take over their threads. Only for work
/// whose results do not depend on its thread count (ParallelFor's fixed partitions).
class TaskPool {
 public:
  using Task = std::function<void(const ThreadsNow&)>;

  explicit TaskPool(int threads)
      : threads_(threads > 0 ? threads
                             : std::max(1, static_cast<int>(std::thread::hardware_concurrency()))) {
  }

  /// `cost`: any unit, the same for every task of the pool (e.g. flops); equal costs keep the
  /// order of Add.
  void Add(double cost, Task task) { tasks_.push_back({cost, std::move(task)}); }

  int threads() const { return threads_; }

  /// Runs every task and returns when all are done. After a task throws no other task starts;
  /// the exception of the failed task added first is rethrown once the running ones finish.
  void Run() {
    const std::size_t count = tasks_.size();
    std::vector<std::size_t> order(count);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return tasks_[a].cost > tasks_[b].cost; });
    const int workers = static_cast<int>(
        std::min<std::size_t>(static_cast<std::size_t>(threads_), std::max<std::size_t>(count, 1)));
    // Workers that still have a task: one finding the queue empty leaves its threads to the
    // others.
    std::atomic<int> running{workers};
    const int total = threads_;
    const ThreadsNow now = [&running, total] {
      return std::max(1, total / std::max(1, running.load()));
    };
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::mutex error_mutex;
    std::size_t error_task = count;
    std::exception_ptr error;
    auto worker = [&] {
      for (std::size_t i; !failed && (i = next++) < count;) {
        try {
          tasks_[order[i]].run(now);
        } catch (...) {
          std::lock_guard<std::mutex> lock(error_mutex);
          failed = true;
          if (order[i] < error_task) {
            error_task = order[i];
            error = std::current_exception();
          }
        }
      }
      --running;
    };
    std::vector<std::thread> pool;
    pool.reserve(static_cast<std::size_t>(workers - 1));
    for (int t = 1; t < workers; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    tasks_.clear();
    if (error) std::rethrow_exception(error);
  }

 private:
  struct Entry {
    double cost;
    Task run;
  };
  int threads_;
  std::vector<Entry> tasks_;
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_CORE_TASK_POOL_HPP_
