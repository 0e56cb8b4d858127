// A deterministic parallel loop: items 0..count-1 are handed out to `threads` std::threads
// (the caller's thread is one of them). Results must be written per item, so the outcome does
// not depend on the thread count; reductions are then done by the caller in item order.
#ifndef SYSID_SRC_CORE_PARALLEL_FOR_HPP_
#define SYSID_SRC_CORE_PARALLEL_FOR_HPP_

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace sysid::internal {

/// Threads to use for a request of `requested` (0 or less: all hardware threads), at most
/// `items` and at least 1.
inline int ResolveThreads(int requested, long items) {
  int t = requested > 0 ? requested : static_cast<int>(std::thread::hardware_concurrency());
  t = std::max(t, 1);
  if (items < t) t = static_cast<int>(std::max(items, 1L));
  return t;
}

/// Calls f(i) once for every i in [0, count) on up to `threads` threads. The first exception
/// (lowest item index) is rethrown after all threads finish.
template <class F>
void ParallelFor(long count, int threads, const F& f) {
  threads = ResolveThreads(threads, count);
  if (threads <= 1) {
    for (long i = 0; i < count; ++i) f(i);
    return;
  }
  std::atomic<long> next{0};
  std::mutex m;
  long error_item = count;
  std::exception_ptr error;
  auto worker = [&] {
    for (long i; (i = next.fetch_add(1)) < count;) {
      try {
        f(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(m);
        if (i < error_item) {
          error_item = i;
          error = std::current_exception();
        }
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<std::size_t>(threads - 1));
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace sysid::internal

#endif  // SYSID_SRC_CORE_PARALLEL_FOR_HPP_
