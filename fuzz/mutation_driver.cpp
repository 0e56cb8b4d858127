// A deterministic mutation fuzzer for CTest, with no compiler requirement: seeded from the
// bundled files, each iteration applies a few random edits (byte flips, deletions, duplicated
// spans, hostile tokens such as 1e400, NUL, control bytes, deep brackets) and runs the target.
// The same seed replays the same inputs; a failing input is written out for replay.
//
//   fuzz_mutations [--input-seconds S --input-mb M] TARGET ITERATIONS SEED CORPUS_FILE...
//
// With the limits, inputs run in child processes (a batch each), every input under S seconds of
// wall time and M MiB of resident memory: a hang, a crash or an input that makes a library fill
// gigabytes fails the run, naming the input (matio and libhdf5 do work a file declares before
// sysid can see it, so the MAT and HDF5 targets run this way).
#include <signal.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_targets.hpp"

namespace {

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

const char* const kTokens[] = {
    "1e400",
    "-1e400",
    "1e-400",
    "NaN",
    "-0",
    "0",
    "-5",
    "1e308",
    "99999999999999999999",
    "\"",
    "\\",
    "[",
    "]",
    "{",
    "}",
    ",",
    ":",
    "null",
    "true",
    "\"\"",
    "\x1b[2J",
    "\x00",
    "\r",
    "\n",
    "\t",
    ";",
    "#",
    "t,u,x",
    "\xff\xfe",
    "\xc2\x9b",
    "1,2,3\n",
    "\"a\":",
    "[[[[[[[[[[[[[[[[",
    "]]]]]]]]]]]]]]]]",
    "1.5e",
    "0x10",
    "+1",
    ".5",
    "5.",
    "e5",
};

std::string Mutate(std::string s, std::mt19937_64& rng) {
  auto pick = [&](std::size_t n) { return n == 0 ? std::size_t{0} : std::size_t(rng() % n); };
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = pick(s.size() + 1);
    switch (rng() % 6) {
      case 0:  // flip a byte
        if (!s.empty()) s[pick(s.size())] ^= static_cast<char>(1u << (rng() % 8));
        break;
      case 1:  // delete a span
        s.erase(at, 1 + pick(16));
        break;
      case 2: {  // duplicate a span
        const std::string span = s.substr(at, 1 + pick(64));
        s.insert(pick(s.size() + 1), span);
        break;
      }
      case 3: {  // insert a hostile token
        const char* t = kTokens[pick(sizeof kTokens / sizeof kTokens[0])];
        s.insert(at, t[0] == '\0' ? std::string(1, '\0') : std::string(t));
        break;
      }
      case 4: {  // replace a number-like run with a token
        const char* t = kTokens[pick(9)];
        std::size_t end = at;
        while (end < s.size() && std::string("0123456789.eE+-").find(s[end]) != std::string::npos)
          ++end;
        s.replace(at, end - at, t);
        break;
      }
      default:  // truncate
        s.resize(at);
        break;
    }
  }
  return s;
}

// What a child tells its parent through shared memory.
struct Shared {
  long current = -1;  ///< the input running (an index into the batch)
  long accepted = 0;
  long rss_kib = 0;  ///< the child's peak resident memory after `current`
  bool over_memory = false;
};

#if defined(__SANITIZE_ADDRESS__)
#define SYSID_FUZZ_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SYSID_FUZZ_SANITIZED 1
#endif
#endif

bool Fail(const std::string& target, long iteration, const std::string& input,
          const std::string& why) {
  const std::string out = "fuzz_failure_" + target + ".bin";
  std::ofstream(out, std::ios::binary) << input;
  std::cerr << "iteration " << iteration << ": " << why << "\n(input written to " << out << ")\n";
  return false;
}

// Runs `inputs` (iterations first..) in one child under the limits; false after reporting the
// input that broke one.
bool RunBatch(const std::string& target, const std::vector<std::string>& inputs, long first,
              unsigned seconds, long limit_mib, long* accepted) {
  auto* shared = static_cast<Shared*>(
      mmap(nullptr, sizeof(Shared), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0));
  if (shared == MAP_FAILED) {
    std::cerr << "mmap failed\n";
    return false;
  }
  *shared = Shared{};
  std::cout.flush();
  const pid_t pid = fork();
  if (pid == 0) {
#ifndef SYSID_FUZZ_SANITIZED
    // A guard for the machine: past it allocations fail (a sanitizer reserves terabytes of
    // address space and cannot run under one).
    const rlim_t guard = static_cast<rlim_t>(3 * limit_mib) << 20;
    const rlimit as{guard, guard};
    setrlimit(RLIMIT_AS, &as);
#endif
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      shared->current = static_cast<long>(i);
      alarm(seconds);  // SIGALRM ends the child: the parent names the input
      try {
        shared->accepted += sysid::fuzz::RunTarget(
            target, reinterpret_cast<const std::uint8_t*>(inputs[i].data()), inputs[i].size());
      } catch (const std::exception& e) {
        std::cerr << e.what() << "\n";
        _exit(2);
      }
      alarm(0);
      rusage usage{};
      getrusage(RUSAGE_SELF, &usage);
      shared->rss_kib = usage.ru_maxrss;
      if (usage.ru_maxrss > limit_mib * 1024) {
        shared->over_memory = true;
        _exit(3);
      }
    }
    std::exit(0);  // not _exit: a leak checker reports at exit
  }
  int status = 0;
  waitpid(pid, &status, 0);
  const Shared result = *shared;
  munmap(shared, sizeof(Shared));
  *accepted += result.accepted;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return true;
  const long i = result.current < 0 ? 0 : result.current;
  const std::string& input = inputs[static_cast<std::size_t>(i)];
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM)
    return Fail(target, first + i, input,
                "took more than " + std::to_string(seconds) + " s (the per-input time limit)");
  if (WIFSIGNALED(status))
    return Fail(target, first + i, input,
                std::string("killed by signal ") + strsignal(WTERMSIG(status)));
  if (result.over_memory)
    return Fail(target, first + i, input,
                "peak resident memory " + std::to_string(result.rss_kib / 1024) +
                    " MiB, more than the per-input limit of " + std::to_string(limit_mib) + " MiB");
  return Fail(target, first + i, input,
              "exited " + std::to_string(WEXITSTATUS(status)) +
                  " (the error, or a sanitizer's report, is above)");
}

}  // namespace

int main(int argc, char** argv) {
  unsigned seconds = 0;
  long limit_mib = 0;
  int a = 1;
  for (; a + 1 < argc && std::strncmp(argv[a], "--input-", 8) == 0; a += 2) {
    if (std::strcmp(argv[a], "--input-seconds") == 0)
      seconds = static_cast<unsigned>(std::stoul(argv[a + 1]));
    else if (std::strcmp(argv[a], "--input-mb") == 0)
      limit_mib = std::stol(argv[a + 1]);
  }
  if (argc - a < 4 || !sysid::fuzz::IsTarget(argv[a]) || (seconds == 0) != (limit_mib == 0)) {
    std::cerr << "usage: fuzz_mutations [--input-seconds S --input-mb M] "
                 "csv|model|network|stage|mat|hdf5 ITERATIONS SEED CORPUS_FILE...\n";
    return 1;
  }
  const std::string target = argv[a];
  const long iterations = std::stol(argv[a + 1]);
  std::mt19937_64 rng(std::stoull(argv[a + 2]));
  std::vector<std::string> corpus;
  for (int i = a + 3; i < argc; ++i) corpus.push_back(ReadAll(argv[i]));
  long accepted = 0;
  if (seconds > 0) {
    // The first seed in this process: the libraries start up once, and the target's scratch
    // file is named here, for every child.
    try {
      (void)sysid::fuzz::RunTarget(target, reinterpret_cast<const std::uint8_t*>(corpus[0].data()),
                                   corpus[0].size());
    } catch (const std::exception& e) {
      std::cerr << argv[a + 3] << ": " << e.what() << "\n";
      return 1;
    }
    constexpr long kBatch = 100;
    for (long first = 0; first < iterations; first += kBatch) {
      std::vector<std::string> batch;
      for (long it = first; it < std::min(iterations, first + kBatch); ++it)
        batch.push_back(Mutate(corpus[static_cast<std::size_t>(it) % corpus.size()], rng));
      if (!RunBatch(target, batch, first, seconds, limit_mib, &accepted)) return 1;
    }
    std::cout << target << ": " << iterations << " mutated inputs, " << accepted
              << " accepted, the rest rejected with a positioned error; each under " << seconds
              << " s and " << limit_mib << " MiB\n";
    return 0;
  }
  for (long it = 0; it < iterations; ++it) {
    const std::string input = Mutate(corpus[it % corpus.size()], rng);
    try {
      accepted += sysid::fuzz::RunTarget(
          target, reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
    } catch (const std::exception& e) {
      const std::string out = "fuzz_failure_" + target + ".bin";
      std::ofstream(out, std::ios::binary) << input;
      std::cerr << "iteration " << it << ": " << e.what() << "\n(input written to " << out << ")\n";
      return 1;
    }
  }
  std::cout << target << ": " << iterations << " mutated inputs, " << accepted
            << " accepted, the rest rejected with a positioned error\n";
  return 0;
}
