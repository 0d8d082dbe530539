#pragma once
// The JSON the nodes and tools write, all through nlohmann::json: ordered_json keeps the keys in
// the order the writer adds them, so a file reads top-down like before. Strings are escaped by the
// library; a byte sequence that is not UTF-8 is written as U+FFFD instead of failing the run.
//
// No NaN or infinity is ever written (nlohmann would write null in its place, and a reader would
// take it for a missing value): what holds one is left out and named in the text itself, under
// "non_finite_removed" (see json_text). Writers that can name the object and time in their log
// remove such values first (remove_non_finite), so this is a last net.

#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

namespace vcockpit {

class AtomicFile;

// Removes from `value` every object member that is a non-finite number, or a list of numbers of
// which one is not finite (a position with a NaN is no position), and returns where each was
// ("final.cup.position", "stages[2].mean_us"). Inside other lists a non-finite element becomes
// null (and is named), so the others keep their places; at the top, the whole value.
std::vector<std::string> remove_non_finite(nlohmann::ordered_json& value);

// One line (a JSON-lines record) when indent < 0, else indented by `indent` spaces; no newline.
// Values that are not finite are left out (remove_non_finite), and an object then gets the member
// "non_finite_removed": [where, ...] at its end.
std::string json_text(const nlohmann::ordered_json& value, int indent = -1);

// `value` indented by 2 with a final newline, written to `file` (not committed).
void write_json(AtomicFile& file, const nlohmann::ordered_json& value);

// A whole JSON file: written under "<path>.partial" and renamed into place; throws FileError
// naming the path.
void write_json_file(const std::string& path, const nlohmann::ordered_json& value);

}  // namespace vcockpit
