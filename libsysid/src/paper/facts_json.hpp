// Private: what a reader or writer of the facts options needs beside core/json_fields.hpp (the
// JSON forms of the PI, delay and training options' enums).
#ifndef SYSID_SRC_PAPER_FACTS_JSON_HPP_
#define SYSID_SRC_PAPER_FACTS_JSON_HPP_

#include <nlohmann/json.hpp>

#include "control/control_json.hpp"
#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "delay/delay_json.hpp"
#include "nn/nn_json.hpp"
#include "sysid/stage_facts.hpp"

#endif  // SYSID_SRC_PAPER_FACTS_JSON_HPP_
