// Private: the C99 text shared by every exported kind (literals, the own tanh, the header, the
// check program, the README fragment, the vectors file).
#ifndef SYSID_SRC_DEPLOY_C_TEXT_HPP_
#define SYSID_SRC_DEPLOY_C_TEXT_HPP_

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "sysid/deploy.hpp"

namespace sysid::internal {

/// `text` with every "@KEY@" of `keys` replaced (C braces stay as they are, unlike fmt).
std::string Fill(std::string text, const std::vector<std::pair<std::string, std::string>>& keys);
/// A C floating literal that parses back to `value` exactly in the chosen precision (double:
/// 17 significant digits; float: the value rounded to float, 9 digits and an f suffix).
std::string CLiteral(double value, ExportPrecision precision);
/// "double" or "float".
std::string CType(ExportPrecision precision);
/// "{a, b, ...}" of CLiteral, wrapped at 4 values a line.
std::string CArray(const std::vector<double>& values, ExportPrecision precision);
/// The file-local expm1 series in C (PREFIX_expm1_series, |r| <= 0.35).
std::string CExpm1Series(const std::string& prefix, ExportPrecision precision);
/// The file-local tanh in C (PREFIX_tanh), the same on every IEEE-754 target (docs/deploy.md:
/// its error bound).
std::string CTanh(const std::string& prefix, ExportPrecision precision);
/// NAME_check.c for a step taking `inputs` (CSV column names) in that order.
std::string CheckProgram(const std::string& prefix, const std::vector<std::string>& inputs,
                         ExportPrecision precision);
/// NAME_vectors.csv: the inputs' columns, then u_expected_v, 17 significant digits.
std::string VectorsCsv(const std::vector<std::string>& inputs, const Eigen::MatrixXd& x,
                       const Eigen::VectorXd& u);
/// The README fragment (Simulink C Caller / S-Function Builder, dSPACE, an MCU interrupt).
std::string Readme(const std::string& prefix, const std::string& kind,
                   const std::vector<std::string>& args, const std::string& dt_text,
                   ExportPrecision precision);
/// The header comment's common lines (precision, bound, provenance).
std::string Provenance(const ExportProvenance& provenance, ExportPrecision precision,
                       double bound_v, const std::string& bound_reason);

/// Unit roundoff of the exported arithmetic: 2^-53 (double) or 2^-24 (float).
double Epsilon(ExportPrecision precision);
/// InputError unless the vectors have `inputs` columns, a row, and finite values.
void CheckVectors(const ExportVectors& vectors, int inputs, const char* kind);
/// NAME.h: the comment (a "*/" in it defused), NAME_INPUTS, NAME_BOUND_V, the state struct and
/// the prototypes of NAME_init and NAME_step (`args` after the state pointer).
std::string Header(const ExportOptions& options, const std::string& comment,
                   const std::string& state, const std::string& args, int inputs, double bound_v);
/// "[min, max]" of x, 6 digits.
std::string Range(const Eigen::VectorXd& x);
/// The check program, the vectors file and the README of `result`; NumericalError when the
/// stepper's outputs are not finite (nothing is exported then).
void Finish(ExportResult* result, const ExportOptions& options, const ExportVectors& vectors,
            const std::string& kind_text, const std::vector<std::string>& args,
            const std::string& dt_text);

}  // namespace sysid::internal

#endif  // SYSID_SRC_DEPLOY_C_TEXT_HPP_
