#include "geometry/sensor_grid.hpp"

#include <algorithm>
#include <climits>
#include <filesystem>
#include <fstream>

#include "geometry/text_scanner.hpp"

namespace daylit {

namespace {

// A sensor line is six numbers; a line longer than this (a comment of a megabyte, or a binary
// file without newlines) is an error rather than a reason to buffer without bound.
constexpr std::size_t kMaxLineBytes = std::size_t(1) << 20;

// Appends the sensor on one line (without its newline), if the line is not blank or a comment.
void parse_sensor_line(std::string_view text, const std::string& path, long line_number, SensorGrid& grid) {
  const SourceLocation where{path, int(std::min<long>(line_number, INT_MAX))};
  if (text.size() > kMaxLineBytes)
    throw input_error(where, "line longer than " + std::to_string(kMaxLineBytes) + " bytes: not a sensor grid");
  TextScanner scan(text, path);
  if (scan.at_end()) return;
  double v[6];
  for (int i = 0; i < 6; ++i) {
    const Token t = scan.next();
    if (t.text.empty()) throw input_error(where, "expected 6 numbers (x y z dx dy dz), found " + std::to_string(i));
    v[i] = i < 3 ? parse_coordinate(t, where, "a sensor coordinate") : parse_real(t, where, "a sensor direction");
  }
  if (!scan.at_end()) throw input_error(where, "more than 6 numbers on a sensor line");
  const Vec3 direction{v[3], v[4], v[5]};
  const double length = norm(direction);  // hypot: finite and exact enough for any finite direction
  if (!(length > 0) || !std::isfinite(length)) throw input_error(where, "sensor direction is zero");
  grid.sensors.push_back({{v[0], v[1], v[2]}, direction / length});
}

SensorGrid empty_grid(const std::string& path) {
  SensorGrid grid;
  grid.path = path;
  grid.name = std::filesystem::path(path).stem().string();
  return grid;
}

}  // namespace

SensorGrid parse_sensor_grid(const std::string& text, const std::string& path) {
  SensorGrid grid = empty_grid(path);
  std::size_t line_start = 0;
  long line = 0;
  while (line_start < text.size()) {
    std::size_t line_end = text.find('\n', line_start);
    if (line_end == std::string::npos) line_end = text.size();
    parse_sensor_line(std::string_view(text).substr(line_start, line_end - line_start), path, ++line, grid);
    line_start = line_end + 1;
  }
  if (grid.sensors.empty()) throw Error(path + ": the sensor grid is empty");
  return grid;
}

// Streams the file in blocks of 64 KiB: memory is the sensors read so far plus at most one line,
// and a file that is not a grid fails at its first bad line without being read to the end.
SensorGrid read_sensor_grid(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  SensorGrid grid = empty_grid(path);
  std::string block(std::size_t(1) << 16, '\0');
  std::string pending;  // the start of a line that continues in the next block
  long line = 0;
  while (in) {
    in.read(block.data(), std::streamsize(block.size()));
    const std::string_view chunk(block.data(), std::size_t(in.gcount()));
    std::size_t start = 0;
    for (std::size_t end; (end = chunk.find('\n', start)) != std::string_view::npos; start = end + 1) {
      if (pending.empty()) {
        parse_sensor_line(chunk.substr(start, end - start), path, ++line, grid);
      } else {
        pending.append(chunk.substr(start, end - start));
        parse_sensor_line(pending, path, ++line, grid);
        pending.clear();
      }
    }
    pending.append(chunk.substr(start));
    if (pending.size() > kMaxLineBytes) parse_sensor_line(pending, path, line + 1, grid);  // throws: too long
  }
  if (in.bad()) throw Error(path + ": read error");
  if (!pending.empty()) parse_sensor_line(pending, path, ++line, grid);
  if (grid.sensors.empty()) throw Error(path + ": the sensor grid is empty");
  return grid;
}

}  // namespace daylit
