#include "geometry/sensor_grid.hpp"

#include <filesystem>

#include "geometry/text_scanner.hpp"

namespace daylit {

SensorGrid parse_sensor_grid(const std::string& text, const std::string& path) {
  SensorGrid grid;
  grid.path = path;
  grid.name = std::filesystem::path(path).stem().string();
  std::size_t line_start = 0;
  int line = 0;
  while (line_start < text.size()) {
    std::size_t line_end = text.find('\n', line_start);
    if (line_end == std::string::npos) line_end = text.size();
    ++line;
    TextScanner scan(std::string_view(text).substr(line_start, line_end - line_start), path);
    line_start = line_end + 1;
    if (scan.at_end()) continue;
    const SourceLocation where{path, line};
    double v[6];
    for (int i = 0; i < 6; ++i) {
      const Token t = scan.next();
      if (t.text.empty())
        throw input_error(where, "expected 6 numbers (x y z dx dy dz), found " + std::to_string(i));
      v[i] = parse_real(t, where, i < 3 ? "a sensor coordinate" : "a sensor direction");
    }
    if (!scan.at_end()) throw input_error(where, "more than 6 numbers on a sensor line");
    const Vec3 direction{v[3], v[4], v[5]};
    const double length = norm(direction);
    if (!(length > 0) || !std::isfinite(length)) throw input_error(where, "sensor direction is zero");
    grid.sensors.push_back({{v[0], v[1], v[2]}, direction / length});
  }
  if (grid.sensors.empty()) throw Error(path + ": the sensor grid is empty");
  return grid;
}

SensorGrid read_sensor_grid(const std::string& path) { return parse_sensor_grid(read_text_file(path), path); }

}  // namespace daylit
