// A downstream program: parses a model and prints its steady-state velocity at 1.6 V.
#include <sysid/model.hpp>

#include <cstdio>

int main() {
  const sysid::FrictionModel m = sysid::ParseModel(
      R"({"a1p":104.0154,"a1n":117.1441,"a2p":3.1023,"a2n":6.8216,"a3":6,"tau":0.0035})",
      "inline");
  std::printf("a1p=%.4f v(1.6 V)=%.6f m/s\n", m.a1p, m.SteadyVelocity(1.6));
  return 0;
}
