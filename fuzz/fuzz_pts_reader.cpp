// Fuzz target: the .pts reader on arbitrary bytes. Any input must end in a grid of finite sensors
// with unit normals, or in a daylit::Error that names the file (and the line, unless the grid is
// empty); anything else is a finding. The streaming file reader must agree with the in-memory one.

#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "geometry/error.hpp"
#include "geometry/input_checks.hpp"
#include "geometry/sensor_grid.hpp"

namespace {

[[noreturn]] void finding(const char* what, const std::string& detail) {
  std::fprintf(stderr, "%s: %s\n", what, detail.c_str());
  std::abort();
}

// The outcome of a read: the sensors, or the error message.
std::string outcome(const std::string& path, bool from_file, const std::string& text) {
  try {
    const daylit::SensorGrid grid = from_file ? daylit::read_sensor_grid(path) : daylit::parse_sensor_grid(text, path);
    std::string out;
    for (const auto& s : grid.sensors) {
      const daylit::Vec3 &p = s.position, &n = s.normal;
      if (!daylit::is_finite(p) || !daylit::is_finite(n)) finding("non-finite sensor", path);
      if (std::abs(p.x) > daylit::kMaxCoordinate || std::abs(p.y) > daylit::kMaxCoordinate ||
          std::abs(p.z) > daylit::kMaxCoordinate)
        finding("sensor beyond the coordinate bound", path);
      if (std::abs(daylit::norm(n) - 1) > 1e-15) finding("sensor normal not of unit length", path);
      char buf[256];
      std::snprintf(buf, sizeof buf, "%a %a %a %a %a %a\n", p.x, p.y, p.z, n.x, n.y, n.z);
      out += buf;
    }
    return out;
  } catch (const daylit::Error& e) {
    const std::string message = e.what();
    const std::string prefix = path + ":";
    if (message.compare(0, prefix.size(), prefix) != 0) finding("error message lacks the file", message);
    if (message != path + ": the sensor grid is empty" && !(message.size() > prefix.size() && std::isdigit(message[prefix.size()])))
      finding("error message lacks the line", message);
    return "error: " + message;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/fuzz_pts_reader-" + std::to_string(::getpid()) + ".pts";
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::string in_memory = outcome(path, false, text);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  const std::string streamed = outcome(path, true, text);
  if (streamed != in_memory) finding("streaming and in-memory readers disagree", streamed + " / " + in_memory);
  return 0;
}
