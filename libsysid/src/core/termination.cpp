#include "sysid/termination.hpp"

namespace sysid {

std::string ToString(Termination termination) {
  switch (termination) {
    case Termination::kConverged:
      return "converged";
    case Termination::kBudgetExhausted:
      return "budget-exhausted";
    case Termination::kFailure:
      return "failure";
  }
  return "?";
}

}  // namespace sysid
