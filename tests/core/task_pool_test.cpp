// TaskPool: the costliest tasks start first, a task's thread share grows when the others finish,
// and a failure stops the pool. References: the start order and shares worked out by hand for
// tasks that wait on each other (every wait has a deadline: a broken pool fails, never hangs).
#include "core/task_pool.hpp"

#include <atomic>
#include <catch2/catch.hpp>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using sysid::internal::TaskPool;
using sysid::internal::ThreadsNow;

namespace {

// Waits until `done()` holds, at most 20 s; whether it held.
template <class Done>
bool WaitFor(const Done& done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return true;
}

}  // namespace

TEST_CASE("task pool: on one thread, tasks run costliest first, ties in the order added",
          "[core][task_pool]") {
  TaskPool pool(1);
  std::vector<std::string> ran;
  std::vector<int> shares;
  for (const auto& [name, cost] : std::vector<std::pair<std::string, double>>{
           {"small", 1}, {"large", 9}, {"mid a", 4}, {"mid b", 4}, {"zero", 0}})
    pool.Add(cost, [&, name = name](const ThreadsNow& now) {
      ran.push_back(name);
      shares.push_back(now());
    });
  pool.Run();
  CHECK(ran == std::vector<std::string>{"large", "mid a", "mid b", "small", "zero"});
  CHECK(shares == std::vector<int>(5, 1));
}

TEST_CASE("task pool: two threads share the cores until one runs alone, then it has both",
          "[core][task_pool]") {
  // Costs 3, 2, 1 on two threads: "large" and "mid" start together (1 thread each); "small"
  // starts when "mid" ends, on mid's thread; when small ends too, that thread finds no task
  // and "large", running alone, may use 2.
  TaskPool pool(2);
  std::atomic<bool> mid_started{false}, large_saw_half{false}, small_done{false};
  std::atomic<int> large_share{0}, mid_share{0}, small_share{0};
  std::atomic<bool> small_started_before_mid_ended{false}, mid_ended{false};
  std::atomic<bool> large_got_all{false}, waits_held{true};
  // No Catch assertion on the pool's threads (Catch 2 is not thread-safe): flags, checked after.
  pool.Add(1, [&](const ThreadsNow& now) {  // small
    small_started_before_mid_ended = !mid_ended;
    small_share = now();
    small_done = true;
  });
  pool.Add(3, [&](const ThreadsNow& now) {  // large
    if (!WaitFor([&] { return mid_started.load(); })) waits_held = false;
    large_share = now();
    large_saw_half = true;
    if (!WaitFor([&] { return small_done.load(); })) waits_held = false;
    large_got_all = WaitFor([&] { return now() == 2; });
  });
  pool.Add(2, [&](const ThreadsNow& now) {  // mid
    mid_started = true;
    mid_share = now();
    if (!WaitFor([&] { return large_saw_half.load(); })) waits_held = false;
    mid_ended = true;
  });
  pool.Run();
  REQUIRE(waits_held);
  CHECK(large_share == 1);
  CHECK(mid_share == 1);
  CHECK_FALSE(small_started_before_mid_ended);
  CHECK(small_share == 1);  // large still runs beside it
  CHECK(large_got_all);
}

TEST_CASE("task pool: a failed task stops the pool, and the failure added first is rethrown",
          "[core][task_pool]") {
  SECTION("one thread: the tasks after the failure do not start") {
    TaskPool pool(1);
    int later = 0;
    pool.Add(1, [&](const ThreadsNow&) { ++later; });
    pool.Add(2, [](const ThreadsNow&) { throw std::runtime_error("large failed"); });
    CHECK_THROWS_WITH(pool.Run(), "large failed");
    CHECK(later == 0);
  }
  SECTION("two threads, both fail: the one added first") {
    TaskPool pool(2);
    std::atomic<int> started{0};
    auto fail = [&](const std::string& what) {
      return [&started, what](const ThreadsNow&) {
        ++started;
        // Both run before either throws: the choice cannot be by time.
        const bool both = WaitFor([&] { return started.load() == 2; });
        throw std::runtime_error(both ? what : "only one task started");
      };
    };
    pool.Add(1, fail("added first"));
    pool.Add(5, fail("added second"));
    CHECK_THROWS_WITH(pool.Run(), "added first");
  }
}
