#include "geometry/json_input.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "geometry/error.hpp"

namespace daylit::json_input {

nlohmann::json parse(const std::string& text, const std::string& name) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the 1-based offset of the last byte read; count the lines up to it.
    const std::size_t end = std::min<std::size_t>(e.byte, text.size());
    const int line = 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(end > 0 ? end - 1 : 0), '\n'));
    // nlohmann's message reads "[json.exception.parse_error.101] parse error at line L, column C: what";
    // keep only "what".
    std::string what = e.what();
    if (const auto colon = what.find(": "); colon != std::string::npos) what = what.substr(colon + 2);
    throw input_error({name, line}, "JSON syntax error: " + what);
  } catch (const nlohmann::json::out_of_range& e) {
    // A number beyond double ("1e400"): nlohmann gives no position for it (found by fuzz_site_json).
    throw Error(name + ": JSON number out of range (" + std::string(e.what()) + ")");
  }
}

nlohmann::json read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path + ": cannot read");
  return parse(text.str(), path);
}

std::string kind_of(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::object: return "an object";
    case nlohmann::json::value_t::array: return "an array";
    case nlohmann::json::value_t::string: return "a string";
    case nlohmann::json::value_t::boolean: return "a boolean";
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned:
    case nlohmann::json::value_t::number_float: return "a number";
    default: return "a value of another kind";
  }
}

}  // namespace daylit::json_input
