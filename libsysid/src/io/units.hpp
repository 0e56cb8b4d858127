// The '# units:' metadata of a recording, applied by the CSV reader (private to io/).
#ifndef SYSID_IO_UNITS_HPP_
#define SYSID_IO_UNITS_HPP_

#include <string_view>

#include "sysid/io.hpp"

namespace sysid::internal {

/// `s` without leading and trailing blanks and tabs (the CSV reader's and the units line's).
inline std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

/// Converts the columns t, u, x, v, a (and x_ref) that a '# units:' line declares in a scaled
/// unit to SI, and rewrites that line to say SI. Entries read "x=mm" or "x [mm]", separated by
/// commas; lengths m, mm, um (µm), nm; times s, ms, us; velocities and accelerations as
/// LENGTH/s and LENGTH/s^2; voltages V, mV. Throws InputError "SOURCE:LINE:1: ..." (`line`:
/// the units line's, 0 when unknown: "SOURCE: ...") naming the entry for a unit it does not
/// know on one of those columns; entries for other columns are kept.
void ApplyUnitsMetadata(Recording& recording, long line = 0);

}  // namespace sysid::internal

#endif  // SYSID_IO_UNITS_HPP_
