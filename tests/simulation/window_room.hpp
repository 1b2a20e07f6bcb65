#pragma once
// The window room of the reflected components' tests (test_reflections, test_annual_reflections).

#include <vector>

#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "test_scenes.hpp"

namespace daylit::test {

// A 2 × 2 × 2 m box room (floor 0.2, walls 0.5, ceiling 0.7) with an open 1 × 1 m window in its
// south wall (y = 0, x 0.5..1.5, z 0.6..1.6) and nothing outside but the far ground (0.2): the
// exterior is the far ground, so no occluder lies beyond any luminaire.
struct WindowRoom {
  Scene scene;
  std::vector<double> reflectance;
  SensorGrid grid;
  WindowRoom() {
    const double w = 2;
    scene.occluders = {test::polygon({{0, 0, 0}, {w, 0, 0}, {w, w, 0}, {0, w, 0}}, "floor"),
                       test::polygon({{0, 0, w}, {0, w, w}, {w, w, w}, {w, 0, w}}, "ceiling"),
                       test::polygon({{0, w, 0}, {w, w, 0}, {w, w, w}, {0, w, w}}, "north"),
                       test::polygon({{0, 0, 0}, {0, w, 0}, {0, w, w}, {0, 0, w}}, "west"),
                       test::polygon({{w, 0, 0}, {w, 0, w}, {w, w, w}, {w, w, 0}}, "east"),
                       test::polygon({{0, 0, 0}, {0, 0, w}, {w, 0, w}, {w, 0, 0}, {0.5, 0, 0}, {0.5, 0, 0.6}, {1.5, 0, 0.6},
                                {1.5, 0, 1.6}, {0.5, 0, 1.6}, {0.5, 0, 0.6}, {0.5, 0, 0}},
                               "south")};
    reflectance = {0.2, 0.7, 0.5, 0.5, 0.5, 0.5};
    scene.apertures.push_back({test::polygon({{0.5, 0, 0.6}, {0.5, 0, 1.6}, {1.5, 0, 1.6}, {1.5, 0, 0.6}}, "window"), 1.0});
    grid.name.push_back('g');  // not = "g": GCC 12 warns falsely (-Wrestrict) on that here
    for (double y : {0.5, 1.0, 1.5}) grid.sensors.push_back({{1.0, y, 0.85}, {0, 0, 1}});
    grid.sensors.push_back({{1.0, 1.2, 1.0}, {0, -1, 0}});  // facing the window: sees the far ground
  }
};

}  // namespace daylit::test
