// CropRecording: a time window of a recording (--t-start, --t-end on every command that reads
// recordings; the fit part of --fit-fraction).
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "sysid/error.hpp"
#include "sysid/io.hpp"

namespace sysid {

Recording CropRecording(const Recording& recording, double t_start_s, double t_end_s) {
  const std::string& source = recording.source;
  if (!recording.has("t"))
    throw InputError(source +
                     ": a time window needs a time column 't' (give --rate HZ or map "
                     "one with --var t=NAME)");
  if (recording.rows() == 0) throw InputError(source + ": no samples");
  const auto t = recording.column("t");
  const double first = t[0], last = t[t.size() - 1];
  const std::string window = fmt::format("the window t = {:.6g} .. {:.6g} s", t_start_s, t_end_s);
  if (!std::isfinite(t_start_s) || !std::isfinite(t_end_s) || !(t_start_s < t_end_s))
    throw InputError(
        fmt::format("{}: {}: expected finite bounds, the start before the end", source, window));
  if (t_start_s < first || t_end_s > last)
    throw InputError(fmt::format("{}: {} reaches outside the recording (t = {:.6g} .. {:.6g} s)",
                                 source, window, first, last));
  Eigen::Index begin = 0, end = t.size();
  while (begin < end && t[begin] < t_start_s) ++begin;
  while (end > begin && t[end - 1] > t_end_s) --end;
  if (end - begin < 2)
    throw InputError(fmt::format("{}: {} holds {} sample{} of the recording; expected at least 2",
                                 source, window, end - begin, end - begin == 1 ? "" : "s"));
  Recording out;
  out.source = recording.source;
  out.names = recording.names;
  out.metadata = recording.metadata;
  out.data = recording.data.middleRows(begin, end - begin);
  bool replaced = false;
  const std::string value = fmt::format("{} {}", t_start_s, t_end_s);
  for (auto& [k, v] : out.metadata)
    if (k == "crop_s") v = value, replaced = true;
  if (!replaced) out.metadata.emplace_back("crop_s", value);
  return out;
}

}  // namespace sysid
