#include "core/json_text.hpp"

#include <cmath>
#include <string>

#include "sysid/error.hpp"

namespace sysid::internal {

nlohmann::ordered_json NumberOrNull(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json VectorJson(const Eigen::VectorXd& v) {
  nlohmann::ordered_json j = nlohmann::ordered_json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) j.push_back(NumberOrNull(v[i]));
  return j;
}

nlohmann::ordered_json MatrixJson(const Eigen::MatrixXd& m) {
  nlohmann::ordered_json j = nlohmann::ordered_json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) j.push_back(VectorJson(m.row(i).transpose()));
  return j;
}

Eigen::VectorXd VectorFromJson(const JsonNode& node, size_t size) {
  node.ExpectArray(size);
  Eigen::VectorXd v(static_cast<Eigen::Index>(node.Size()));
  for (size_t i = 0; i < node.Size(); ++i)
    v[static_cast<Eigen::Index>(i)] = node.Element(i).NumberOrNaN();
  return v;
}

Eigen::MatrixXd MatrixFromJson(const JsonNode& node, size_t rows, size_t cols) {
  node.ExpectArray(rows);
  if (rows == 0 && node.Size() != 0) node.Expected("an empty array");
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  for (size_t i = 0; i < rows; ++i)
    m.row(static_cast<Eigen::Index>(i)) = VectorFromJson(node.Element(i), cols).transpose();
  return m;
}

Termination TerminationFromJson(const JsonNode& node) {
  return ReadName(node,
                  {Termination::kConverged, Termination::kBudgetExhausted, Termination::kFailure},
                  [](Termination t) { return ToString(t); }, "a termination");
}

std::string DumpJson(const nlohmann::ordered_json& j, int indent) {
  return j.dump(indent) + "\n";
}

}  // namespace sysid::internal
