#include "common/json_file.hpp"

#include <nlohmann/json.hpp>

#include "common/atomic_file.hpp"

namespace vcockpit {

std::string json_text(const nlohmann::ordered_json& value, int indent) {
  return value.dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
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
