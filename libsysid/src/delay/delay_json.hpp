// Private: what a reader or writer of the delay options needs beside core/json_fields.hpp (the
// JSON forms of the motion options' enums).
#ifndef SYSID_SRC_DELAY_DELAY_JSON_HPP_
#define SYSID_SRC_DELAY_DELAY_JSON_HPP_

#include <nlohmann/json.hpp>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "motion/motion_json.hpp"
#include "sysid/delay.hpp"

#endif  // SYSID_SRC_DELAY_DELAY_JSON_HPP_
