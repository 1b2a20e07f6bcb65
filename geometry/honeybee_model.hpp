#pragma once
// Honeybee models as users have them: an HBJSON file (honeybee-schema's Model) or a Honeybee
// Radiance folder (what honeybee-radiance's `model-to-rad-folder` writes), read into the same
// RadContent the .rad reader produces, with the model's sensor grids.
//
// HBJSON: rooms → faces → apertures and doors, orphaned faces, apertures, doors and shades, shade
// meshes, with the modifiers and modifier sets of `properties.radiance`; where none is assigned,
// Honeybee's own rule picks the modifier from the room's modifier set, else from Honeybee's
// default set (honeybee_model.cpp states its values and their source). Faces are punched: each
// face's polygon has its holes and its apertures' and doors' outlines cut out by seams (as
// Honeybee's writer does), so a window is not covered by its own wall. Apertures and doors on an
// Outdoors boundary condition come from "aperture files" (their glass is a sky opening, opaque
// doors are occluders); those on a Surface boundary condition (between two rooms) are marked
// RadContent::Entry::interior. Air boundaries are left out (Honeybee writes no geometry for them).
// A hole in an aperture or door on the outside is an opening of transmittance 1 (Honeybee cuts the
// wall by the outer outline, so Radiance sees the sky through it). Dynamic groups, apertures and
// shades, are taken in their first state with the geometry that state adds, as Honeybee's static
// octree includes them.
// The geometry is read as it is: Honeybee's translator moves one face of each pair shared by two
// rooms 2 × tolerance into its room, so the two paths may differ there, and only there.
//
// Radiance folder: model/scene/*.mat then *.rad, model/aperture/*.mat then *.rad, the first
// (static default) state of each group in model/aperture_group/states.json and in the dynamic
// shade groups' model/scene_dynamic/states.json and scene_dynamic/indoor/states.json, and the grids
// of model/grid (in _info.json's order, else by file name). The holes that seams cut in polygons
// of aperture files are openings, as above. The .blk files (black redefinitions of the same
// modifiers, for other simulations) are not read.

#include <string>
#include <vector>

#include "geometry/rad_reader.hpp"
#include "geometry/sensor_grid.hpp"

namespace daylit {

struct HoneybeeModel {
  RadContent content;
  // The floors of each room (faces of type Floor; their own holes, not their sub-faces), for grids.
  struct RoomFloor {
    std::string room;
    std::vector<std::vector<Vec3>> loops;
  };
  std::vector<RoomFloor> floors;
  // Every face of each room, its outer boundary (sub-faces lie in it): the room's closed volume,
  // for what lies inside it (daylit grid keeps the sensors its room encloses).
  struct RoomFace {
    std::string room;
    std::vector<Vec3> boundary;
  };
  std::vector<RoomFace> room_faces;
  std::vector<SensorGrid> grids;  // the model's, in its order
  // What an HBJSON held (a folder leaves them 0: it holds polygons, not rooms).
  long rooms = 0, faces = 0, apertures = 0, doors = 0, shades = 0;
};

// Reads an HBJSON file, or the folder that holds model/ (or model/ itself). Throws daylit::Error
// naming the file and the JSON path (e.g. "m.hbjson: rooms[2].faces[0].geometry.boundary: …") or
// file:line of bad input.
HoneybeeModel read_honeybee_model(const std::string& path);

// The HBJSON text itself; `name` is used in messages.
HoneybeeModel parse_hbjson(const std::string& text, const std::string& name);

}  // namespace daylit
