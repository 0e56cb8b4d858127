// The C99 text every exported kind shares.
#include "c_text.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <string>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/io_csv_table.hpp"
#include "sysid/io_output.hpp"

namespace sysid::internal {

std::string Fill(std::string text, const std::vector<std::pair<std::string, std::string>>& keys) {
  for (const auto& [key, value] : keys) {
    const std::string token = "@" + key + "@";
    for (size_t at = text.find(token); at != std::string::npos;
         at = text.find(token, at + value.size()))
      text.replace(at, token.size(), value);
  }
  return text;
}

std::string CLiteral(double value, ExportPrecision precision) {
  std::string s = precision == ExportPrecision::kDouble
                      ? fmt::format("{:.17g}", value)
                      : fmt::format("{:.9g}", static_cast<double>(static_cast<float>(value)));
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return precision == ExportPrecision::kFloat ? s + "f" : s;
}

std::string CType(ExportPrecision precision) {
  return precision == ExportPrecision::kDouble ? "double" : "float";
}

std::string CArray(const std::vector<double>& values, ExportPrecision precision) {
  std::string out = "{";
  for (size_t i = 0; i < values.size(); ++i) {
    if (i > 0) out += i % 4 == 0 ? ",\n    " : ", ";
    out += CLiteral(values[i], precision);
  }
  return out + "}";
}

// Taylor terms of expm1 on |r| <= 0.35: the first left out, 0.35^n / n!, is below 2^-56
// (double, n = 14) or 2^-27 (float, n = 9) of r.
std::string CExpm1Series(const std::string& prefix, ExportPrecision precision) {
  const int terms = precision == ExportPrecision::kDouble ? 13 : 8;
  std::vector<double> coefficient{0.0};
  double factorial = 1;
  for (int n = 1; n <= terms; ++n) coefficient.push_back(1.0 / (factorial *= n));
  return Fill(R"(/* expm1(r) = sum r^n / n! on |r| <= 0.35 (Horner), the same on every IEEE-754 target. */
static const @T@ @P@_kExpm1[@N1@] = @COEF@;

static @T@ @P@_expm1_series(@T@ r) {
  @T@ s = @P@_kExpm1[@N@];
  int n;
  for (n = @N@ - 1; n >= 1; --n) s = s * r + @P@_kExpm1[n];
  return s * r;
}
)",
              {{"P", prefix},
               {"T", CType(precision)},
               {"N1", std::to_string(terms + 1)},
               {"N", std::to_string(terms)},
               {"COEF", CArray(coefficient, precision)}});
}

std::string CTanh(const std::string& prefix, ExportPrecision precision) {
  const bool dbl = precision == ExportPrecision::kDouble;
  std::vector<double> pow2;
  for (int k = 0; k <= 58; ++k) pow2.push_back(std::ldexp(1.0, k));
  // The [n/n] Pade approximant of exp, P(r) / P(-r), c_j = (2n - j)! n! / ((2n)! j! (n - j)!):
  // on |r| <= ln2 / 2 its relative error is at most |r|^(2n+1) e^|r| (n!)^2 / ((2n)! (2n+1)!
  // P(-r)), 3e-19 for n = 6 (double), 5e-12 for n = 4 (float). E and O are its even and odd
  // parts, P(+-r) = E +- O.
  const int n = dbl ? 6 : 4;
  auto factorial = [](int m) {
    double f = 1;
    for (int i = 2; i <= m; ++i) f *= i;
    return f;
  };
  std::vector<double> c;
  for (int j = 0; j <= n; ++j)
    c.push_back(factorial(2 * n - j) * factorial(n) /
                (factorial(2 * n) * factorial(j) * factorial(n - j)));
  auto horner = [&](int first) {  // c_first + r2 (c_first+2 + r2 (...))
    std::string text = CLiteral(c[static_cast<size_t>(first + 2 * ((n - first) / 2))], precision);
    for (int j = first + 2 * ((n - first) / 2) - 2; j >= first; j -= 2)
      text = "(" + CLiteral(c[static_cast<size_t>(j)], precision) + " + r2 * " + text + ")";
    return text;
  };
  // Cody–Waite ln 2 split: k ln2_hi is exact for k < 64 (fdlibm's hi; float's has 9 zero bits).
  const std::string ln2_hi = dbl ? "6.93147180369123816490e-01" : "0.693145751953125f";
  const std::string ln2_lo = dbl ? "1.90821492927058770002e-10" : "1.42860677e-06f";
  return Fill(R"(/* tanh without the platform's libm, so every IEEE-754 target computes the same
 * values, and without a data-dependent branch or loop: for a = min(|x|, 20) (NaN: 20),
 * e^(2a) = 2^k e^r with 2a = k ln2 + r (Cody-Waite, k rounded to nearest by adding and
 * subtracting 1.5 2^@MANT@, |r| <= ln2 / 2), e^r = (E + O) / (E - O) the [@N@/@N@] Pade approximant
 * (E, O its even and odd parts in r), and tanh a = (e^2a - 1) / (e^2a + 1)
 * = ((2^k - 1) E + (2^k + 1) O) / ((2^k + 1) E + (2^k - 1) O): one division. */
static const @T@ @P@_kPow2[59] = @POW2@;

static @T@ @P@_tanh(@T@ x) {
  const @T@ ax = x < @ZERO@ ? -x : x;
  const @T@ a = ax <= @TWENTY@ ? ax : @TWENTY@;
  const @T@ y = @TWO@ * a;
  const @T@ k = (y * @INV_LN2@ + @MAGIC@) - @MAGIC@;
  const @T@ r = (y - k * @LN2_HI@) - k * @LN2_LO@;
  const @T@ r2 = r * r;
  const @T@ e = @ONE@ + r2 * @EVEN@;
  const @T@ o = r * @ODD@;
  const @T@ s = @P@_kPow2[(int)k];
  const @T@ t = ((s - @ONE@) * e + (s + @ONE@) * o) / ((s + @ONE@) * e + (s - @ONE@) * o);
  return x < @ZERO@ ? -t : t;
}
)",
              {{"P", prefix},
               {"T", CType(precision)},
               {"N", std::to_string(n)},
               {"MANT", dbl ? "52" : "23"},
               {"POW2", CArray(pow2, precision)},
               {"EVEN", horner(2)},
               {"ODD", horner(1)},
               {"MAGIC", CLiteral(1.5 * std::ldexp(1.0, dbl ? 52 : 23), precision)},
               {"INV_LN2", CLiteral(1.0 / std::log(2.0), precision)},
               {"LN2_HI", ln2_hi},
               {"LN2_LO", ln2_lo},
               {"ONE", CLiteral(1.0, precision)},
               {"TWO", CLiteral(2.0, precision)},
               {"ZERO", CLiteral(0.0, precision)},
               {"TWENTY", CLiteral(20.0, precision)}});
}

// Long function: one C routine's text, emitted top to bottom as the compiler will read it;
// split, its lines would be scattered over helpers.
std::string CheckProgram(const std::string& prefix, const std::vector<std::string>& inputs,
                         ExportPrecision precision) {
  std::string names, call;
  for (size_t i = 0; i < inputs.size(); ++i) {
    names += (i ? ", \"" : "\"") + inputs[i] + "\"";
    call += fmt::format(", ({})value[column[{}]]", CType(precision), i);
  }
  return Fill(R"(/* @P@_check: runs @P@_step over a vectors file (columns @NAMES@ and u_expected_v,
 * any order, '#' lines skipped), prints each output with @DIGITS@ significant digits, one per
 * line, and exits 1 if any differs from u_expected_v by more than @P@_BOUND_V (@P@.h);
 * 2 when the file cannot be read or lacks a column.
 * Generated by @GEN@ (sysid export). Build: cc -std=c99 -O2 @P@_check.c @P@.c -o @P@_check */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "@P@.h"

#define MAX_COLUMNS 64
#define MAX_LINE 8192

static const char* const kInputs[@P@_INPUTS] = {@NAMES@};

/* Splits `line` at commas in place; returns the number of fields (at most MAX_COLUMNS). */
static int split(char* line, char* field[MAX_COLUMNS]) {
  int n = 0;
  char* p = line;
  for (;;) {
    char* end = p;
    if (n == MAX_COLUMNS) return n;
    field[n++] = p;
    while (*end != '\0' && *end != ',' && *end != '\r' && *end != '\n') ++end;
    if (*end != ',') {
      *end = '\0';
      return n;
    }
    *end = '\0';
    p = end + 1;
  }
}

int main(int argc, char** argv) {
  static char line[MAX_LINE];
  char* field[MAX_COLUMNS];
  int column[@P@_INPUTS];
  double value[MAX_COLUMNS];
  int expected = -1, columns, i;
  long row = 0;
  int failed = 0;
  double worst = 0.0;
  @P@_state state;
  FILE* file;
  if (argc != 2) {
    fprintf(stderr, "usage: %s VECTORS.csv\n", argv[0]);
    return 2;
  }
  file = fopen(argv[1], "r");
  if (file == NULL) {
    fprintf(stderr, "%s: cannot open\n", argv[1]);
    return 2;
  }
  do {
    if (fgets(line, MAX_LINE, file) == NULL) {
      fprintf(stderr, "%s: no header line\n", argv[1]);
      fclose(file);
      return 2;
    }
  } while (line[0] == '#');
  columns = split(line, field);
  for (i = 0; i < @P@_INPUTS; ++i) column[i] = -1;
  for (i = 0; i < columns; ++i) {
    int j;
    if (strcmp(field[i], "u_expected_v") == 0) expected = i;
    for (j = 0; j < @P@_INPUTS; ++j)
      if (strcmp(field[i], kInputs[j]) == 0) column[j] = i;
  }
  for (i = 0; i < @P@_INPUTS; ++i)
    if (column[i] < 0) {
      fprintf(stderr, "%s: no column '%s'\n", argv[1], kInputs[i]);
      fclose(file);
      return 2;
    }
  if (expected < 0) {
    fprintf(stderr, "%s: no column 'u_expected_v'\n", argv[1]);
    fclose(file);
    return 2;
  }
  @P@_init(&state);
  while (fgets(line, MAX_LINE, file) != NULL) {
    @T@ u;
    double diff;
    if (line[0] == '#' || line[0] == '\n' || line[0] == '\r') continue;
    ++row;
    if (split(line, field) != columns) {
      fprintf(stderr, "%s: row %ld: expected %d fields\n", argv[1], row, columns);
      fclose(file);
      return 2;
    }
    for (i = 0; i < columns; ++i) {
      char* end;
      value[i] = strtod(field[i], &end);
      if (end == field[i] || *end != '\0') {
        fprintf(stderr, "%s: row %ld, field %d: expected a number\n", argv[1], row, i + 1);
        fclose(file);
        return 2;
      }
    }
    u = @P@_step(&state@CALL@);
    printf("%.@DIGITS@g\n", (double)u);
    diff = (double)u - value[expected];
    if (diff < 0.0) diff = -diff;
    if (!(diff <= @P@_BOUND_V)) failed = 1;
    if (diff > worst || diff != diff) worst = diff;
  }
  fclose(file);
  fprintf(stderr, "%s: %ld rows, max |u - u_expected_v| = %.3g V, bound %.3g V: %s\n", argv[1],
          row, worst, @P@_BOUND_V, failed ? "FAILED" : "ok");
  return failed ? 1 : 0;
}
)",
              {{"P", prefix},
               {"NAMES", names},
               {"CALL", call},
               {"T", CType(precision)},
               {"GEN", GeneratorName()},
               {"DIGITS", precision == ExportPrecision::kDouble ? "17" : "9"}});
}

std::string VectorsCsv(const std::vector<std::string>& inputs, const Eigen::MatrixXd& x,
                       const Eigen::VectorXd& u) {
  std::vector<std::string> header = inputs;
  header.push_back("u_expected_v");
  CsvTable csv(header, GeneratorLine());
  for (Eigen::Index k = 0; k < x.rows(); ++k) {
    for (Eigen::Index i = 0; i < x.cols(); ++i) csv.Number(x(k, i), 17);
    csv.Number(u[k], 17).EndRow();
  }
  return csv.str();
}

std::string Provenance(const ExportProvenance& provenance, ExportPrecision precision,
                       double bound_v, const std::string& bound_reason) {
  return fmt::format(
      " * Precision: {} (compile with -ffp-contract=off: a fused multiply-add changes the last "
      "bits)\n"
      " * Bound: |u - u_expected_v| <= {:.3g} V over the vectors ({}); {}_BOUND_V below\n"
      " * Provenance: {} (SHA-256 {}), {}\n",
      CType(precision), bound_v, bound_reason, "@P@", provenance.model_file, provenance.sha256,
      GeneratorName());
}

std::string Readme(const std::string& prefix, const std::string& kind,
                   const std::vector<std::string>& args, const std::string& dt_text,
                   ExportPrecision precision) {
  std::string arg_list;
  for (const auto& a : args) arg_list += ", " + a;
  return Fill(R"(# @P@: the @KIND@ as C99

Generated by `sysid export`. `@P@.h` and `@P@.c` are the whole model: no heap, no stdio, no
libm, no static mutable state. The state lives in a `@P@_state` you own (its size is a
compile-time constant); call `@P@_init(&state)` once before the first sample and
`u = @P@_step(&state@ARGS@)` once per sample, every @DT@, in order. Inputs and units are in the
header comment. Compile with `-ffp-contract=off` (or `/fp:precise`) so the results match the
vectors bit for bit where the header says so.

Check on a new compiler or target:
```sh
cc -std=c99 -O2 -ffp-contract=off @P@_check.c @P@.c -o @P@_check
./@P@_check @P@_vectors.csv > outputs.txt   # exit 0: every output within @P@_BOUND_V
```

## Simulink
- **C Caller block** (R2018b+): add `@P@.h` / `@P@.c` under Configuration Parameters →
  Simulation Target → Header file / Source files, and call a two-line wrapper
  `@T@ @P@_sl(@T@ ...)` that keeps a `static @P@_state` (a wrapper you write, outside the
  exported files) with `@P@_init` on the first call; set the block's sample time to @DT@.
- **S-Function Builder**: add `@P@.c` as a library/source file, put a `@P@_state` in the
  discrete states or a PWork, call `@P@_init` in Start and `@P@_step` in Outputs.

## dSPACE / Speedgoat
The Simulink model above builds for the real-time target unchanged (the code has no OS
calls). Run the block in the task at @DT@; the state struct lives in the block's work memory.

## MCU control interrupt
```c
static @P@_state ff;                          /* one per axis */
void control_init(void) { @P@_init(&ff); }
void TIMx_IRQHandler(void) {                  /* every @DT@ */
  /* read the reference sample k, then: */
  @T@ u_ff = @P@_step(&ff@ARGS@);
  /* u = u_ff + PI(e); write the DAC */
}
```
Only the past reaches `@P@_step`: it is causal, and every loop in it has a fixed bound, so
its worst-case run time is bounded@LOOPS@.
)",
              {{"P", prefix},
               {"KIND", kind},
               {"ARGS", arg_list},
               {"DT", dt_text},
               {"T", CType(precision)},
               {"LOOPS", ""}});
}

// Unit roundoff of the exported arithmetic.
double Epsilon(ExportPrecision p) {
  return p == ExportPrecision::kDouble ? 0x1p-53 : 0x1p-24;
}

void CheckVectors(const ExportVectors& v, int inputs, const char* kind) {
  if (v.inputs.cols() != inputs || v.inputs.rows() < 1)
    throw InputError(fmt::format("{}: the {} export takes {} input column(s) and at least one "
                                 "row; the vectors have {} x {}",
                                 v.source, kind, inputs, v.inputs.rows(), v.inputs.cols()));
  if (!v.inputs.allFinite())
    throw InputError(v.source + ": the vectors hold a non-finite input");
}

// The header file: the comment, the bound, the state struct and the two functions.
std::string Header(const ExportOptions& o, const std::string& comment, const std::string& state,
                   const std::string& args, int inputs, double bound_v) {
  // File names and units are the user's text: a "*/" in them must not end the comment.
  std::string safe = comment;
  for (size_t at = safe.find("*/"); at != std::string::npos; at = safe.find("*/", at))
    safe.replace(at, 2, "* /");
  std::string guard = o.prefix + "_H_";
  for (char& c : guard) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return Fill(R"(/* @P@.h -- generated by sysid export; do not edit (regenerate instead).
@COMMENT@ */
#ifndef @GUARD@
#define @GUARD@

#define @P@_INPUTS @INPUTS@
/* [V] the largest |u - u_expected_v| @P@_check accepts (see the comment above). */
#define @P@_BOUND_V @BOUND@

@STATE@
/* Puts the state at rest (the model's initial state). Call before the first sample. */
void @P@_init(@P@_state* state);
/* u_k [V] from the inputs at sample k; call once per sample, in order. */
@T@ @P@_step(@P@_state* state@ARGS@);

#endif /* @GUARD@ */
)",
              {{"COMMENT", safe},
               {"GUARD", guard},
               {"INPUTS", std::to_string(inputs)},
               {"BOUND", fmt::format("{:.17g}", bound_v).find_first_of(".e") == std::string::npos
                             ? fmt::format("{:.17g}.0", bound_v)
                             : fmt::format("{:.17g}", bound_v)},
               {"STATE", state},
               {"ARGS", args},
               {"T", CType(o.precision)},
               {"P", o.prefix}});
}

std::string Range(const Eigen::VectorXd& x) {
  return fmt::format("[{:.6g}, {:.6g}]", x.minCoeff(), x.maxCoeff());
}

void Finish(ExportResult* r, const ExportOptions& o, const ExportVectors& v,
            const std::string& kind_text, const std::vector<std::string>& args,
            const std::string& dt_text) {
  r->check = internal::CheckProgram(o.prefix, r->input_names, o.precision);
  r->vectors_csv = internal::VectorsCsv(r->input_names, v.inputs, r->u_expected_v);
  r->readme = internal::Readme(o.prefix, kind_text, args, dt_text, o.precision);
  if (!r->u_expected_v.allFinite())
    throw NumericalError(kind_text + ": the library's stepper gives a non-finite u on " +
                         v.source + ": the model overflows there; nothing exported");
}

}  // namespace sysid::internal
