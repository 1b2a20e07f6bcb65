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
  // Whether sensors of the grid see the sky directly, not through an aperture (outdoors, on a
  // façade, in a courtyard or a model open to the sky): set where the model is read (a ray test,
  // simulation/model_inputs.cpp); such a grid's sensors also count what they see past every
  // surface (geometry/sky_box.hpp), exactly. Other grids leave that work out.
  bool sees_sky_directly = false;
};

// Blank lines and '#' comments are allowed; anything else that is not six finite numbers with a
// non-zero direction is an error naming the file and line. An empty grid is an error.
SensorGrid read_sensor_grid(const std::string& path);
SensorGrid parse_sensor_grid(const std::string& text, const std::string& path);

}  // namespace daylit
