#include <memory>
#include <utility>

#include "sysid/control.hpp"
#include "sysid/error.hpp"

namespace sysid {

Feedforward SampledFeedforward(Eigen::VectorXd u_ff_v) {
  auto next = std::make_shared<Eigen::Index>(0);
  auto values = std::make_shared<const Eigen::VectorXd>(std::move(u_ff_v));
  return [next, values](const ReferenceSample&) {
    SYSID_CHECK(*next < values->size(), "feedforward called more often than it has samples (" +
                                            std::to_string(values->size()) + ")");
    return (*values)[(*next)++];
  };
}

}  // namespace sysid
