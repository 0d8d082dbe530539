#pragma once
// The JSON the nodes and tools write, all through nlohmann::json: ordered_json keeps the keys in
// the order the writer adds them, so a file reads top-down like before. Strings are escaped by the
// library; a byte sequence that is not UTF-8 is written as U+FFFD instead of failing the run.

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace vcockpit {

class AtomicFile;

// One line (a JSON-lines record) when indent < 0, else indented by `indent` spaces; no newline.
std::string json_text(const nlohmann::ordered_json& value, int indent = -1);

// `value` indented by 2 with a final newline, written to `file` (not committed).
void write_json(AtomicFile& file, const nlohmann::ordered_json& value);

// A whole JSON file: written under "<path>.partial" and renamed into place; throws FileError
// naming the path.
void write_json_file(const std::string& path, const nlohmann::ordered_json& value);

}  // namespace vcockpit
