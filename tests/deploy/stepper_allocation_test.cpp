// The streaming inverses allocate nothing per sample: a counting operator new (this test
// executable's only replacement of the new and delete family) and, where the linker wraps it, a counting malloc (Eigen's
// storage in libsysid.a) see no allocation over 10^5 steps of each.
#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <new>
#include <vector>

#include "support/known_pi.hpp"
#include "sysid/hysteresis_stepper.hpp"
#include "sysid/model_stepper.hpp"
#include "sysid/nn_stepper.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

#ifdef SYSID_TEST_WRAP_MALLOC
// Linked with -Wl,--wrap=malloc (tests/CMakeLists.txt): every malloc call from the test and
// from libsysid.a (Eigen's storage) comes here first.
extern "C" void* __real_malloc(std::size_t size);
extern "C" void* __wrap_malloc(std::size_t size) {
  ++g_allocations;
  return __real_malloc(size);
}
#endif

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// Every form that pairs with the plain delete is replaced too: under AddressSanitizer an
// unreplaced form keeps the sanitizer's allocator, and its memory freed here is a mismatch.
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  ++g_allocations;
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
  return operator new(size, tag);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

TEST_CASE("streaming inverses do not allocate inside Step", "[deploy][stream]") {
  constexpr int kSteps = 100000;
  sysid::FrictionInverseStepper friction(sysid::FrictionModel::Paper(), 1e-4);
  sysid::NeuralNetwork net({{"v", "m/s", -0.1, 0.1}, {"a", "m/s^2", -1, 1}}, {"u", "V", -2, 2},
                           24);
  Eigen::VectorXd theta = Eigen::VectorXd::LinSpaced(net.parameter_count(), -1, 1);
  net.set_parameters(theta);
  sysid::NetworkStepper network(net);
  const sysid::PrandtlIshlinskiiModel pi(sysid::test::KnownPiParameters());
  sysid::PiInverseStepper inverse(pi, 5e-3);
  sysid::PiezoBoucWenParameters bw;
  bw.d_m_per_v = 1e-6;
  bw.alpha = 0.3;
  bw.beta_per_v = 0.05;
  bw.gamma_per_v = 0.02;
  sysid::BoucWenInverseStepper bouc_wen{sysid::PiezoBoucWen(bw)};
  const long before = g_allocations.load();
  double sum = 0;
  for (int k = 0; k < kSteps; ++k) {
    const double t = 1e-4 * k, v = 0.05 * std::sin(7 * t), a = 0.35 * std::cos(7 * t);
    sum += friction.Step(v, a);
    const double x[2] = {v, a};
    sum += network.Step(x);
    sum += inverse.Step(-1e-4 + 5e-6 * (1 + std::sin(3 * t)));
    sum += bouc_wen.Step(5e-6 * std::sin(3 * t));
  }
  friction.Reset();
  inverse.Reset();
  CHECK(g_allocations.load() - before == 0);
  CHECK(std::isfinite(sum));
  // The shim counts: one vector is one allocation.
  const long after = g_allocations.load();
  std::vector<double>* probe = new std::vector<double>(3);
  delete probe;
  CHECK(g_allocations.load() - after >= 2);  // 4 where malloc is counted too
#ifdef SYSID_TEST_WRAP_MALLOC
  // And an Eigen vector, whose storage is malloc'd, is counted too.
  const long before_eigen = g_allocations.load();
  const Eigen::VectorXd probe_eigen = Eigen::VectorXd::Constant(1000, sum);
  CHECK(g_allocations.load() - before_eigen >= 1);
  CHECK(probe_eigen[999] == sum);
#endif
}
