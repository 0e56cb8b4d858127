// The fixed-length vector operations (core/small_vector_ops.hpp) against SUNDIALS' own serial
// operations, bit for bit: every special case of N_VLinearSum_Serial, in place and not, and the
// vector-array operations CVODES calls on its sensitivities.
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "core/small_vector_ops.hpp"

namespace sysid {
namespace {

bool SameBits(N_Vector a, N_Vector b) {
  return std::memcmp(NV_DATA_S(a), NV_DATA_S(b), sizeof(double) * NV_LENGTH_S(a)) == 0;
}

struct Vectors {
  N_Vector ours[4], theirs[4];  // same numbers; ours with the small operations
  Vectors(int n, SUNContext ctx, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    N_Vector tmpl = N_VNew_Serial(n, ctx);
    REQUIRE(internal::UseSmallVectorOps(tmpl));
    for (int k = 0; k < 4; ++k) {
      ours[k] = N_VClone(tmpl);
      theirs[k] = N_VNew_Serial(n, ctx);
      for (int i = 0; i < n; ++i) NV_Ith_S(ours[k], i) = NV_Ith_S(theirs[k], i) = u(rng) / 7.0;
    }
    N_VDestroy(tmpl);
  }
  ~Vectors() {
    for (int k = 0; k < 4; ++k) {
      N_VDestroy(ours[k]);
      N_VDestroy(theirs[k]);
    }
  }
  bool Same(int k) const { return SameBits(ours[k], theirs[k]); }
};

TEST_CASE("small vector operations are bit-identical to SUNDIALS' serial ones", "[core][cvode]") {
  SUNContext ctx = nullptr;
  REQUIRE(SUNContext_Create(nullptr, &ctx) == 0);
  std::mt19937 rng(7);
  const double a = 0.3718, b = -1.9;
  const std::vector<std::pair<double, double>> coefficients = {
      {1, 1}, {1, -1}, {-1, 1}, {-1, -1}, {a, a}, {a, -a}, {-a, a}, {1, b}, {b, 1},
      {-1, b}, {b, -1}, {a, b}, {0, b}, {a, 0}, {0, 0}, {1, 0}, {0, -1}};
  int cases = 0;
  for (int n = 1; n <= 4; ++n) {
    for (const auto& [ca, cb] : coefficients)
      for (int alias = 0; alias < 3; ++alias) {  // z apart, z = x, z = y
        Vectors v(n, ctx, rng);
        const int z = alias == 0 ? 2 : alias == 1 ? 0 : 1;
        N_VLinearSum(ca, v.ours[0], cb, v.ours[1], v.ours[z]);
        N_VLinearSum_Serial(ca, v.theirs[0], cb, v.theirs[1], v.theirs[z]);
        INFO("n = " << n << ", a = " << ca << ", b = " << cb << ", alias " << alias);
        CHECK(v.Same(z));
        ++cases;
      }
    for (double c : {1.0, -1.0, a, 0.0})
      for (int alias = 0; alias < 2; ++alias) {
        Vectors v(n, ctx, rng);
        const int z = alias == 0 ? 1 : 0;
        N_VScale(c, v.ours[0], v.ours[z]);
        N_VScale_Serial(c, v.theirs[0], v.theirs[z]);
        CHECK(v.Same(z));
      }
    {
      Vectors v(n, ctx, rng);
      const double ours = N_VWrmsNorm(v.ours[0], v.ours[1]);
      const double theirs = N_VWrmsNorm_Serial(v.theirs[0], v.theirs[1]);
      CHECK(std::memcmp(&ours, &theirs, sizeof ours) == 0);
      N_VConst(0.0, v.ours[2]);
      CHECK(N_VWrmsNorm(v.ours[2], v.ours[1]) == 0.0);
    }
    for (int alias = 0; alias < 2; ++alias) {  // the error weights' operations
      Vectors v(n, ctx, rng);
      const int z = alias == 0 ? 1 : 0;
      N_VAbs(v.ours[0], v.ours[z]);
      N_VAbs_Serial(v.theirs[0], v.theirs[z]);
      CHECK(v.Same(z));
      N_VAddConst(v.ours[z], 1e-12, v.ours[2]);
      N_VAddConst_Serial(v.theirs[z], 1e-12, v.theirs[2]);
      CHECK(v.Same(2));
      N_VInv(v.ours[2], v.ours[3]);
      N_VInv_Serial(v.theirs[2], v.theirs[3]);
      CHECK(v.Same(3));
    }
    // Linear combinations of 1 to 3 vectors, with the two-vector special cases and z = X[0].
    for (const auto& [ca, cb] : coefficients)
      for (int nvec = 1; nvec <= 3; ++nvec)
        for (int alias = 0; alias < 2; ++alias) {
          Vectors v(n, ctx, rng);
          double c[3] = {ca, cb, a};
          const int z = alias == 0 ? 3 : 0;
          N_Vector xo[3] = {v.ours[0], v.ours[1], v.ours[2]};
          N_Vector xt[3] = {v.theirs[0], v.theirs[1], v.theirs[2]};
          REQUIRE(N_VLinearCombination(nvec, c, xo, v.ours[z]) == 0);
          REQUIRE(N_VLinearCombination_Serial(nvec, c, xt, v.theirs[z]) == 0);
          INFO("n = " << n << ", nvec = " << nvec << ", c = " << ca << ", " << cb);
          CHECK(v.Same(z));
        }
    // Z[i] = a[i] x + Y[i], apart and in place, one and two vectors.
    for (int nvec = 1; nvec <= 2; ++nvec)
      for (double c0 : {1.0, -1.0, a}) {
        Vectors v(n, ctx, rng), w(n, ctx, rng);
        double c[2] = {c0, b};
        N_Vector yo[2] = {v.ours[1], v.ours[2]}, yt[2] = {v.theirs[1], v.theirs[2]};
        N_Vector zo[2] = {v.ours[3], w.ours[0]}, zt[2] = {v.theirs[3], w.theirs[0]};
        REQUIRE(N_VScaleAddMulti(nvec, c, v.ours[0], yo, zo) == 0);
        REQUIRE(N_VScaleAddMulti_Serial(nvec, c, v.theirs[0], yt, zt) == 0);
        CHECK(v.Same(3));
        CHECK(w.Same(0));
        REQUIRE(N_VScaleAddMulti(nvec, c, v.ours[0], yo, yo) == 0);
        REQUIRE(N_VScaleAddMulti_Serial(nvec, c, v.theirs[0], yt, yt) == 0);
        CHECK(v.Same(1));
        CHECK(v.Same(2));
      }
  }
  CHECK(cases == 4 * 17 * 3);
  SUNContext_Free(&ctx);
}

// CVODES' vector-array operations on its sensitivities (one vector per parameter): arrays of 1
// to 3 vectors of each length, every linear-sum special case, apart and in place.
TEST_CASE("small vector-array operations are bit-identical to SUNDIALS' serial ones",
          "[core][cvode]") {
  SUNContext ctx = nullptr;
  REQUIRE(SUNContext_Create(nullptr, &ctx) == 0);
  std::mt19937 rng(11);
  const double a = 0.3718, b = -1.9;
  const std::vector<std::pair<double, double>> coefficients = {
      {1, 1}, {1, -1}, {-1, 1}, {-1, -1}, {a, a}, {a, -a}, {-a, a}, {1, b}, {b, 1},
      {-1, b}, {b, -1}, {a, b}, {0, b}, {a, 0}, {0, 0}, {1, 0}, {0, -1}};
  // Array k of `ours` / `theirs` is vector k of every Vectors in `sets` (k = 0..3).
  struct Arrays {
    std::vector<std::unique_ptr<Vectors>> sets;
    std::vector<N_Vector> ours[4], theirs[4];
    Arrays(int n, int nvec, SUNContext ctx, std::mt19937& rng) {
      for (int i = 0; i < nvec; ++i) {
        sets.push_back(std::make_unique<Vectors>(n, ctx, rng));
        for (int k = 0; k < 4; ++k) {
          ours[k].push_back(sets.back()->ours[k]);
          theirs[k].push_back(sets.back()->theirs[k]);
        }
      }
    }
    bool Same(int k) const {
      for (const auto& v : sets)
        if (!v->Same(k)) return false;
      return true;
    }
  };
  int cases = 0;
  for (int n = 1; n <= 4; ++n)
    for (int nvec = 1; nvec <= 3; ++nvec) {
      INFO("n = " << n << ", nvec = " << nvec);
      for (const auto& [ca, cb] : coefficients)
        for (int alias = 0; alias < 3; ++alias) {  // Z apart, Z = X, Z = Y
          Arrays v(n, nvec, ctx, rng);
          const int z = alias == 0 ? 2 : alias == 1 ? 0 : 1;
          INFO("a = " << ca << ", b = " << cb << ", alias " << alias);
          REQUIRE(N_VLinearSumVectorArray(nvec, ca, v.ours[0].data(), cb, v.ours[1].data(),
                                          v.ours[z].data()) == 0);
          REQUIRE(N_VLinearSumVectorArray_Serial(nvec, ca, v.theirs[0].data(), cb,
                                                 v.theirs[1].data(), v.theirs[z].data()) == 0);
          CHECK(v.Same(z));
          ++cases;
        }
      for (int alias = 0; alias < 2; ++alias) {
        Arrays v(n, nvec, ctx, rng);
        const int z = alias == 0 ? 1 : 0;
        double c[3] = {a, -1.0, b};
        REQUIRE(N_VScaleVectorArray(nvec, c, v.ours[0].data(), v.ours[z].data()) == 0);
        REQUIRE(N_VScaleVectorArray_Serial(nvec, c, v.theirs[0].data(), v.theirs[z].data()) == 0);
        CHECK(v.Same(z));
        REQUIRE(N_VConstVectorArray(nvec, b, v.ours[2].data()) == 0);
        REQUIRE(N_VConstVectorArray_Serial(nvec, b, v.theirs[2].data()) == 0);
        CHECK(v.Same(2));
      }
      {
        Arrays v(n, nvec, ctx, rng);
        double ours[3] = {}, theirs[3] = {};
        REQUIRE(N_VWrmsNormVectorArray(nvec, v.ours[0].data(), v.ours[1].data(), ours) == 0);
        REQUIRE(N_VWrmsNormVectorArray_Serial(nvec, v.theirs[0].data(), v.theirs[1].data(),
                                              theirs) == 0);
        CHECK(std::memcmp(ours, theirs, sizeof ours) == 0);
        N_VConstVectorArray(nvec, 0.0, v.ours[2].data());
        REQUIRE(N_VWrmsNormVectorArray(nvec, v.ours[2].data(), v.ours[1].data(), ours) == 0);
        for (int i = 0; i < nvec; ++i) CHECK(ours[i] == 0.0);
      }
      // Z[j][i] = a[j] X[i] + Y[j][i] for 1 to 3 sums, apart and in place.
      for (int nsum = 1; nsum <= 3; ++nsum)
        for (double c0 : {1.0, -1.0, a}) {
          Arrays v(n, nvec, ctx, rng), w(n, nvec, ctx, rng);
          double c[3] = {c0, b, -1.0};
          N_Vector* yo[3] = {v.ours[1].data(), v.ours[2].data(), w.ours[1].data()};
          N_Vector* yt[3] = {v.theirs[1].data(), v.theirs[2].data(), w.theirs[1].data()};
          N_Vector* zo[3] = {v.ours[3].data(), w.ours[0].data(), w.ours[2].data()};
          N_Vector* zt[3] = {v.theirs[3].data(), w.theirs[0].data(), w.theirs[2].data()};
          INFO("nsum = " << nsum << ", a0 = " << c0);
          REQUIRE(N_VScaleAddMultiVectorArray(nvec, nsum, c, v.ours[0].data(), yo, zo) == 0);
          REQUIRE(N_VScaleAddMultiVectorArray_Serial(nvec, nsum, c, v.theirs[0].data(), yt,
                                                     zt) == 0);
          CHECK(v.Same(3));
          CHECK(w.Same(0));
          CHECK(w.Same(2));
          REQUIRE(N_VScaleAddMultiVectorArray(nvec, nsum, c, v.ours[0].data(), yo, yo) == 0);
          REQUIRE(N_VScaleAddMultiVectorArray_Serial(nvec, nsum, c, v.theirs[0].data(), yt,
                                                     yt) == 0);
          CHECK(v.Same(1));
          CHECK(v.Same(2));
          CHECK(w.Same(1));
        }
      // Z[j] = sum over i of c[i] X[i][j], 1 to 3 terms (two: the linear-sum cases), and
      // Z = X[0] with c[0] = 1 and not.
      for (const auto& [ca, cb] : coefficients)
        for (int nsum = 1; nsum <= 3; ++nsum)
          for (int alias = 0; alias < 2; ++alias) {
            Arrays v(n, nvec, ctx, rng);
            double c[3] = {ca, cb, a};
            const int z = alias == 0 ? 3 : 0;
            N_Vector* xo[3] = {v.ours[0].data(), v.ours[1].data(), v.ours[2].data()};
            N_Vector* xt[3] = {v.theirs[0].data(), v.theirs[1].data(), v.theirs[2].data()};
            INFO("nsum = " << nsum << ", c = " << ca << ", " << cb << ", alias " << alias);
            REQUIRE(N_VLinearCombinationVectorArray(nvec, nsum, c, xo, v.ours[z].data()) == 0);
            REQUIRE(N_VLinearCombinationVectorArray_Serial(nvec, nsum, c, xt,
                                                           v.theirs[z].data()) == 0);
            CHECK(v.Same(z));
          }
    }
  CHECK(cases == 4 * 3 * 17 * 3);
  // Other lengths keep SUNDIALS' operations.
  N_Vector big = N_VNew_Serial(5, ctx);
  CHECK_FALSE(internal::UseSmallVectorOps(big));
  CHECK(big->ops->nvlinearsum == &N_VLinearSum_Serial);
  N_VDestroy(big);
  SUNContext_Free(&ctx);
}

}  // namespace
}  // namespace sysid
