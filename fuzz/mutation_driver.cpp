// A deterministic mutation fuzzer for CTest, with no compiler requirement: seeded from the
// bundled files, each iteration applies a few random edits (byte flips, deletions, duplicated
// spans, hostile tokens such as 1e400, NUL, control bytes, deep brackets) and runs the target.
// The same seed replays the same inputs; a failing input is written out for replay.
//
//   fuzz_mutations TARGET ITERATIONS SEED CORPUS_FILE...
#include <cstdint>
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
    "1e400", "-1e400", "1e-400", "NaN", "-0", "0", "-5", "1e308", "99999999999999999999",
    "\"", "\\", "[", "]", "{", "}", ",", ":", "null", "true", "\"\"", "\x1b[2J", "\x00",
    "\r", "\n", "\t", ";", "#", "t,u,x", "\xff\xfe", "\xc2\x9b", "1,2,3\n", "\"a\":",
    "[[[[[[[[[[[[[[[[", "]]]]]]]]]]]]]]]]", "1.5e", "0x10", "+1", ".5", "5.", "e5",
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

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5 || !sysid::fuzz::IsTarget(argv[1])) {
    std::cerr << "usage: fuzz_mutations csv|model|network|stage ITERATIONS SEED CORPUS_FILE...\n";
    return 1;
  }
  const std::string target = argv[1];
  const long iterations = std::stol(argv[2]);
  std::mt19937_64 rng(std::stoull(argv[3]));
  std::vector<std::string> corpus;
  for (int i = 4; i < argc; ++i) corpus.push_back(ReadAll(argv[i]));
  long accepted = 0;
  for (long it = 0; it < iterations; ++it) {
    const std::string input = Mutate(corpus[it % corpus.size()], rng);
    try {
      accepted += sysid::fuzz::RunTarget(
          target, reinterpret_cast<const std::uint8_t*>(input.data()), input.size());
    } catch (const std::exception& e) {
      const std::string out = "fuzz_failure_" + target + ".bin";
      std::ofstream(out, std::ios::binary) << input;
      std::cerr << "iteration " << it << ": " << e.what() << "\n(input written to " << out
                << ")\n";
      return 1;
    }
  }
  std::cout << target << ": " << iterations << " mutated inputs, " << accepted
            << " accepted, the rest rejected with a positioned error\n";
  return 0;
}
