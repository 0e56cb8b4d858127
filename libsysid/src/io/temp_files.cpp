#include "io/temp_files.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>

namespace sysid::internal {
namespace {

constexpr int kSlots = 64;
constexpr std::size_t kPathBytes = 4096;

// Slot states: 0 free, 1 being filled, 2 live (the handler unlinks live slots only).
std::atomic<int> g_state[kSlots];
char g_path[kSlots][kPathBytes];

extern "C" void RemoveTempFilesAndReraise(int sig) {
  // Async-signal-safe: atomic loads, unlink, signal, raise.
  for (int i = 0; i < kSlots; ++i)
    if (g_state[i].load() == 2) ::unlink(g_path[i]);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void InstallHandlers() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;
    struct sigaction sa {};
    sa.sa_handler = &RemoveTempFilesAndReraise;
    sigemptyset(&sa.sa_mask);
    sigaction(sig, &sa, nullptr);
  }
}

}  // namespace

TempFileGuard::TempFileGuard(const std::string& path) {
  // Checked at every registration (two sigaction calls beside a file write): a program that
  // sets its own handlers later keeps them, one that restores the defaults gets ours again.
  InstallHandlers();
  if (path.size() >= kPathBytes) return;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!g_state[i].compare_exchange_strong(expected, 1)) continue;
    std::memcpy(g_path[i], path.c_str(), path.size() + 1);
    g_state[i].store(2);
    slot_ = i;
    return;
  }
}

TempFileGuard::~TempFileGuard() {
  if (slot_ >= 0) g_state[slot_].store(0);
}

}  // namespace sysid::internal
