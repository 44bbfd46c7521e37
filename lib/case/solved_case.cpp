#include "case/solved_case.hpp"

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace quadapt {

namespace {

using nlohmann::json;

std::string without_blanks(const std::string& s) {
  std::string out;
  for (char c : s)
    if (!std::isspace(static_cast<unsigned char>(c))) out += c;
  return out;
}

json data_map(const std::vector<BoundaryData>& data) {
  json m = json::object();  // nlohmann's object is ordered by key: the record does not depend on the file's order
  for (const BoundaryData& bd : data) m[bd.boundary] = without_blanks(bd.source);
  return m;
}

json record_json(const Case& cs) {
  json r;
  r["diffusion"] = {{cs.diffusion(0, 0), cs.diffusion(0, 1)}, {cs.diffusion(1, 0), cs.diffusion(1, 1)}};
  r["advection"] = {cs.advection.x(), cs.advection.y()};
  r["exact"] = without_blanks(cs.exact_source);
  if (cs.dirichlet_all) {
    r["dirichlet"] = "all";
  } else {
    std::vector<std::string> names = cs.dirichlet;
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    r["dirichlet"] = names;
  }
  r["dirichlet_data"] = data_map(cs.dirichlet_data);
  r["neumann"] = data_map(cs.neumann_data);
  return r;
}

json parse_record(const std::string& record, const std::string& path) {
  json stored;
  try {
    stored = json::parse(record);
  } catch (const json::exception&) {
    stored = nullptr;
  }
  if (!stored.is_object())
    throw InputError(path, "$SolvedCase is not a JSON object (written by dgsolve; remove the section if edited by hand)");
  return stored;
}

}  // namespace

std::string solved_case_record(const Case& cs, double penalty_factor) {
  json r = record_json(cs);
  r["penalty"] = penalty_factor;
  return r.dump();
}

std::vector<std::string> solved_case_differences(const std::string& record, const Case& cs, const std::string& path) {
  const json stored = parse_record(record, path);
  const json now = record_json(cs);
  std::vector<std::string> diff;
  for (const auto& [key, value] : now.items())
    if (!stored.contains(key) || stored[key] != value) diff.push_back(key);
  return diff;
}

std::optional<double> solved_penalty(const std::string& record, const std::string& path) {
  const json stored = parse_record(record, path);
  const auto it = stored.find("penalty");
  if (it == stored.end()) return std::nullopt;
  if (!it->is_number() || !(it->get<double>() > 0))
    throw InputError(path, "$SolvedCase: \"penalty\" is not a positive number (written by dgsolve; remove the section if edited by hand)");
  return it->get<double>();
}

}  // namespace quadapt
