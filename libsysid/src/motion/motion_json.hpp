// Private: what a reader or writer of the motion options needs beside core/json_fields.hpp (the
// derivative method's JSON form).
#ifndef SYSID_SRC_MOTION_MOTION_JSON_HPP_
#define SYSID_SRC_MOTION_MOTION_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_text.hpp"
#include "signal/signal_json.hpp"
#include "sysid/motion.hpp"

#endif  // SYSID_SRC_MOTION_MOTION_JSON_HPP_
