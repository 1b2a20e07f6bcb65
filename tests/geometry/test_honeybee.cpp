// Honeybee models (geometry/honeybee_model.hpp) on honeybee-schema's public sample models
// (tests/data/honeybee/README.md), synthetic Radiance folders and bad input.

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "geometry/honeybee_model.hpp"
#include "geometry/input_checks.hpp"
#include "geometry/visibility.hpp"
#include "illumination/solid_angle.hpp"
#include "materials/scene_materials.hpp"

using namespace daylit;
using Catch::Contains;

namespace {

const std::string kData = DAYLIT_TEST_DATA_DIR "/honeybee/";

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

const Polygon* find(const std::vector<Polygon>& polygons, const std::string& name) {
  for (const auto& p : polygons)
    if (p.name == name) return &p;
  return nullptr;
}

double area(const std::vector<Vec3>& v) { return 0.5 * norm(newell_normal(v)); }

// A file of a synthetic Radiance folder, its folders made.
void write_file(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// The smallest valid HBJSON room around one face, for bad-input cases.
std::string model_with_face(const std::string& face, const std::string& radiance = "{}") {
  return R"({"type": "Model", "identifier": "m", "properties": {"type": "ModelProperties", "radiance": )" + radiance +
         R"(}, "rooms": [{"type": "Room", "identifier": "r", "properties": {}, "faces": [)" + face + "]}]}";
}

const char* const kWall =
    R"({"type": "Face", "identifier": "w", "face_type": "Wall", "boundary_condition": {"type": "Outdoors"},
        "properties": {}, "geometry": {"type": "Face3D", "boundary": [[0,0,0],[4,0,0],[4,0,3],[0,0,3]]}})";

}  // namespace

TEST_CASE("HBJSON: a door becomes an occluder, the window is cut out of its wall, Honeybee's defaults apply") {
  const HoneybeeModel model = read_honeybee_model(kData + "model_5vertex_sub_faces.hbjson");
  CHECK(model.rooms == 1);
  CHECK(model.faces == 6);
  CHECK(model.apertures == 1);
  CHECK(model.doors == 1);
  CHECK(model.grids.empty());
  // No radiance properties at all: Honeybee's default set, with its exact values.
  const Material& glass = model.content.materials.at("generic_exterior_window_vis_0.64");
  CHECK(glass.type == "glass");
  CHECK(glass.reals == std::vector<double>(3, 0.6975761815384331));
  CHECK(model.content.materials.at("generic_wall_0.50").reals == std::vector<double>{0.5, 0.5, 0.5, 0, 0});
  CHECK(model.content.materials.at("generic_opaque_door_0.50").type == "plastic");

  const Scene scene = assemble_scene(model.content);
  REQUIRE(scene.apertures.size() == 1);
  CHECK(scene.apertures[0].polygon.name == "FrontAperture");
  CHECK(scene.apertures[0].transmittance == Approx(0.64).epsilon(1e-6));  // Radiance's 0.88/0.64 naming
  CHECK(scene.occluders.size() == 7);                                     // 6 faces and the door
  CHECK(find(scene.occluders, "FrontDoor") != nullptr);
  bool door_notice = false;
  for (const auto& n : scene.notices) door_notice |= n.find("'FrontDoor' first") != std::string::npos;
  CHECK(door_notice);

  // The wall holding both is punched: its area is the wall's less the window's and the door's
  // (the door, a pentagon on the floor line, shares an edge stretch with the wall's boundary).
  const Polygon* door = find(scene.occluders, "FrontDoor");
  const Aperture& window = scene.apertures[0];
  const Polygon* wall = nullptr;
  for (const auto& p : scene.occluders)
    if (p.vertices.size() > 8) wall = &p;
  REQUIRE(wall != nullptr);
  double full = 0;
  {
    // The wall's own boundary: its first four vertices before any seam.
    std::vector<Vec3> outline;
    for (const Vec3& v : wall->vertices) {
      if (!outline.empty() && v == outline.front()) break;
      outline.push_back(v);
    }
    full = area(outline);
  }
  CHECK(area(wall->vertices) == Approx(full - area(window.polygon.vertices) - area(door->vertices)).epsilon(1e-12));

  // From inside the room, the window is seen whole: the punched wall does not cover it. The
  // reference is the window alone, clipped to the same hemisphere.
  Vec3 centre;
  for (const Vec3& v : window.polygon.vertices) centre += v;
  centre = centre / double(window.polygon.vertices.size());
  const Vec3 unit_normal = newell_normal(window.polygon.vertices) / norm(newell_normal(window.polygon.vertices));
  // Honeybee's normals point out of the room: the sensor stands 1.5 inside, facing the window.
  const Vec3 p = centre - unit_normal * 1.5;
  Scene alone;
  alone.apertures.push_back(window);
  const VisibilityEngine with(scene, GeometryMode::exact), without(alone, GeometryMode::exact);
  VisibilityCounters counters;
  const double seen = solid_angle(with.visible_region(p, unit_normal, 0, counters));
  const double whole = solid_angle(without.visible_region(p, unit_normal, 0, counters));
  CHECK(whole > 0.1);
  CHECK(seen == Approx(whole).epsilon(1e-12));
}

TEST_CASE("HBJSON: a room's modifier set, the model's modifiers and their defaults") {
  const HoneybeeModel model = read_honeybee_model(kData + "model_complete_multiroom_radiance.hbjson");
  CHECK(model.rooms == 3);
  CHECK(model.faces == 17);
  CHECK(model.apertures == 8);
  const auto material_of = [&](const std::string& name) {
    for (const auto& e : model.content.polygons)
      if (e.polygon.name == name) return e.polygon.material;
    return std::string("(none)");
  };
  CHECK(material_of("First_Floor_Front_Glz0") == "Triple_Pane_0.35");           // its own
  CHECK(material_of("Second_Floor_Front_Glz0") == "generic_exterior_window_vis_0.64");  // the default set
  CHECK(model.content.materials.at("Triple_Pane_0.35").type == "glass");
  // The attic's set names PolyIso for exterior roofs only, and the attic's faces are a floor and
  // walls: its null wall slots take the default set's modifier.
  int polyiso = 0, attic_walls = 0;
  for (const auto& e : model.content.polygons) {
    polyiso += e.polygon.material == "PolyIso";
    attic_walls += e.polygon.where.file.find("rooms[2].faces") != std::string::npos && e.polygon.material == "generic_wall_0.50";
  }
  CHECK(polyiso == 0);
  CHECK(attic_walls == 4);
  const Scene scene = assemble_scene(model.content);
  CHECK(scene.apertures.size() == 8);
  CHECK(scene.occluders.size() == 17);
}

TEST_CASE("HBJSON: a room's modifier set fills its slots, null slots take Honeybee's defaults") {
  const std::string radiance = R"({"modifiers": [{"type": "Plastic", "identifier": "paint", "r_reflectance": 0.3,
      "g_reflectance": 0.3, "b_reflectance": 0.3, "specularity": 0, "roughness": 0}],
      "modifier_sets": [{"type": "ModifierSetAbridged", "identifier": "s",
                         "wall_set": {"exterior_modifier": "paint", "interior_modifier": null}}]})";
  std::string text = model_with_face(kWall, radiance);
  text.replace(text.find(R"("identifier": "r", "properties": {})"), 35,
               R"("identifier": "r", "properties": {"radiance": {"modifier_set": "s"}})");
  const HoneybeeModel model = parse_hbjson(text, "m.hbjson");
  REQUIRE(model.content.polygons.size() == 1);
  CHECK(model.content.polygons[0].polygon.material == "paint");
  std::string unknown = text;
  unknown.replace(unknown.find(R"("modifier_set": "s")"), 19, R"("modifier_set": "t")");
  CHECK_THAT(error_of([&] { parse_hbjson(unknown, "m.hbjson"); }),
             Contains("rooms[0].properties.radiance.modifier_set") && Contains("'t' is not in"));
}

TEST_CASE("HBJSON: a window between two rooms is one interior pane, doors between them occluders, said so") {
  const HoneybeeModel model = read_honeybee_model(kData + "model_5vertex_sub_faces_interior.hbjson");
  CHECK(model.rooms == 2);
  CHECK(model.apertures == 2);  // the window, once per room
  CHECK(model.doors == 2);
  const Scene scene = assemble_scene(model.content);
  REQUIRE(scene.apertures.size() == 1);  // one pane: the second room's copy has the same vertices
  CHECK(scene.interior_apertures == 1);
  CHECK(!scene.apertures[0].angular_transmittance.empty());  // glass, angle-dependent
  CHECK(scene.occluders.size() == 12 + 2);
  bool pane = false, copy = false;
  for (const auto& n : scene.notices) {
    pane |= n.find("1 glass polygon") != std::string::npos && n.find("taken as panes") != std::string::npos;
    copy |= n.find("adjacent room's copy") != std::string::npos;
  }
  CHECK(pane);
  CHECK(copy);
}

TEST_CASE("Honeybee Radiance folder: an interior window's two copies, 2 x tolerance apart facing opposite ways, are one pane") {
  const std::filesystem::path root = std::filesystem::temp_directory_path() / "daylit_test_hb_interior";
  std::filesystem::remove_all(root);
  const auto write = [&](const std::string& relative, const std::string& text) { write_file(root / relative, text); };
  write("model/scene/m.mat", "void glass clear 0 0 3 .96 .96 .96\n");
  // Room A's copy at y = 3 facing +y; room B's moved 2 x 0.01 into room B, facing -y (as
  // Honeybee's translator writes them); a pane of another window facing the same way 0.02 behind
  // its twin (double glazing drawn as two panes), and one facing the other way 0.5 away (beyond 5 %
  // of its 1.41 m extent): both stay two panes.
  write("model/scene/m.rad",
        "clear polygon a_window 0 0 12 1 3 1  1 3 2  2 3 2  2 3 1\n"
        "clear polygon b_window 0 0 12 1 3.02 1  2 3.02 1  2 3.02 2  1 3.02 2\n"
        "clear polygon outer 0 0 12 5 3 1  5 3 2  6 3 2  6 3 1\n"
        "clear polygon inner 0 0 12 5 3.02 1  5 3.02 2  6 3.02 2  6 3.02 1\n"
        "clear polygon far_a 0 0 12 8 3 1  8 3 2  9 3 2  9 3 1\n"
        "clear polygon far_b 0 0 12 8 3.5 1  9 3.5 1  9 3.5 2  8 3.5 2\n");
  const HoneybeeModel model = read_honeybee_model(root.string());
  const Scene scene = assemble_scene(model.content);
  REQUIRE(scene.apertures.size() == 5);  // b_window left out
  CHECK(scene.interior_apertures == 1);  // a_window
  CHECK(scene.apertures[0].polygon.name == "a_window");
  bool copy = false;
  for (const auto& n : scene.notices) copy |= n.find("'b_window' first) left out as the adjacent room's copy") != std::string::npos;
  CHECK(copy);
  std::filesystem::remove_all(root);
}

TEST_CASE("HBJSON: sensor grids come from properties.radiance, named and ordered as the model's") {
  const HoneybeeModel model = read_honeybee_model(kData + "model_radiance_grid_views.hbjson");
  REQUIRE(model.grids.size() == 2);
  CHECK(model.grids[0].name == "Tiny_House_Zone");
  CHECK(model.grids[1].name == "Tiny_Garage");
  CHECK(model.grids[0].sensors.size() == 200);
  CHECK(model.grids[1].sensors.size() == 200);
  for (const auto& g : model.grids)
    for (const auto& s : g.sensors) CHECK(std::abs(norm(s.normal) - 1) < 1e-15);
}

TEST_CASE("HBJSON: lower-case modifier types (older files) and a window on its wall's edge") {
  // A full-width window along the bottom of its wall: its edge lies on the wall's boundary.
  const std::string face =
      R"({"type": "Face", "identifier": "w", "face_type": "Wall", "boundary_condition": {"type": "Outdoors"},
          "properties": {"radiance": {"modifier": "paint"}},
          "geometry": {"type": "Face3D", "boundary": [[0,0,0],[4,0,0],[4,0,3],[0,0,3]]},
          "apertures": [{"type": "Aperture", "identifier": "a", "boundary_condition": {"type": "Outdoors"},
                         "properties": {"radiance": {"modifier": "clear"}},
                         "geometry": {"type": "Face3D", "boundary": [[1,0,0],[3,0,0],[3,0,2],[1,0,2]]}}]})";
  const std::string radiance = R"({"modifiers": [
      {"type": "plastic", "identifier": "paint", "r_reflectance": 0.5, "g_reflectance": 0.5, "b_reflectance": 0.5,
       "specularity": 0, "roughness": 0},
      {"type": "glass", "identifier": "clear", "r_transmissivity": 0.96, "g_transmissivity": 0.96,
       "b_transmissivity": 0.96, "refraction_index": null}]})";
  const HoneybeeModel model = parse_hbjson(model_with_face(face, radiance), "m.hbjson");
  const Scene scene = assemble_scene(model.content);
  REQUIRE(scene.apertures.size() == 1);
  REQUIRE(scene.occluders.size() == 1);
  CHECK(area(scene.occluders[0].vertices) == Approx(12 - 4).epsilon(1e-14));
  // Seen from inside (y > 0), nothing of the wall covers the window.
  Scene alone;
  alone.apertures = scene.apertures;
  const VisibilityEngine with(scene, GeometryMode::exact), without(alone, GeometryMode::exact);
  VisibilityCounters counters;
  for (const Vec3 p : {Vec3{2, 1, 1}, Vec3{0.5, 2, 0.2}, Vec3{3.9, 0.5, 1.5}}) {
    const double whole = solid_angle(without.visible_region(p, {0, -1, 0}, 0, counters));
    CHECK(whole > 0.01);
    CHECK(solid_angle(with.visible_region(p, {0, -1, 0}, 0, counters)) == Approx(whole).epsilon(1e-12));
  }
}

TEST_CASE("HBJSON: bad input names the file and the JSON path") {
  CHECK_THAT(error_of([] { parse_hbjson("{\n\"type\": \"Model\",\n]", "m.hbjson"); }),
             Contains("m.hbjson:3:") && Contains("JSON syntax error"));
  CHECK_THAT(error_of([] { parse_hbjson(R"({"type": "Room"})", "m.hbjson"); }), Contains("not an HBJSON model"));
  std::string face = kWall;
  face.replace(face.find("\"boundary\""), 10, "\"outline\"");
  CHECK_THAT(error_of([&] { parse_hbjson(model_with_face(face), "m.hbjson"); }),
             Contains("m.hbjson: rooms[0].faces[0].geometry: missing \"boundary\""));
  face = kWall;
  face.replace(face.find("[4,0,3]"), 7, "[4,0,\"x\"]");
  CHECK_THAT(error_of([&] { parse_hbjson(model_with_face(face), "m.hbjson"); }),
             Contains("rooms[0].faces[0].geometry.boundary[2][2]: expected a number, found a string"));
  face = kWall;
  face.replace(face.find("\"Wall\""), 6, "\"Ceiling\"");
  CHECK_THAT(error_of([&] { parse_hbjson(model_with_face(face), "m.hbjson"); }), Contains("rooms[0].faces[0].face_type"));
  face = kWall;
  face.replace(face.find("\"properties\": {}"), 16, R"("properties": {"radiance": {"modifier": "nowhere"}})");
  CHECK_THAT(error_of([&] { parse_hbjson(model_with_face(face), "m.hbjson"); }),
             Contains("rooms[0].faces[0]: modifier 'nowhere' is neither"));
  CHECK_THAT(error_of([] {
               parse_hbjson(model_with_face(kWall, R"({"modifiers": [{"type": "Glass", "identifier": "g",
                 "r_transmissivity": 7, "g_transmissivity": 0.5, "b_transmissivity": 0.5}]})"), "m.hbjson");
             }),
             Contains("properties.radiance.modifiers[0]") && Contains("transmissivity 7"));
  CHECK_THAT(error_of([] {
               parse_hbjson(model_with_face(kWall, R"({"modifiers": [{"type": "Mixture", "identifier": "x"}]})"), "m.hbjson");
             }),
             Contains("properties.radiance.modifiers[0].type: modifier type 'mixture' is not read"));
  face = kWall;
  face.replace(face.find("[4,0,3],[0,0,3]"), 15, "[2,0,0],[3,0,0]");  // collinear: zero area
  CHECK_THAT(error_of([&] { parse_hbjson(model_with_face(face), "m.hbjson"); }),
             Contains("m.hbjson rooms[0].faces[0]:") && Contains("zero area"));
  CHECK_THAT(error_of([] { read_honeybee_model("/nonexistent/m.hbjson"); }), Contains("cannot open"));
}

TEST_CASE("Honeybee Radiance folder: .mat before .rad, .blk not read, grids in _info.json's order") {
  const std::filesystem::path root = std::filesystem::temp_directory_path() / "daylit_test_hb_folder";
  std::filesystem::remove_all(root);
  const auto write = [&](const std::string& relative, const std::string& text) { write_file(root / relative, text); };
  write("model/scene/envelope.mat", "void plastic wall 0 0 5 .5 .5 .5 0 0\n");
  write("model/scene/envelope.rad", "wall polygon floor 0 0 12 0 0 0 0 4 0 4 4 0 4 0 0\n");
  write("model/scene/envelope.blk", "this is not read: it would be an error\n");
  write("model/aperture/a.mat", "void glass clear 0 0 3 .96 .96 .96\nvoid plastic door_paint 0 0 5 .5 .5 .5 0 0\n");
  write("model/aperture/a.rad",
        "clear polygon window 0 0 12 0 0 3 1 0 3 1 1 3 0 1 3\ndoor_paint polygon door 0 0 12 2 0 0 3 0 0 3 0 2 2 0 2\n");
  write("model/aperture/a.blk", "garbage too\n");
  write("model/grid/b.pts", "1 1 0.8 0 0 1\n");
  write("model/grid/a.pts", "2 2 0.8 0 0 1\n2 3 0.8 0 0 1\n");
  write("model/grid/_info.json", R"([{"identifier": "b", "full_id": "b"}, {"identifier": "a", "full_id": "a"}])");
  const HoneybeeModel model = read_honeybee_model(root.string());
  REQUIRE(model.grids.size() == 2);
  CHECK(model.grids[0].name == "b");
  CHECK(model.grids[1].sensors.size() == 2);
  const Scene scene = assemble_scene(model.content);
  CHECK(scene.apertures.size() == 1);
  CHECK(scene.occluders.size() == 2);  // the floor and the door (from the aperture folder)
  // The folder itself (holding model/) and model/ both work; something else is named.
  CHECK(read_honeybee_model((root / "model").string()).grids.size() == 2);
  CHECK_THAT(error_of([&] { read_honeybee_model((root / "model" / "grid").string()); }),
             Contains("not a Honeybee Radiance folder"));
  std::filesystem::remove_all(root);
}

TEST_CASE("Honeybee: a hole in an aperture is an opening of transmittance 1, from HBJSON and from a folder's seams") {
  // honeybee-schema's model_complete_holes: a 2 x 2 m window with a 1 x 1 m hole; the wall is cut
  // by the window's outer outline, so Radiance sees the sky through the hole.
  const Scene from_hbjson = assemble_scene(read_honeybee_model(kData + "model_complete_holes.hbjson").content);
  REQUIRE(from_hbjson.apertures.size() == 2);
  const Aperture* hole = nullptr;
  for (const auto& a : from_hbjson.apertures)
    if (a.polygon.name == "HoleAperture hole 1") hole = &a;
  REQUIRE(hole != nullptr);
  CHECK(hole->transmittance == 1);
  CHECK(hole->angular_transmittance.empty());
  CHECK(area(hole->polygon.vertices) == Approx(1).epsilon(1e-15));
  bool said = false;
  for (const auto& n : from_hbjson.notices) said |= n.find("1 holes in 1 apertures or doors taken as openings") != std::string::npos;
  CHECK(said);

  // A folder's window with two holes, bridged from different boundary vertices (as
  // ladybug-geometry bridges them), and a window without holes: the holes come back as openings
  // turning as their window does; the window without holes gets none.
  const std::filesystem::path root = std::filesystem::temp_directory_path() / "daylit_test_hb_holes";
  std::filesystem::remove_all(root);
  write_file(root / "model/aperture/a.mat", "void glass clear 0 0 3 .96 .96 .96\n");
  write_file(root / "model/aperture/a.rad",
             "clear polygon w 0 0 48  0 0 0  4 0 0  4 0 3  3 0 2  3 0 1  2 0 1  2 0 2  3 0 2  4 0 3  0 0 3"
             "  1 0 2.5  1.5 0 2.5  1.5 0 0.5  1 0 0.5  1 0 2.5  0 0 3\n"
             "clear polygon plain 0 0 12  5 0 0  6 0 0  6 0 1  5 0 1\n");
  const Scene from_folder = assemble_scene(read_honeybee_model(root.string()).content);
  REQUIRE(from_folder.apertures.size() == 4);
  std::vector<double> hole_areas;
  for (const auto& a : from_folder.apertures)
    if (a.polygon.material == "void") {
      CHECK(a.transmittance == 1);
      CHECK(dot(newell_normal(a.polygon.vertices), newell_normal(from_folder.apertures[0].polygon.vertices)) > 0);
      hole_areas.push_back(area(a.polygon.vertices));
    }
  std::sort(hole_areas.begin(), hole_areas.end());
  REQUIRE(hole_areas.size() == 2);
  CHECK(hole_areas[0] == Approx(1).epsilon(1e-15));
  CHECK(hole_areas[1] == Approx(1).epsilon(1e-15));
  std::filesystem::remove_all(root);
}
