#pragma once
// Sensor grids on the floors of rooms: cell-centred sensors on a square lattice of a given spacing,
// at a height above the floor, kept where the cell centre lies inside the floor and at least the
// wall offset from its boundary. Defaults: 0.85 m above the floor (EN 17037:2018, 5.1: the
// reference plane 0.85 m above the floor) and 0.5 m from the walls (BREEAM Hea 01: the 0.5 m
// perimeter band left out of the assessed area), spacing 0.5 m.

#include <string>
#include <vector>

#include "geometry/obj_model.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/vec3.hpp"

namespace daylit {

struct FloorGridOptions {
  double spacing = 0.5;      // model units; > 0
  double height = 0.85;      // above the floor, along +z
  double wall_offset = 0.5;  // ≥ 0: the least distance of a sensor from the floor's boundary
};

// One floor: loops of vertices in one horizontal plane (an outer boundary and holes, in any
// orientation; Radiance's seams, edges traversed both ways, are allowed and cancel).
struct FloorOutline {
  std::vector<std::vector<Vec3>> loops;
};

// The sensors of one grid over all `floors` (a room's), facing +z. The lattice is aligned with the
// model's x and y axes, its cells' corners at the lowest x and y of the floors' region inset by
// the wall offset, so that a rectangle inset to a × b holds ⌈a/s⌉·⌈b/s⌉ cells whose centres lie
// inside it. Membership is exact for any polygon (the inset of a non-convex floor included): a
// centre is kept when it is inside by the even-odd rule and its distance to every boundary edge
// is at least the offset. Throws daylit::Error for a floor that is not horizontal (its vertices'
// heights differ by more than 1e-6 of its extent). O(cells × edges).
std::vector<Sensor> floor_grid(const std::vector<FloorOutline>& floors, const FloorGridOptions& options);

// Where floors come from: an HBJSON model (one grid per room, named by the room's identifier, from
// its faces of type Floor), an OBJ model (a `model` path ending in .obj, read with `obj`: the faces
// that a rule of the map `obj_materials` marks "floor": true, else every horizontal face facing up;
// one grid per group, else object, name), or .rad files (one grid per floor polygon, named by the
// polygon: those whose modifier is one of `floor_modifiers`, else every horizontal polygon facing
// up, as a Radiance floor faces into its room). Grids with no sensor are left out, said in `notices`.
struct FloorSources {
  std::string model;
  ObjOptions obj;
  std::string obj_materials;
  std::vector<std::string> rad_files;
  std::vector<std::string> floor_modifiers;
};
std::vector<SensorGrid> floor_grids(const FloorSources& sources, const FloorGridOptions& options,
                                    std::vector<std::string>& notices);

}  // namespace daylit
