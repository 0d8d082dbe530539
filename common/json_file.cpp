#include "common/json_file.hpp"

#include <nlohmann/json.hpp>

#include <cmath>

#include "common/atomic_file.hpp"

namespace vcockpit {
namespace {

using Json = nlohmann::ordered_json;

bool is_non_finite(const Json& v) { return v.is_number_float() && !std::isfinite(v.get<double>()); }

// A list of numbers with a non-finite one among them.
bool is_broken_number_list(const Json& v) {
  if (!v.is_array()) return false;
  bool numbers_only = true, broken = false;
  for (const Json& e : v) {
    numbers_only = numbers_only && e.is_number();
    broken = broken || is_non_finite(e);
  }
  return numbers_only && broken;
}

bool holds_non_finite(const Json& v) {
  if (is_non_finite(v)) return true;
  if (v.is_object() || v.is_array()) {
    for (const Json& e : v)
      if (holds_non_finite(e)) return true;
  }
  return false;
}

void remove_at(Json& v, const std::string& where, std::vector<std::string>& removed) {
  if (v.is_object()) {
    for (auto it = v.begin(); it != v.end();) {
      const std::string at = where.empty() ? it.key() : where + "." + it.key();
      if (is_non_finite(*it) || is_broken_number_list(*it)) {
        removed.push_back(at);
        it = v.erase(it);
      } else {
        remove_at(*it, at, removed);
        ++it;
      }
    }
  } else if (v.is_array()) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::string at = where + "[" + std::to_string(i) + "]";
      if (is_non_finite(v[i])) {
        removed.push_back(at);  // a mixed list: the element alone, kept in place as null
        v[i] = nullptr;
      } else {
        remove_at(v[i], at, removed);
      }
    }
  }
}

}  // namespace

std::vector<std::string> remove_non_finite(nlohmann::ordered_json& value) {
  std::vector<std::string> removed;
  if (is_non_finite(value) || is_broken_number_list(value)) {
    removed.push_back("(top level)");
    value = nullptr;
    return removed;
  }
  remove_at(value, "", removed);
  return removed;
}

std::string json_text(const nlohmann::ordered_json& value, int indent) {
  constexpr auto kReplace = nlohmann::ordered_json::error_handler_t::replace;
  if (!holds_non_finite(value)) return value.dump(indent, ' ', false, kReplace);
  Json copy = value;
  const std::vector<std::string> removed = remove_non_finite(copy);
  if (copy.is_object()) copy["non_finite_removed"] = removed;
  return copy.dump(indent, ' ', false, kReplace);
}

void write_json(AtomicFile& file, const nlohmann::ordered_json& value) {
  file.write(json_text(value, 2) + "\n");
}

void write_json_file(const std::string& path, const nlohmann::ordered_json& value) {
  AtomicFile file(path);
  write_json(file, value);
  file.commit();
}

}  // namespace vcockpit
