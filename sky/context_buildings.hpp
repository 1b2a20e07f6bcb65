#pragma once
// Context buildings: footprints from GeoJSON in WGS84, placed into the model frame with a Site and
// extruded into opaque prisms that occlude the apertures.
//
// Input (RFC 7946): a FeatureCollection (or a single Feature) whose features carry Polygon or
// MultiPolygon geometries, positions [longitude, latitude] in degrees (a third number, an
// altitude, is ignored), the first ring of each polygon its outline and the others its holes
// (courtyards). Rings must be closed (last position = first), have at least 3 distinct vertices
// and enclose an area; no ring may cross or touch itself or another ring of its polygon (rings
// may share a vertex), and holes must lie inside the outline and outside each other. Either
// winding is accepted (RFC 7946 asks parsers not to reject the other one). Features of other
// geometry types (points, lines: an OpenStreetMap export has them) and features with null
// geometry are skipped with a notice. Every feature is one building, however many polygons it has.
//
// Properties (as OpenStreetMap's tags and most city-model exports name them):
// - "height" (required): the top of the building in metres above the ground; a number, or a
//   string holding a number with an optional unit "m" ("12", "12.5 m", as OSM exports give it).
//   Any other unit is an error: convert feet yourself.
// - "min_height" or "base" (optional, default 0): the bottom of the prism in metres above the
//   ground, for parts that stand on others or bridge a passage; same forms; below "height".
//
// Placement: a vertex goes where Site::model_from_wgs84 puts (latitude, longitude) at the site's
// origin elevation, keeping x and y; the prism is vertical in the model frame, from
// ground_z + base to ground_z + height (Site::ground_z_m). The earth's curvature is left out: it
// would lower a building at distance d by d²/2R (8 mm at 300 m, 8 cm at 1 km, in angle at most
// d/2R: 0.005° at 1 km). Footprints more than 100 km from the origin are an error (swapped
// longitude and latitude, or the wrong site).
//
// Faces: one vertical quad per footprint edge (holes included) and one roof polygon per polygon,
// its holes cut by seams (Radiance's convention, geometry/convex_pieces.hpp). Outlines are turned
// anticlockwise and holes clockwise seen from above, so every normal points out of the solid. No
// floor is made: a line that passes through the prism crosses its boundary at two points at
// least, and only a line lying in the floor's plane has both on the floor.
//
// Errors name the file and the feature, e.g. "buildings.geojson: feature 3 (id way/1234): …";
// so do the faces' SourceLocations, for errors found later by the visibility engine.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "geometry/polygon.hpp"
#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "sky/site.hpp"
#include "sky/sky_model.hpp"

namespace daylit {

struct PlanPoint {
  double x = 0, y = 0;
};

// One polygon of a footprint in the model's plan: rings[0] the outline (anticlockwise seen from
// above), the others holes (clockwise); no ring repeats its first vertex at the end.
struct Footprint {
  std::vector<std::vector<PlanPoint>> rings;
};

struct ContextBuilding {
  std::size_t feature = 0;  // 0-based index in the FeatureCollection's "features"
  std::string label;        // "buildings.geojson: feature 3 (id way/1234)", for messages
  std::vector<Footprint> parts;
  double base_z = 0, top_z = 0;  // model z of the prism's bottom and top
  Vec3 box_min, box_max;         // axis-aligned bounding box of the prism, model frame
  std::vector<Polygon> faces;    // walls and roofs, model frame, normals out of the solid
};

struct ContextBuildings {
  std::string path;
  std::size_t features = 0;           // features in the file
  std::size_t skipped_features = 0;   // of those, without a Polygon or MultiPolygon geometry
  std::vector<ContextBuilding> buildings;
  std::vector<std::string> notices;
};

// Throws daylit::Error naming the file (and the line for JSON syntax errors, the feature for
// everything else) on bad input.
ContextBuildings read_context_buildings(const std::string& path, const Site& site);
ContextBuildings parse_context_buildings(const std::string& text, const std::string& name, const Site& site);

// Default for the size rule below: a building left out by it changes the sky component at any
// sensor by at most 100·2π(1 − cos 0.05°)/E_h = 9.8e-5 % per aperture under the CIE overcast sky
// (7.6e-5 % under the uniform sky), far below what footprint data (metres) and DF reporting
// (0.1 %) resolve, while a whole city district of footprints kilometres away drops out.
inline constexpr double kDefaultContextMinAngularSizeDeg = 0.1;

// What place_context_buildings did.
struct ContextPlacement {
  std::size_t read = 0;         // buildings read
  std::size_t placed = 0;       // appended to the scene
  std::size_t faces = 0;        // polygons they added to scene.occluders
  std::size_t enclosing_model = 0;   // left out: the prism holds a sensor or an aperture vertex
  std::size_t below_horizon = 0;     // left out (exact): too low to be seen above any sensor's horizon
  std::size_t behind_apertures = 0;  // left out (exact): behind every aperture (or below, for some)
  std::size_t too_small = 0;         // left out (bounded): smaller than the angular threshold
  std::size_t kept_in_sun_beam = 0;  // placed although smaller than the threshold: they meet the sun's beam
  double min_angular_size_deg = 0;
  // Upper bound on the change of the sky component (percent) at any sensor caused by the buildings
  // left out as too small: 100 Σ_buildings Σ_apertures 2π(1 − cos α) L_max / E_h.
  double sc_change_bound_percent = 0;
  // Σ_buildings Σ_apertures 2π(1 − cos α) over the buildings left out as too small: an upper
  // bound on the solid angle they could hide from any sensor (for bounds under other skies and
  // for the sun when no SunBeam was given).
  double left_out_solid_angle_sr = 0;
  bool sun_beam_kept = false;  // a SunBeam was given: nothing left out can hide any of the sun's disk
  std::string rule;  // the rules in words, for the summary
  std::vector<std::string> notices;
};

// The sun's disk seen from the model: the directions within half_angle of `direction` (a unit
// vector towards the sun's centre).
struct SunBeam {
  Vec3 direction;
  double half_angle = 0;
};

// Appends the faces of the buildings that may be seen from the sensors of `grids` through the
// apertures of `scene` to scene.occluders, and leaves the others out. Call it after every
// aperture is in the scene and before the VisibilityEngine is built. For each building:
// 1. Its prism holds a sensor or an aperture vertex: it is the model's own building (OpenStreetMap
//    exports have it) and is left out, with a notice.
// 2. Its box meets the box of the sensors and aperture vertices, or its top is above the lowest
//    sensor of a grid that sees the sky directly (SensorGrid::sees_sky_directly: such a sensor
//    sees it without any aperture): placed. Otherwise no segment from
//    a sensor to an aperture point touches it, so any line of sight reaches it beyond an aperture
//    point q, where it rises no lower than q and than the sensor, and moves away from the sensor's
//    side of the aperture's plane. For each aperture, the building is hidden from it when
//    (a) its top is no higher than the aperture's lowest vertex or than the lowest sensor, or
//    (b) it lies on the side of the aperture's plane where all the sensors are (nothing on the
//        other side, seen through the aperture, can be it), or
//    (c) its angular size 2·asin(r/(d − 2r)) is below min_angular_size_deg, r its bounding
//        sphere's radius, d the distance from the sphere's centre to the nearest point of the
//        aperture: a sensor seeing a building point s through the aperture point q has
//        |p − s| ≥ |q − s| ≥ d − r, so |p − c| ≥ d − 2r and the sphere fills a cone of half-angle
//        α ≤ asin(r/(d − 2r)) around p.
//    With a `sun`, (c) applies only to a building whose sphere also misses the sun's beam through
//    the aperture, the points q + t·s' (q on the aperture, t ≥ 0, s' within the half-angle ρ of
//    the sun's direction s): such a point within r of c has t = |x − q| ≤ D + r, D the largest
//    distance from c to an aperture vertex, so projected along s it lies within (D + r) sin ρ of
//    the projected aperture, and c within r + (D + r) sin ρ of it; and s·c ≥ min s·v − r. A
//    building that fails either cannot shade any part of the disk at any sensor through that
//    aperture; one that passes both is placed (counted in kept_in_sun_beam).
//    A building hidden from every aperture is left out: as too small if (c) was needed for one
//    aperture, else as below the horizon if (a) held for all, else as behind the apertures.
// (a) and (b) change nothing in the sky component; (c) changes it by at most the bound reported,
// and with a `sun` changes nothing of the sun's. min_angular_size_deg = 0 turns rule (c) off.
ContextPlacement place_context_buildings(const ContextBuildings& context, const std::vector<SensorGrid>& grids,
                                         SkyModel sky, double min_angular_size_deg, Scene& scene,
                                         const std::optional<SunBeam>& sun = std::nullopt);

}  // namespace daylit
