// Dominance over richer candidates, without a friction model: which measured variable carries
// the input? A linear inverse model in the candidates,
//   u_k ~ c + th_x x_k + th_v v_k + th_a a_k + sum_i th_i F_ri[x]_k            [V]
// (F_ri the play operators of sysid/hysteresis.hpp on x, thresholds uniform over x's range),
// is fitted by least squares on the moving and resting samples alike, and each candidate's term
// T_j = th_j (phi_j - mean phi_j) [V] is sized by its RMS, as the dominance module sizes the
// friction model's terms. Variables are ranked by the RMS of the terms they generate: the
// displacement generates its own term and the play operators' (they are functions of x alone,
// and collinear with it, so only their sum is meaningful). A stack actuator (displacement
// follows the voltage through hysteresis) should rank x first; the stage (a velocity source)
// should rank v first.
#ifndef SYSID_DOMINANCE_CANDIDATES_HPP_
#define SYSID_DOMINANCE_CANDIDATES_HPP_

#include <string>
#include <vector>

#include "sysid/dominance.hpp"
#include "sysid/io.hpp"
#include "sysid/motion.hpp"

namespace sysid {

struct CandidateRankingOptions {
  MotionOptions motion;           ///< how v and a are obtained from x
  int operators = 3;              ///< play operators on x (0..kMaxPlayOperators)
  double negligible_ratio = 0.1;  ///< a variable with rms <= this x the top's is negligible
  void Validate() const;          ///< OptionsError naming the field and the rule
};

struct CandidateRanking {
  std::string source;
  std::vector<TermStats> terms;    ///< every regressor's term [V]: x, F1[x].., v, a
  std::vector<TermStats> ranking;  ///< variables x, v, a by the RMS of their terms [V]
  std::string dominant;            ///< ranking[0].name
  double margin = 0;               ///< rms(top) / rms(second)
  double residual_rms_v = 0;       ///< [V] RMS of u minus the linear model
  double r2 = 0;                   ///< 1 - SSE / SST of the linear model
  std::string BriefReport() const;
};

/// Ranks x, v and a (with play operators of x) on one recording (t, u, x). Throws InputError
/// for a recording without x, OptionsError for bad options.
CandidateRanking RankCandidates(const Recording& recording,
                                const CandidateRankingOptions& options = {});

}  // namespace sysid

#endif  // SYSID_DOMINANCE_CANDIDATES_HPP_
