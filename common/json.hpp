#pragma once
// A JSON string literal (quotes and escapes) for the JSON files the nodes write.

#include <string>

namespace vcockpit {

std::string json_string(const std::string& text);

}  // namespace vcockpit
