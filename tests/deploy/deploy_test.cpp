// The export's parts against references it did not produce: SHA-256 against FIPS 180-2's
// examples, C literals parsed back by the C library, the generated step's refusal of what it
// cannot export, and the program's exit codes with nothing written.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "deploy/c_text.hpp"
#include "support/known_pi.hpp"
#include "support/test_support.hpp"
#include "sysid/deploy.hpp"
#include "sysid/error.hpp"

using Catch::Matchers::Contains;

TEST_CASE("SHA-256 gives FIPS 180-2's digests", "[deploy]") {
  CHECK(sysid::Sha256Hex("") ==
        "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sysid::Sha256Hex("abc") ==
        "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sysid::Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  CHECK(sysid::Sha256Hex(std::string(1000000, 'a')) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("C literals parse back to the same number", "[deploy]") {
  for (double x : {0.0, 1.0, -2.5, 0.1, 1.0 / 3, 104.0154, 6.8216e-300, -1.7976931348623157e308,
                   3.7e-6, 123456789.0}) {
    const std::string d = sysid::internal::CLiteral(x, sysid::ExportPrecision::kDouble);
    CHECK(d.find_first_of(".e") != std::string::npos);  // a floating literal, never an int
    CHECK(std::strtod(d.c_str(), nullptr) == x);
    const std::string f = sysid::internal::CLiteral(x, sysid::ExportPrecision::kFloat);
    CHECK(f.back() == 'f');
    if (std::abs(x) < 1e38 && (x == 0 || std::abs(x) > 1e-37))
      CHECK(std::strtof(f.c_str(), nullptr) == static_cast<float>(x));
  }
}

TEST_CASE("export refuses what it cannot generate", "[deploy]") {
  const sysid::ExportProvenance prov{"m.json", std::string(64, '0')};
  sysid::ExportOptions o;
  for (const char* bad : {"int", "static", "1abc", "_x", "a-b", ""}) {
    o.prefix = bad;
    INFO(bad);
    CHECK_THROWS_AS(o.Validate(), sysid::OptionsError);
  }
  o.prefix = "ff_1";
  CHECK_NOTHROW(o.Validate());
  sysid::FrictionModel m = sysid::FrictionModel::Paper();
  // tau / dt = 5000 samples: beyond the exported delay line.
  CHECK_THROWS_WITH(
      sysid::ExportFrictionInverse(m, 7e-7, sysid::DefaultFrictionVectors(7e-7), o, prov),
      Contains("kMaxExportDelaySamples"));
  m.a3 = 0;
  CHECK_THROWS_AS(
      sysid::ExportFrictionInverse(m, 1e-3, sysid::DefaultFrictionVectors(1e-3), o, prov),
      sysid::OptionsError);
  sysid::PiParameters g = sysid::test::KnownPiParameters();
  g.form = sysid::PiForm::kPolynomial;
  g.polynomial = {4e-6, 0.0, 2e-8};
  const sysid::PrandtlIshlinskiiModel gpi(g);
  o.precision = sysid::ExportPrecision::kFloat;
  CHECK(sysid::ExportPiInverse(gpi, 5e-3, sysid::DefaultPiVectors(gpi, 5e-3), o, prov).bound_v > 0);
  // An rdpi whose inverse the library runs (error gain 0.76 < 1) but whose rate feedback
  // leaves the float bound no contraction (4 sum q max|u| / (dt s_min) = 3.0): double only.
  sysid::PiParameters rd;
  rd.form = sysid::PiForm::kRateDependent;
  rd.thresholds = {0.5, 1.0, 1.5};
  rd.weights = {2e-6, 1e-6, 0.5e-6};
  rd.polynomial = {4e-6};
  rd.rate_weights = {1e-9, 2e-9, 0, 1e-9};
  rd.offset_m = -1e-4;
  rd.input_min_v = 0;
  rd.input_max_v = 3.6;
  const sysid::PrandtlIshlinskiiModel rdpi(rd);
  CHECK_THROWS_WITH(
      sysid::ExportPiInverse(rdpi, 5e-3, sysid::DefaultPiVectors(rdpi, 5e-3), o, prov),
      Contains("no float bound"));
  o.precision = sysid::ExportPrecision::kDouble;
  CHECK(sysid::ExportPiInverse(rdpi, 5e-3, sysid::DefaultPiVectors(rdpi, 5e-3), o, prov).bound_v ==
        0);
  // A Bouc-Wen loop that is not monotone in u (alpha > 1): no inverse, nothing exported.
  sysid::PiezoBoucWenParameters bw;
  bw.alpha = 1.5;
  const sysid::PiezoBoucWen folded(bw);
  CHECK_THROWS_AS(sysid::ExportBoucWenInverse(folded, sysid::DefaultBoucWenVectors(folded), o,
                                              prov),
                  sysid::NumericalError);
  sysid::PiParameters bad = sysid::test::KnownPiParameters();
  bad.polynomial = {-1e-6};  // p0 < 0: no inverse
  const sysid::PrandtlIshlinskiiModel none(bad);
  CHECK_THROWS_AS(sysid::ExportPiInverse(none, 5e-3, sysid::ExportVectors{}, o, prov),
                  sysid::NumericalError);
}

TEST_CASE("a file name holding the comment's end cannot end the header's comment", "[deploy]") {
  const sysid::ExportProvenance prov{"evil*/ int x; /*.json", std::string(64, '0')};
  const sysid::ExportResult r = sysid::ExportFrictionInverse(
      sysid::FrictionModel::Paper(), 1e-3, sysid::DefaultFrictionVectors(1e-3), {}, prov);
  const size_t end = r.header.find("*/");
  REQUIRE(end != std::string::npos);
  // The first comment ends after the provenance line: the name's "*/" was defused.
  CHECK(r.header.find("evil* / int x;") < end);
}

TEST_CASE("sysid export: a usage error exits 1 and bad data 2 with nothing written", "[deploy]") {
  sysid::test::TempDir dir;
  sysid::test::WriteText(dir / "m.json", R"({"a1p":100,"a1n":120,"a2p":3,"a2n":7,"a3":5,"tau":0.002})");
  auto r = sysid::test::RunCli({"export", "--model", dir / "m.json", "--dt", "1e-3", "--prefix",
                                "int", "-o", dir / "out"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Contains("C99 keyword"));
  CHECK_FALSE(std::filesystem::exists(dir / "out"));
  r = sysid::test::RunCli({"export", "--model", dir / "m.json", "-o", dir / "out"});
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Contains("--dt"));
  sysid::test::WriteText(dir / "rec.csv", "t,v\n0,0.001\n0.001,0.002\n");
  r = sysid::test::RunCli({"export", "--model", dir / "m.json", "--dt", "1e-3", "--vectors",
                           dir / "rec.csv", "-o", dir / "out"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Contains("'a'"));
  CHECK_FALSE(std::filesystem::exists(dir / "out"));
  r = sysid::test::RunCli({"export", "--model", dir / "m.json", "--dt", "1e-3", "-o",
                           dir / "out"});
  CHECK(r.exit_code == 0);
  const std::string header = sysid::test::ReadText(dir / "out/sysid_inverse.h");
  // The provenance is the file's digest (the file's bytes, hashed by the FIPS-checked function).
  CHECK_THAT(header, Contains(sysid::Sha256Hex(sysid::test::ReadText(dir / "m.json"))));
}
