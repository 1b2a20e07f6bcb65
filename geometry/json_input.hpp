#pragma once
// JSON input files (site descriptions, GeoJSON) read with nlohmann-json, with errors that name the
// file, and the line for syntax errors. Used by the readers in geometry/ and sky/; the public headers
// of both stay free of nlohmann.

#include <string>

#include <nlohmann/json.hpp>

namespace daylit::json_input {

// Reads and parses `path`. Throws daylit::Error "path: cannot read" or
// "path:LINE: JSON syntax error: …" (LINE 1-based, counted up to the byte where parsing stopped).
nlohmann::json read_file(const std::string& path);

// The same for text already in memory; `name` is used in messages.
nlohmann::json parse(const std::string& text, const std::string& name);

// "a number", "a string", … for messages about a value of the wrong type.
std::string kind_of(const nlohmann::json& value);

}  // namespace daylit::json_input
