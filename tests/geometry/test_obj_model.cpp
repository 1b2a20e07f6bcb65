// Wavefront OBJ models (geometry/obj_model.hpp), the material map (geometry/obj_material_map.hpp)
// and the roles of their faces (materials/obj_materials.hpp): the bundled room and office written
// as OBJ (tests/data/obj/make_obj_models.py) against their .rad files, tinyobjloader's double
// build as an independent reader of the same files, and bad input.

#include <catch2/catch.hpp>

#include <cmath>
#include <map>

#include <tiny_obj_loader.h>

#include "geometry/obj_material_map.hpp"
#include "geometry/obj_model.hpp"
#include "geometry/text_scanner.hpp"
#include "materials/obj_materials.hpp"
#include "materials/scene_materials.hpp"

using namespace daylit;
using Catch::Contains;

namespace {

const std::string kData = DAYLIT_TEST_DATA_DIR "/obj/";
const std::string kSamples = DAYLIT_SAMPLES_DIR "/";

// An OBJ text with .mtl libraries in memory.
ObjModel obj(const std::string& text, const std::map<std::string, std::string>& libraries = {},
             const ObjOptions& options = {}) {
  return parse_obj(text, "m.obj", options, [&](const std::string& name) -> std::optional<std::pair<std::string, std::string>> {
    const auto it = libraries.find(name);
    if (it == libraries.end()) return std::nullopt;
    return std::pair{name, it->second};
  });
}

Scene scene_of(const ObjModel& model, const std::string& map_json = "") {
  if (map_json.empty()) return assemble_scene(obj_rad_content(model));
  const ObjMaterialMap map = parse_obj_material_map(map_json, "map.json");
  return assemble_scene(obj_rad_content(model, &map));
}

bool has_notice(const Scene& scene, const std::string& text) {
  for (const auto& n : scene.notices)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

// The scenes of the same polygons: identical vertex doubles, the same reflectances, the same
// apertures with the same glass fit. Exact comparisons: the OBJ files hold the .rad's decimal text
// (or, for millimetres, 1000 times it, which the reader divides back to the nearest double).
void check_same_scene(const Scene& a, const Scene& b) {
  REQUIRE(a.occluders.size() == b.occluders.size());
  REQUIRE(a.apertures.size() == b.apertures.size());
  for (std::size_t i = 0; i < a.occluders.size(); ++i) {
    INFO("occluder " << i << ": " << a.occluders[i].name << " / " << b.occluders[i].name);
    CHECK(a.occluders[i].vertices == b.occluders[i].vertices);
    const Material& ma = a.materials.at(a.occluders[i].material);
    const Material& mb = b.materials.at(b.occluders[i].material);
    CHECK(ma.type == mb.type);
    CHECK(ma.reals == mb.reals);
  }
  for (std::size_t i = 0; i < a.apertures.size(); ++i) {
    CHECK(a.apertures[i].polygon.vertices == b.apertures[i].polygon.vertices);
    CHECK(a.apertures[i].transmittance == b.apertures[i].transmittance);
    CHECK(a.apertures[i].angular_transmittance == b.apertures[i].angular_transmittance);
  }
}

Scene rad_scene(const std::string& sample) {
  return load_scene({kSamples + sample + "/scene.rad"}, {kSamples + sample + "/apertures.rad"});
}

}  // namespace

TEST_CASE("OBJ: the room and the office written as OBJ are the scenes of their .rad files") {
  for (const std::string sample : {"room", "office"}) {
    INFO(sample);
    const ObjMaterialMap map = read_obj_material_map(kData + sample + "_map.json");
    const Scene from_obj = assemble_scene(obj_rad_content(read_obj_model(kData + sample + ".obj"), &map));
    check_same_scene(from_obj, rad_scene(sample));
  }
}

TEST_CASE("OBJ: y up in millimetres reads back to the room in metres, exactly, relative indices and v/vt/vn too") {
  const ObjMaterialMap map = read_obj_material_map(kData + "room_map.json");
  const Scene rad = rad_scene("room");
  ObjOptions mm;
  mm.metres_per_unit = 0.001;
  mm.up = ObjUpAxis::y;
  check_same_scene(assemble_scene(obj_rad_content(read_obj_model(kData + "room_yup_mm.obj", mm), &map)), rad);
  const ObjModel indices = read_obj_model(kData + "room_indices.obj");
  CHECK(indices.vertices == 35);  // every face's vertices again, referenced backwards
  check_same_scene(assemble_scene(obj_rad_content(indices, &map)), rad);
}

TEST_CASE("OBJ: faces, groups and materials agree with tinyobjloader's double build, whose numbers are not correctly rounded") {
  // (room_indices.obj is left out: tinyobjloader does not join lines continued with a backslash,
  // and refuses the face that ends in one.)
  for (const std::string file : {"room.obj", "room_yup_mm.obj", "office.obj"}) {
    INFO(file);
    const ObjModel ours = read_obj_model(kData + file);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    REQUIRE(tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, (kData + file).c_str(), kData.c_str(), false));
    static_assert(sizeof(tinyobj::real_t) == sizeof(double), "link tinyobjloader::tinyobjloader_double");
    CHECK(long(attrib.vertices.size()) == 3 * ours.vertices);
    std::size_t face = 0;
    long differ = 0, coordinates = 0;
    for (const auto& shape : shapes) {
      std::size_t offset = 0;
      for (std::size_t k = 0; k < shape.mesh.num_face_vertices.size(); ++k) {
        REQUIRE(face < ours.faces.size());
        const ObjFace& f = ours.faces[face++];
        CHECK(shape.name == f.groups.front());
        const int id = shape.mesh.material_ids[k];
        CHECK((id < 0 ? std::string() : materials[std::size_t(id)].name) == f.polygon.material);
        // Ours drops repeated consecutive vertices (none in these files) and nothing else.
        const std::size_t n = shape.mesh.num_face_vertices[k];
        REQUIRE(n == f.polygon.vertices.size());
        for (std::size_t j = 0; j < n; ++j) {
          const std::size_t v = std::size_t(shape.mesh.indices[offset + j].vertex_index);
          for (int c = 0; c < 3; ++c) {
            const double theirs = attrib.vertices[3 * v + std::size_t(c)], mine = f.polygon.vertices[j][c];
            // tinyobjloader sums digit × 10^-k: within a few ulp of the nearest double, not on it.
            CHECK(std::abs(theirs - mine) <= 4 * std::numeric_limits<double>::epsilon() * std::abs(mine));
            ++coordinates;
            differ += theirs != mine;
          }
        }
        offset += n;
      }
    }
    CHECK(face == ours.faces.size());
    WARN(file << ": tinyobjloader's coordinate differs from the nearest double in " << differ << " of " << coordinates);
  }
  // Relative indices and the v/vt/vn forms, read by both.
  const std::string relative = "v 0 0 0.3\nv 1 0 0.3\nv 1 1 0.3\nv 0 1 0.3\nvt 0 0\nvt 1 0\nvn 0 0 1\n"
                               "g A\nf -4/-2/-1 -3/-1/-1 -2//-1\ng B\nf 1/1 -3/2 -1/1\n";
  tinyobj::ObjReader reader;
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  REQUIRE(reader.ParseFromString(relative, "", config));
  const ObjModel m = obj(relative);
  REQUIRE(reader.GetShapes().size() == 2);
  REQUIRE(m.faces.size() == 2);
  for (std::size_t s = 0; s < 2; ++s) {
    CHECK(reader.GetShapes()[s].name == m.faces[s].groups.front());
    for (std::size_t j = 0; j < 3; ++j) {
      const std::size_t v = std::size_t(reader.GetShapes()[s].mesh.indices[j].vertex_index);
      CHECK(reader.GetAttrib().vertices[3 * v] == m.faces[s].polygon.vertices[j].x);
      CHECK(reader.GetAttrib().vertices[3 * v + 1] == m.faces[s].polygon.vertices[j].y);
    }
  }
  // The reason the reader is daylit's own: "0.3" must be the double nearest 0.3, as in the .rad
  // and .pts files; tinyobjloader makes it 3 × 0.1 = 0.30000000000000004.
  CHECK(m.faces[0].polygon.vertices[0].z == 0.3);
  CHECK(reader.GetAttrib().vertices[2] != 0.3);
}

TEST_CASE("OBJ: negative indices, the v/vt/vn forms, groups, objects and materials of each face") {
  const ObjModel m = obj(
      "mtllib a.mtl\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n"
      "o Building\ng Walls North\nusemtl Wall\n"
      "f -4/-3/-1 -3/-2/-1 -2/-1/-1\n"  // relative
      "f 1//1 3//1 4//1\n"              // v//vn
      "g\nusemtl Glass\n"
      "f 1/1 2/2 3/3 4/1\n",            // v/vt, a quad
      {{"a.mtl", "newmtl Wall\nKd 0.5 0.5 0.5\nnewmtl Glass\nd 0.3\n"}});
  REQUIRE(m.faces.size() == 3);
  CHECK(m.faces[0].polygon.vertices == std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}});
  CHECK(m.faces[1].polygon.vertices == std::vector<Vec3>{{0, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  CHECK(m.faces[2].polygon.vertices.size() == 4);
  CHECK(m.faces[0].groups == std::vector<std::string>{"Walls", "North"});
  CHECK(m.faces[0].object == "Building");
  CHECK(m.faces[0].polygon.material == "Wall");
  CHECK(m.faces[0].polygon.where.str() == "m.obj:13");
  CHECK(m.faces[2].groups == std::vector<std::string>{"default"});
  CHECK(m.faces[2].polygon.material == "Glass");
  CHECK(m.faces[0].polygon.name == "Walls#1");

  // Without a map: the transparent material is an aperture of transmittance 1 − d, the other
  // opaque with its Kd's grey.
  const Scene s = scene_of(m);
  REQUIRE(s.apertures.size() == 1);
  CHECK(s.apertures[0].transmittance == 1 - 0.3);
  CHECK(s.apertures[0].angular_transmittance.empty());
  CHECK(s.occluders.size() == 2);
  CHECK(s.materials.at("Wall").reals == std::vector<double>{0.5, 0.5, 0.5, 0, 0});
  CHECK(has_notice(s, "materials transparent in the .mtl are apertures of constant transmittance: 'Glass' 0.7"));
}

TEST_CASE("OBJ: units and the up axis") {
  ObjOptions mm;
  mm.metres_per_unit = 0.001;
  const ObjModel a = obj("v 1234 -850 2400.5\nv 0 0 0\nv 1 0 0\nf 1 2 3\n", {}, mm);
  // 1/0.001 is an integer: divided, so each is the double nearest the metres' decimal.
  CHECK(a.faces[0].polygon.vertices[0] == Vec3{1.234, -0.85, 2.4005});
  ObjOptions inch;
  inch.metres_per_unit = 0.0254;
  const ObjModel b = obj("v 10 0 0\nv 0 0 0\nv 0 1 0\nf 1 2 3\n", {}, inch);
  CHECK(b.faces[0].polygon.vertices[0].x == 10 * 0.0254);
  ObjOptions up;
  up.up = ObjUpAxis::y;
  const ObjModel c = obj("v 1 2 3\nv 0 0 0\nv 1 0 0\nf 1 2 3\n", {}, up);
  CHECK(c.faces[0].polygon.vertices[0] == Vec3{1, -3, 2});  // Blender's Y up, −Z forward, undone
  ObjOptions bad;
  bad.metres_per_unit = 0;
  CHECK_THROWS_WITH(obj("v 0 0 0\n", {}, bad), Contains("positive"));
  ObjOptions huge;
  huge.metres_per_unit = 1e9;
  CHECK_THROWS_WITH(obj("v 0 0 0\nv 2000 0 0\n", {}, huge), Contains("m.obj:2") && Contains("beyond 1e12"));
}

TEST_CASE("OBJ: a warped quad becomes two triangles, a warped pentagon is refused, degenerate faces are skipped") {
  // The quad's corner (1, 1) is lifted by 0.01: 5e-3 of its extent, far beyond 1e-4.
  const ObjModel m = obj("v 0 0 0\nv 1 0 0\nv 1 1 0.01\nv 0 1 0\nf 1 2 3 4\n");
  REQUIRE(m.faces.size() == 2);
  CHECK(m.split_quads == 1);
  // Both diagonals keep the triangles facing up; the shorter, 1–3 (0–2 is longer by the lift), is taken.
  CHECK(m.faces[0].polygon.vertices == std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  CHECK(m.faces[1].polygon.vertices == std::vector<Vec3>{{1, 0, 0}, {1, 1, 0.01}, {0, 1, 0}});
  CHECK(m.faces[0].polygon.name == "m#1a");
  CHECK(Contains("m.obj:5: split 1 warped quad").match(m.notices.at(0)));
  // A concave warped quad: only the diagonal from the reflex vertex keeps both triangles.
  const ObjModel dart = obj("v 0 0 0\nv 2 0 0\nv 0.5 0.5 0.05\nv 0 2 0\nf 1 2 3 4\n");
  REQUIRE(dart.faces.size() == 2);
  CHECK(dart.faces[0].polygon.vertices == std::vector<Vec3>{{0, 0, 0}, {2, 0, 0}, {0.5, 0.5, 0.05}});
  // Within tolerance: kept whole (CAD exports in single precision sit near 1e-7).
  CHECK(obj("v 0 0 0\nv 1 0 0\nv 1 1 1e-7\nv 0 1 0\nf 1 2 3 4\n").faces.size() == 1);
  CHECK_THROWS_WITH(obj("v 0 0 0\nv 1 0 0\nv 2 1 0.1\nv 1 2 0\nv 0 1 0\nf 1 2 3 4 5\n"),
                    Contains("m.obj:6") && Contains("not planar") && Contains("export this face as triangles"));
  // Two vertices, a repeated one, collinear ones: skipped, counted once.
  const ObjModel d = obj("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2\nf 1 1 2 2\nf 1 2 3\nf 1 2 4\n");
  CHECK(d.faces.size() == 1);
  CHECK(d.skipped_degenerate == 3);
  CHECK(Contains("m.obj:5: skipped 3 faces with fewer than 3 distinct vertices or zero area").match(d.notices.at(0)));
}

TEST_CASE("OBJ: bad files name the file and line") {
  CHECK_THROWS_WITH(obj("v 0 0 0\nv 1 0 x\n"), Contains("m.obj:2") && Contains("expected a number") && Contains("'x'"));
  CHECK_THROWS_WITH(obj("v 1.5x 0 0\n"), Contains("m.obj:1") && Contains("'1.5x'"));
  CHECK_THROWS_WITH(obj("v 0 0\n"), Contains("m.obj:1") && Contains("x y z"));
  CHECK_THROWS_WITH(obj("v 0,5 0 0\n"), Contains("m.obj:1") && Contains("decimal comma"));
  CHECK_THROWS_WITH(obj("v 0 0 1e999\n"), Contains("m.obj:1") && Contains("out of range"));
  CHECK_THROWS_WITH(obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), Contains("m.obj:4") && Contains("vertex index 9 is out of range: 3 vertices are defined before this line"));
  CHECK_THROWS_WITH(obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 -2 -1\n"), Contains("m.obj:4") && Contains("index -4 is out of range"));
  CHECK_THROWS_WITH(obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"), Contains("m.obj:4") && Contains("index 0"));
  CHECK_THROWS_WITH(obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n"), Contains("texture coordinate index 1 is out of range"));
  CHECK_THROWS_WITH(obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 three\n"), Contains("m.obj:4") && Contains("'three'"));
  CHECK_THROWS_WITH(obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2 3\n"), Contains("ends in '/'"));
  CHECK_THROWS_WITH(obj("# a\n\nsurf 0 1 0 1 1 2 3\n"), Contains("m.obj:3") && Contains("free-form"));
  CHECK_THROWS_WITH(obj("vv 1 2 3\n"), Contains("m.obj:1") && Contains("unknown OBJ statement 'vv'"));
  CHECK_THROWS_WITH(obj("call other.obj\n"), Contains("merge the files"));
  std::string binary(512, '\0');
  for (std::size_t i = 0; i < binary.size(); ++i) binary[i] = char((i * 37) % 32);
  CHECK_THROWS_WITH(obj(binary), Contains("m.obj:1") && Contains("binary"));
  // A continued line keeps the line it starts on.
  CHECK_THROWS_WITH(obj("v 0 0 \\\n 0\nv 1 0 \\\n bad\n"), Contains("m.obj:3") && Contains("'bad'"));
}

TEST_CASE("OBJ: .mtl materials, and bad .mtl files with file:line") {
  std::map<std::string, MtlMaterial> mats;
  std::vector<std::string> notices;
  parse_mtl("# exported\nnewmtl Glass Pane\nKd 0.1\nTr 0.75\nTf 0.9 0.8 0.7\nillum 4\nPr 0.2\nfoo 1\n"
            "newmtl Both\nd 0.4\nTr 0.9\n",
            "a.mtl", mats, notices);
  const MtlMaterial& g = mats.at("Glass Pane");
  CHECK(*g.kd == std::array<double, 3>{0.1, 0.1, 0.1});  // one value: grey
  CHECK(*g.dissolve == 1 - 0.75);                        // Tr is 1 − d
  CHECK(*g.illum == 4);
  CHECK(g.where.str() == "a.mtl:2");
  CHECK(*mats.at("Both").dissolve == 0.4);  // d wins over Tr
  CHECK(*mtl_transmittance(g) == Approx(0.75 * (0.265 * 0.9 + 0.670 * 0.8 + 0.065 * 0.7)).epsilon(1e-15));
  CHECK(Contains("a.mtl:8: skipped 1 statement").match(notices.at(0)));
  const auto bad = [](const std::string& text) {
    std::map<std::string, MtlMaterial> m;
    std::vector<std::string> n;
    parse_mtl(text, "a.mtl", m, n);
  };
  CHECK_THROWS_WITH(bad("newmtl A\nKd 0.5 abc 0.5\n"), Contains("a.mtl:2") && Contains("'abc'"));
  CHECK_THROWS_WITH(bad("newmtl A\nKd 1.2 0.5 0.5\n"), Contains("a.mtl:2") && Contains("outside [0, 1]"));
  CHECK_THROWS_WITH(bad("newmtl A\nd 2\n"), Contains("a.mtl:2") && Contains("outside [0, 1]"));
  CHECK_THROWS_WITH(bad("newmtl A\nKd spectral wood.rfl\n"), Contains("spectral"));
  CHECK_THROWS_WITH(bad("newmtl A\nillum 12\n"), Contains("illum"));
  CHECK_THROWS_WITH(bad("Kd 0.5 0.5 0.5\n"), Contains("a.mtl:1") && Contains("before any newmtl"));
  // illum 6/7 transmit through Tf; Tf alone on an opaque illum does not.
  std::map<std::string, MtlMaterial> m;
  parse_mtl("newmtl R\nillum 7\nTf 0.5 0.5 0.5\nnewmtl O\nillum 2\nTf 1 1 1\n", "b.mtl", m, notices);
  CHECK(*mtl_transmittance(m.at("R")) == 0.5);
  CHECK(!mtl_transmittance(m.at("O")));
}

TEST_CASE("OBJ: a missing .mtl is an error when a face needs it, a notice when the map gives everything") {
  const std::string text = "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl Wall\nf 1 2 3\nusemtl Glass\nf 1 2 4\n";
  CHECK_THROWS_WITH(scene_of(obj(text)), Contains("m.obj:1") && Contains("mtllib 'gone.mtl'") && Contains("cannot read") &&
                                             Contains("2 faces take their material from it"));
  CHECK_THROWS_WITH(scene_of(obj(text), R"({"materials": {"Wall": {"role": "opaque"}, "Glass": {"role": "aperture", "transmittance": 0.6}}})"),
                    Contains("1 face take"));
  const Scene s = scene_of(obj(text), R"({"materials": {"Wall": {"role": "opaque", "reflectance": 0.4},
                                          "Glass": {"role": "aperture", "transmittance": 0.6}}})");
  CHECK(s.apertures.size() == 1);
  CHECK(s.apertures[0].transmittance == 0.6);
  CHECK(has_notice(s, "could not be read"));
  CHECK(has_notice(s, "not needed"));
  // Every material found in another library, no map; and no face at all (fuzz_obj_reader found
  // the notice reaching for the absent map: regression-missing-library-no-map).
  const Scene other = scene_of(obj("mtllib gone.mtl here.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Wall\nf 1 2 3\n",
                                   {{"here.mtl", "newmtl Wall\nKd 0.3 0.3 0.3\n"}}));
  CHECK(has_notice(other, "m.obj:1: mtllib 'gone.mtl' could not be read (gone.mtl); not needed: no face takes a value from it"));
  CHECK(has_notice(scene_of(obj("mtllib gone.mtl\n")), "not needed"));
}

TEST_CASE("OBJ: the map's roles, patterns and precedence") {
  const std::string text =
      "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\n"
      "g Window_1\nusemtl Frame\nf 1 2 3\n"  // a group rule beats the material rule
      "g Wall\nusemtl Brick\nf 1 2 4\n"
      "g Tree\nusemtl Leaves\nf 1 3 4\n"
      "g Skylight\nusemtl Pane\nf 2 3 5\n"
      "g Misc\nf 1 4 5\n";  // still Pane: usemtl stays in force across g
  const std::map<std::string, std::string> libs = {
      {"a.mtl", "newmtl Frame\nKd 0.3 0.3 0.3\nnewmtl Brick\nKd 0.4 0.3 0.2\nKs 0.5 0.5 0.5\nNs 50\nnewmtl Leaves\nKd 0 1 0\n"
                "newmtl Pane\nKd 0 0 0\nd 0.2\n"}};
  const Scene s = scene_of(obj(text, libs), R"({
      "materials": {"Br*": {"role": "opaque", "reflectance": 0.35}, "Brick": {"role": "opaque"},
                    "Leaves": {"role": "ignore"}, "Pane": {"role": "glass", "transmittance": 0.64, "refractive_index": 1.52},
                    "Unused": {"role": "opaque"}},
      "aperture_groups": ["Window_?"]})");
  // Window_1: an aperture by its group; the frame material is not transparent, so open (T = 1).
  // Skylight and Misc: glass of transmittance 0.64. Tree: left out. Wall: Brick's Kd (exact beats Br*).
  REQUIRE(s.apertures.size() == 3);
  CHECK(s.apertures[0].transmittance == 1);
  CHECK(s.apertures[0].polygon.material == "group Window_? / Frame");
  CHECK(s.apertures[1].transmittance == Approx(0.64).epsilon(1e-15));
  CHECK(s.materials.at("Pane").reals.size() == 4);
  REQUIRE(s.occluders.size() == 1);
  CHECK(s.materials.at("Brick").reals == std::vector<double>{0.4, 0.3, 0.2, 0, 0});
  CHECK(has_notice(s, "1 face of aperture rules are open"));
  CHECK(has_notice(s, "1 face left out (role ignore"));
  CHECK(has_notice(s, "the specular Ks/Ns of 'Brick' is not added"));
  CHECK(has_notice(s, "map.json: materials.Unused: matches no face"));
  CHECK(has_notice(s, "map.json: materials.Br*: matches no face"));  // Brick was named exactly

  // Two patterns for one name, glass beyond what glass passes, a glass with no transmittance.
  CHECK_THROWS_WITH(scene_of(obj(text, libs), R"({"materials": {"B*": {"role": "opaque"}, "*k": {"role": "opaque"}}})"),
                    Contains("both match 'Brick'"));
  CHECK_THROWS_WITH(scene_of(obj(text, libs), R"({"materials": {"Pane": {"role": "glass", "transmittance": 0.95}}})"),
                    Contains("map.json: materials.Pane") && Contains("more than glass"));
  CHECK_THROWS_WITH(scene_of(obj(text, libs), R"({"materials": {"Brick": {"role": "glass"}}})"),
                    Contains("needs a transmittance"));
}

TEST_CASE("OBJ: faces without a known material are opaque at 0.5, counted, glass by transmittance inverts Radiance's model") {
  const Scene s = scene_of(obj("mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl Nowhere\nf 1 2 3\nusemtl G\nf 1 2 3\n",
                               {{"a.mtl", "newmtl G\nd 0.5\n"}}),
                           R"({"materials": {"G": {"role": "glass", "transmittance": 0.64}}})");
  CHECK(s.occluders.size() == 2);
  CHECK(s.materials.at("(no material)").reals == std::vector<double>{0.5, 0.5, 0.5, 0, 0});
  CHECK(s.materials.at("Nowhere").reals == std::vector<double>{0.5, 0.5, 0.5, 0, 0});
  CHECK(has_notice(s, "m.obj:5: 2 faces without a material daylit knows"));
  // Honeybee's generic_exterior_window_vis_0.64 uses Radiance's closed form, an approximation of
  // the model whose exact inverse daylit takes: they agree to 1.2e-8.
  const double t = s.materials.at("G").reals[0];
  CHECK(std::abs(t - 0.6975761815384331) < 2e-8);
  CHECK(glass_transmittance({{t, t, t}, 1.52}, 1.0) == Approx(0.64).epsilon(4e-16));
}

TEST_CASE("OBJ material map: bad maps name the JSON path") {
  const auto bad = [](const std::string& json) { parse_obj_material_map(json, "map.json"); };
  CHECK_THROWS_WITH(bad(R"({"material": {}})"), Contains("map.json: material: unknown key"));
  CHECK_THROWS_WITH(bad(R"({"materials": {"W": {"reflectance": 0.5}}})"), Contains("materials.W: missing \"role\""));
  CHECK_THROWS_WITH(bad(R"({"materials": {"W": {"role": "wall"}}})"), Contains("materials.W.role: unknown role 'wall'"));
  CHECK_THROWS_WITH(bad(R"({"materials": {"W": {"role": "opaque", "reflectence": 0.5}}})"),
                    Contains("materials.W.reflectence: unknown field (opaque takes reflectance and floor)"));
  CHECK_THROWS_WITH(bad(R"({"materials": {"W": {"role": "opaque", "transmittance": 0.5}}})"),
                    Contains("materials.W.transmittance: not a field of the role opaque"));
  CHECK_THROWS_WITH(bad(R"({"materials": {"W": {"role": "opaque", "reflectance": 1}}})"),
                    Contains("materials.W.reflectance: 1 is outside [0, 1)"));
  CHECK_THROWS_WITH(bad(R"({"materials": {"W": {"role": "opaque", "reflectance": "0.5"}}})"), Contains("expected a number"));
  CHECK_THROWS_WITH(bad(R"({"materials": {"G": {"role": "glass", "transmittance": 0.6, "transmissivity": 0.7}}})"),
                    Contains("not both"));
  CHECK_THROWS_WITH(bad(R"({"groups": {"W": {"role": "aperture"}}, "aperture_groups": ["W"]})"), Contains("give it once"));
  CHECK_THROWS_WITH(bad(R"({"aperture_groups": "W*"})"), Contains("aperture_groups: expected an array"));
  CHECK_THROWS_WITH(bad("{\n\"materials\": {,}\n}"), Contains("map.json:2") && Contains("JSON syntax error"));
}

TEST_CASE("OBJ material map: glob patterns") {
  CHECK(glob_match("Window*", "Window_12"));
  CHECK(glob_match("*", ""));
  CHECK(glob_match("W?ll", "Wall"));
  CHECK(glob_match("*glass*", "clear_glass_01"));
  CHECK(glob_match("a*b*c", "axxbyyc"));
  CHECK_FALSE(glob_match("a*b*c", "axxbyy"));
  CHECK_FALSE(glob_match("Window*", "window_1"));  // case-sensitive, as OBJ names are
  CHECK_FALSE(glob_match("W?ll", "Wl"));
}
