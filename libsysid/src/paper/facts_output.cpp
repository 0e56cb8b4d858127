// The facts' table as JSON and Markdown.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "sysid/stage_facts.hpp"

namespace sysid {

const StageFact* StageFacts::Find(const std::string& id) const {
  for (const auto& f : facts)
    if (f.id == id) return &f;
  return nullptr;
}

bool StageFacts::RequiredMet() const {
  return std::all_of(facts.begin(), facts.end(),
                     [](const StageFact& f) { return !f.required || f.met; });
}

std::string StageFacts::ToJson() const {
  nlohmann::ordered_json j;
  j["stage"] = stage_name;
  j["facts"] = nlohmann::ordered_json::array();
  for (const auto& f : facts) {
    nlohmann::ordered_json o;
    o["id"] = f.id;
    o["fact"] = f.fact;
    o["paper"] = f.paper;
    o["virtual"] = f.virtual_value;
    o["tolerance"] = f.tolerance;
    o["met"] = f.met;
    o["required"] = f.required;
    o["note"] = f.note;
    nlohmann::ordered_json values = nlohmann::ordered_json::object();
    for (const auto& [name, value] : f.values) {
      if (std::isfinite(value))
        values[name] = value;
      else
        values[name] = nullptr;
    }
    o["values"] = values;
    j["facts"].push_back(o);
  }
  j["required_met"] = RequiredMet();
  return j.dump(2);
}

std::string StageFacts::ToMarkdown() const {
  auto cell = [](std::string s) {
    for (size_t p = s.find('|'); p != std::string::npos; p = s.find('|', p + 2))
      s.replace(p, 1, "\\|");
    return s;
  };
  std::string md = "| id | fact | paper | stage | tolerance | met |\n|---|---|---|---|---|---|\n";
  for (const auto& f : facts)
    md += fmt::format("| {} | {} | {} | {} | {} | {} |\n", f.id, cell(f.fact), cell(f.paper),
                      cell(f.virtual_value), cell(f.tolerance),
                      f.met ? "yes" : (f.required ? "**no**" : "no (reported only)"));
  return md;
}

}  // namespace sysid
