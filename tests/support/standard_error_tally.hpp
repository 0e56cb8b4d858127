// The Monte-Carlo check of reported standard errors that refine's and the Bouc–Wen fit's tests
// share: the estimates over many noise seeds have a sample standard deviation, and the root
// mean square of the reported standard errors must match it within 4 sampling errors of a
// standard deviation from N estimates, 4 / sqrt(2 (N - 1)).
#ifndef SYSID_TESTS_SUPPORT_STANDARD_ERROR_TALLY_HPP_
#define SYSID_TESTS_SUPPORT_STANDARD_ERROR_TALLY_HPP_

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace sysid::test {

class StandardErrorTally {
 public:
  /// `names`: the parameters' names, in the order of Add's index.
  explicit StandardErrorTally(std::vector<std::string> names)
      : names_(std::move(names)),
        sum_(names_.size(), 0.0),
        sum2_(names_.size(), 0.0),
        se2_(names_.size(), 0.0),
        count_(names_.size(), 0) {}

  /// One seed's estimate of parameter i and the standard error reported with it.
  void Add(size_t i, double estimate, double std_error) {
    REQUIRE(std::isfinite(std_error));
    sum_[i] += estimate;
    sum2_[i] += estimate * estimate;
    se2_[i] += std_error * std_error;
    ++count_[i];
  }

  /// The check, for every parameter with two estimates or more.
  void CheckAgreement() const {
    for (size_t i = 0; i < names_.size(); ++i) {
      if (count_[i] < 2) continue;
      const double n = count_[i];
      const double agreement = 4.0 / std::sqrt(2.0 * (n - 1));
      const double mean = sum_[i] / n;
      const double sd = std::sqrt(std::max(0.0, (sum2_[i] - n * mean * mean) / (n - 1)));
      const double reported = std::sqrt(se2_[i] / n);
      INFO(names_[i] << ": Monte-Carlo sd " << sd << ", reported " << reported << ", mean "
                     << mean << ", agreement +-" << agreement);
      CHECK(reported / sd == Approx(1.0).margin(agreement));
    }
  }

 private:
  std::vector<std::string> names_;
  std::vector<double> sum_, sum2_, se2_;
  std::vector<int> count_;
};

}  // namespace sysid::test

#endif  // SYSID_TESTS_SUPPORT_STANDARD_ERROR_TALLY_HPP_
