#pragma once
// Sensor grids in Radiance's .pts convention: one sensor per line, "x y z dx dy dz".

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/vec3.hpp"

namespace daylit {

struct Sensor {
  Vec3 position;
  Vec3 normal;  // unit
};

struct SensorGrid {
  std::string name;  // file stem, used in reports
  std::string path;
  std::vector<Sensor> sensors;
  // The index of sensors[0] in the grid read from `path`: 0, or where an MPI rank computes a
  // block of it, the block's start (what a result that must not depend on the blocks keys on).
  std::size_t first = 0;
};

// Blank lines and '#' comments are allowed; anything else that is not six finite numbers with a
// non-zero direction is an error naming the file and line. An empty grid is an error.
SensorGrid read_sensor_grid(const std::string& path);
SensorGrid parse_sensor_grid(const std::string& text, const std::string& path);

}  // namespace daylit
