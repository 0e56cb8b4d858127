// Private: JSON text helpers shared by the model, network and stage file parsers, so that every
// file error names "SOURCE:LINE:COLUMN:" the same way.
#ifndef SYSID_DETAIL_JSON_TEXT_HPP_
#define SYSID_DETAIL_JSON_TEXT_HPP_

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace sysid::detail {

/// "LINE:COLUMN" (1-based) of byte offset `pos` in `text`.
std::string TextPosition(std::string_view text, size_t pos);

/// "LINE:COLUMN" where the quoted `key` first appears, searching from the first appearance of
/// the quoted `parent` key when one is given (nested objects); "1:1" when absent.
std::string JsonKeyPosition(std::string_view text, const std::string& key,
                            const std::string& parent = "");

/// Parses `text`; a syntax error throws InputError "SOURCE:LINE:COLUMN: invalid JSON: ...".
nlohmann::json ParseJsonText(std::string_view text, const std::string& source);

}  // namespace sysid::detail

#endif  // SYSID_DETAIL_JSON_TEXT_HPP_
