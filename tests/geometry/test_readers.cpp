// Readers reject bad input with a message naming the file, the line and the problem.

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "materials/scene_materials.hpp"
#include "geometry/rad_reader.hpp"
#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"

using namespace daylit;
using Catch::Contains;

namespace {

RadContent read(const std::string& text, bool apertures = false) {
  RadContent content;
  read_rad_text(text, "scene.rad", apertures, content);
  return content;
}

void write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

}  // namespace

TEST_CASE("polygons, materials, comments and multi-line primitives are read") {
  const auto content = read(
      "# a comment line\n"
      "void plastic wall_mat 0 0 5 0.5 0.5 0.5 0 0\n"
      "void glass clear\n0\n0\n3 0.96 0.96 0.96  # transmissivity\n"
      "wall_mat polygon wall\n0\n0\n12\n 0 0 0\n 1 0 0\n 1 0 1\n 0 0 1\n"
      "clear polygon pane 0 0 9 0 1 0  1 1 0  1 1 1\n");
  REQUIRE(content.polygons.size() == 2);
  CHECK(content.polygons[0].polygon.vertices.size() == 4);
  CHECK(content.polygons[0].polygon.where.line == 7);
  CHECK(content.polygons[1].polygon.where.line == 15);
  const Scene scene = assemble_scene(content);
  CHECK(scene.occluders.size() == 1);
  REQUIRE(scene.apertures.size() == 1);
  // Radiance's own conversion from transmittance T to transmissivity (glass documentation) must
  // give back the 0.96 we wrote.
  const double T = scene.apertures[0].transmittance;
  const double t = (std::sqrt(.8402528435 + .0072522239 * T * T) - .9166530661) / .0036261119 / T;
  CHECK(t == Approx(0.96).epsilon(1e-8));
}

TEST_CASE("sky and source primitives are skipped with a notice") {
  const auto content = read(
      "void brightfunc skyfunc 2 skybright skybright.cal 0 0\n"
      "skyfunc glow sky_glow 0 0 4 1 1 1 0\n"
      "sky_glow source sky 0 0 4 0 0 1 180\n");
  CHECK(content.polygons.empty());
  REQUIRE(content.notices.size() == 2);
  CHECK_THAT(content.notices[1], Contains("scene.rad:3") && Contains("source"));
}

TEST_CASE("bad scene input is an error naming file and line") {
  CHECK_THROWS_WITH(read("void polygon a 0 0 9 0 0 0 1 0 0 1 x 0\n"), Contains("scene.rad:1") && Contains("'x'"));
  CHECK_THROWS_WITH(read("\nvoid polygon a 0 0 6 0 0 0 1 0 0\n"), Contains("scene.rad:2") && Contains("at least 3"));
  CHECK_THROWS_WITH(read("void polygon a 0 0 9 0 0 0 1 0 0 nan 1 0\n"), Contains("scene.rad:1") && Contains("nan"));
  CHECK_THROWS_WITH(read("void polygon a 0 0 9 0 0 0 1 0 0 1e999 1 0\n"), Contains("out of range"));
  CHECK_THROWS_WITH(read("void polygon a 0 0 8 0 0 0 1 0 0 1 1\n"), Contains("multiple of 3"));
  CHECK_THROWS_WITH(read("void polygon a 0 0 9 0 0 0 1 0 0 2 0 0\n"), Contains("zero area"));
  CHECK_THROWS_WITH(read("void polygon a 0 0 12 0 0 0 1 0 0 1 1 0.5 0 1 0\n"), Contains("not planar"));
  CHECK_THROWS_WITH(read("void polygon a 0 0 9 0 0 0 1 0 0\n"), Contains("scene.rad:1") && Contains("end of file"));
  CHECK_THROWS_WITH(read("!gensky 3 21 12\n"), Contains("scene.rad:1") && Contains("gensky"));
  CHECK_THROWS_WITH(read("\n\nvoid instance tree 1 tree.oct 0 0\n"), Contains("scene.rad:3") && Contains("instance"));
  CHECK_THROWS_WITH(read("\n\nvoid sphere ball 0 0 3 0 0 0\n"), Contains("scene.rad:3") && Contains("sphere") && Contains("takes 4"));
  CHECK_THROWS_WITH(read("void sphere ball 0 0 4 0 0 0 0\n"), Contains("radius must be positive"));
  CHECK_THROWS_WITH(read("void ring r 0 0 8 0 0 0 0 0 0 0 1\n"), Contains("normal is zero"));
  CHECK_THROWS_WITH(read("void ring r 0 0 8 0 0 0 0 0 1 2 1\n"), Contains("inner < outer"));
  CHECK_THROWS_WITH(read("void cylinder c 0 0 7 1 1 1 1 1 1 0.5\n"), Contains("ends coincide"));
  CHECK_THROWS_WITH(read("void cone c 0 0 8 0 0 0 0 0 1 0 0\n"), Contains("not both zero"));
  CHECK_THROWS_WITH(read("paint polygon a 0 0 9 0 0 0 1 0 0 1 1 0\n"), Contains("undefined modifier 'paint'"));
  CHECK_THROWS_WITH(read("void polygon a -1 0 9 0 0 0 1 0 0 1 1 0\n"), Contains("non-negative integer"));
  CHECK_THROWS_WITH(read("void plastic p 0 0 3 0.5 0.5 0.5\n"), Contains("wrong for its type"));
  RadContent sink;
  CHECK_THROWS_WITH(read_rad_file("/nonexistent/scene.rad", false, sink), Contains("/nonexistent/scene.rad") && Contains("cannot open"));
}

TEST_CASE("opaque materials in aperture files are occluders, with one notice") {
  // Honeybee writes doors into the aperture folder: they block, as in Radiance, and the run goes on.
  const std::string text = "void plastic door_mat 0 0 5 .5 .5 .5 0 0\ndoor_mat polygon door 0 0 9 0 0 0 1 0 0 1 1 0\n"
                           "door_mat polygon door2 0 0 9 0 0 1 1 0 1 1 1 1\nvoid polygon w 0 0 9 0 0 0 1 0 0 1 1 0\n";
  const Scene scene = assemble_scene(read(text, true));
  CHECK(scene.occluders.size() == 2);
  REQUIRE(scene.apertures.size() == 1);
  CHECK(scene.apertures[0].transmittance == 1);  // void stays an opening in aperture files
  REQUIRE(scene.notices.size() == 1);
  CHECK_THAT(scene.notices[0], Contains("scene.rad:2") && Contains("2 polygons") && Contains("'door' first") &&
                                   Contains("occluders"));
}

TEST_CASE("void polygons in scene files are nothing, light, glow and illum polygons are left out") {
  const std::string text =
      "void plastic black 0 0 5 0 0 0 0 0\nvoid light lamp 0 0 3 10 10 10\nvoid glow window_glow 0 0 4 1 1 1 0\n"
      "void illum ill 0 0 3 1 1 1\n"
      "void polygon ghost 0 0 9 0 0 2 1 0 2 1 1 2\n"           // line 5
      "lamp polygon l 0 0 9 0 0 3 1 0 3 1 1 3\n"               // line 6
      "window_glow polygon g 0 0 9 0 0 4 1 0 4 1 1 4\n"
      "ill polygon i 0 0 9 0 0 5 1 0 5 1 1 5\n"
      "black polygon wall 0 0 9 0 0 6 1 0 6 1 1 6\n";
  const Scene scene = assemble_scene(read(text));
  REQUIRE(scene.occluders.size() == 1);
  CHECK(scene.occluders[0].name == "wall");
  CHECK(scene.apertures.empty());
  REQUIRE(scene.notices.size() == 2);
  CHECK_THAT(scene.notices[0], Contains("scene.rad:5") && Contains("1 void polygon ") && Contains("does not exist"));
  CHECK_THAT(scene.notices[1], Contains("scene.rad:6") && Contains("3 light, glow or illum polygons"));
}

TEST_CASE("BSDF apertures take a stated uniform transmittance, or are an error saying how to give it") {
  const std::string text =
      "void BSDF shade_state 6 0.0 bsdf/shade.xml 0 0 1 . 0 0\nshade_state polygon w 0 0 9 0 0 0 1 0 0 1 1 0\n";
  CHECK_THROWS_WITH(assemble_scene(read(text, true)),
                    Contains("scene.rad:2") && Contains("bsdf/shade.xml") && Contains("--bsdf-transmittance"));
  const Scene scene = assemble_scene(read(text, true), SceneOptions{0.25});
  REQUIRE(scene.apertures.size() == 1);
  CHECK(scene.apertures[0].transmittance == 0.25);
  CHECK(scene.apertures[0].angular_transmittance.empty());
  // In a scene file it blocks, said so.
  const Scene in_scene = assemble_scene(read(text, false));
  CHECK(in_scene.occluders.size() == 1);
  CHECK_THAT(in_scene.notices.at(0), Contains("left out"));
}

TEST_CASE("glass known to lie between two rooms is a pane counted as interior, once per pair, other glass is an aperture") {
  RadContent content = read("void glass g 0 0 3 .9 .9 .9\ng polygon a 0 0 9 0 0 0 1 0 0 1 1 0\n"
                            "g polygon b 0 0 9 0 0 1 1 0 1 1 1 1\ng polygon b2 0 0 9 1 1 1 1 0 1 0 0 1\n");
  content.polygons[1].interior = true;
  content.polygons[2].interior = true;  // b again, from the adjacent room, its vertices reversed
  const Scene scene = assemble_scene(content);
  REQUIRE(scene.apertures.size() == 2);
  CHECK(scene.apertures[1].polygon.name == "b");
  CHECK(scene.interior_apertures == 1);
  CHECK(scene.occluders.empty());
  bool pane = false, copy = false;
  for (const auto& n : scene.notices) {
    pane |= n.find("scene.rad:3") != std::string::npos && n.find("between two rooms") != std::string::npos;
    copy |= n.find("scene.rad:4") != std::string::npos && n.find("adjacent room's copy") != std::string::npos;
  }
  CHECK(pane);
  CHECK(copy);
}

TEST_CASE("sensor grids are read, and bad grids are errors naming file and line") {
  const auto grid = parse_sensor_grid("0 0 0.85 0 0 1\n\n# comment\n1 2 3 0 0 2\n", "room.pts");
  REQUIRE(grid.sensors.size() == 2);
  CHECK(grid.name == "room");
  CHECK(grid.sensors[1].normal.z == 1);
  CHECK_THROWS_WITH(parse_sensor_grid("0 0 0.85 0 0 1\n0 0 x 0 0 1\n", "g.pts"), Contains("g.pts:2") && Contains("'x'"));
  CHECK_THROWS_WITH(parse_sensor_grid("0 0 0.85 0 0\n", "g.pts"), Contains("g.pts:1") && Contains("6 numbers"));
  CHECK_THROWS_WITH(parse_sensor_grid("0 0 0.85 0 0 1 7\n", "g.pts"), Contains("more than 6"));
  CHECK_THROWS_WITH(parse_sensor_grid("0 0 0.85 0 0 0\n", "g.pts"), Contains("g.pts:1") && Contains("zero"));
  CHECK_THROWS_WITH(parse_sensor_grid("0 nan 0.85 0 0 1\n", "g.pts"), Contains("g.pts:1"));
  CHECK_THROWS_WITH(parse_sensor_grid("\n# only a comment\n", "g.pts"), Contains("g.pts") && Contains("empty"));
  CHECK_THROWS_WITH(read_sensor_grid("/nonexistent/g.pts"), Contains("cannot open"));
}

TEST_CASE("quoted words run to the matching quote, white space and '#' included, as Radiance reads them") {
  const auto content = read(
      "void plastic \"porsche #1\" 0 0 5 0.5 0.5 0.5 0 0\n"
      "'porsche #1' polygon 'left\n door' 0 0 9 0 0 0 1 0 0 1 1 0\n");
  REQUIRE(content.materials.count("porsche #1") == 1);
  REQUIRE(content.polygons.size() == 1);
  CHECK(content.polygons[0].polygon.material == "porsche #1");
  CHECK(content.polygons[0].polygon.name == "left\n door");
  CHECK(content.polygons[0].polygon.where.line == 2);
  CHECK_THROWS_WITH(read("void plastic \"open 0 0 5 0.5 0.5 0.5 0 0\n"), Contains("scene.rad:1") && Contains("closing \""));
  CHECK_THROWS_WITH(read("void plastic '' 0 0 5 0.5 0.5 0.5 0 0\n"), Contains("scene.rad:1") && Contains("empty quoted"));
}

TEST_CASE("a file that is not a scene description is named for what it is") {
  CHECK_THROWS_WITH(read("#?RADIANCE\noconv scene.rad\nFORMAT=Radiance_octree\n\n"), Contains("scene.rad:1") && Contains("octree"));
  CHECK_THROWS_WITH(read("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 2\n"), Contains("picture"));
  CHECK_THROWS_WITH(read("# exported\nmtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), Contains("Wavefront OBJ") && Contains("give it with --model"));
  std::string binary(256, '\0');
  for (std::size_t i = 0; i < binary.size(); ++i) binary[i] = char((i * 37) % 32);
  CHECK_THROWS_WITH(read(binary), Contains("scene.rad:1") && Contains("binary"));
}

TEST_CASE("a command line names the program to run first, and a sky generator is to be left out") {
  CHECK_THROWS_WITH(read("\n!xform -n chair -t 1 0 0 chair.rad\n"),
                    Contains("scene.rad:2") && Contains("'xform'") && Contains("chair.rad > out.rad"));
  CHECK_THROWS_WITH(read("! gensky 6 21 12 +s\n"), Contains("generates a sky") && Contains("--sky"));
}

TEST_CASE("a mesh is read from the OBJ it was made from, transformed as xform transforms, without that OBJ it is an error saying so") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("daylit_mesh_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // A unit square in the plane z = 0, facing +z, whose material the scene defines.
  write_file(dir / "square.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl white\nf 1 2 3 4\n");
  write_file(dir / "loose.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");  // no usemtl
  write_file(dir / "nowhere.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl nowhere\nf 1 2 3\n");
  const std::string scene_path = (dir / "scene.rad").string();
  const auto read_scene = [&](const std::string& text) {
    RadContent content;
    read_rad_text(text, scene_path, false, content);
    return content;
  };
  const std::string white = "void plastic white 0 0 5 .5 .5 .5 0 0\nvoid plastic grey 0 0 5 .2 .2 .2 0 0\n";
  const RadContent c = read_scene(white +
                                  "void mesh as_is 1 square.rtm 0 0\n"                 // the face's own usemtl
                                  "grey mesh turned 7 square.rtm -rz 90 -t 1 2 3 0 0\n"  // the mesh's modifier
                                  "void mesh mirrored 2 square.rtm -mx 0 0\n");
  REQUIRE(c.polygons.size() == 3);
  const Polygon& a = c.polygons[0].polygon;
  CHECK(a.name == "as_is.0");
  CHECK(a.material == "white");
  CHECK_THAT(a.where.str(), Contains("square.obj:6"));
  CHECK(a.vertices == std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  // -rz 90 maps (x, y, z) to (−y, x, z) exactly, then -t moves it by (1, 2, 3).
  const Polygon& b = c.polygons[1].polygon;
  CHECK(b.material == "grey");
  CHECK(b.vertices == std::vector<Vec3>{{1, 2, 3}, {1, 3, 3}, {0, 3, 3}, {0, 2, 3}});
  // A mirror reverses the vertex order, so the face still faces +z, as xform keeps it.
  const Polygon& m = c.polygons[2].polygon;
  CHECK(m.vertices == std::vector<Vec3>{{0, 1, 0}, {-1, 1, 0}, {-1, 0, 0}, {0, 0, 0}});
  CHECK(newell_normal(m.vertices).z > 0);
  CHECK(std::any_of(c.notices.begin(), c.notices.end(), [](const std::string& n) {
    return n.find("mesh 'turned'") != std::string::npos && n.find("square.obj: 1 face, transformed") != std::string::npos;
  }));

  CHECK_THROWS_WITH(read_scene(white + "void mesh gone 1 missing.rtm 0 0\n"),
                    Contains("scene.rad:3") && Contains("missing.obj") && Contains("obj2mesh"));
  CHECK_THROWS_WITH(read_scene(white + "void mesh copies 3 square.rtm -a 2 0 0\n"),
                    Contains("scene.rad:3") && Contains("-a") && Contains("arrays of copies"));
  CHECK_THROWS_WITH(read_scene(white + "void mesh bad 3 square.rtm -s 0 0 0\n"), Contains("scale must be positive"));
  CHECK_THROWS_WITH(read_scene(white + "void mesh bad 3 square.rtm -rx ninety 0 0\n"), Contains("expected a number for transform option -rx, found 'ninety'"));
  CHECK_THROWS_WITH(read_scene(white + "void mesh loose 1 loose.rtm 0 0\n"),
                    Contains("loose.obj:4") && Contains("no usemtl"));
  CHECK(read_scene(white + "grey mesh loose 1 loose.rtm 0 0\n").polygons.at(0).polygon.material == "grey");
  CHECK_THROWS_WITH(read_scene(white + "void mesh named 1 nowhere.obj 0 0\n"),
                    Contains("nowhere.obj:5") && Contains("'nowhere'") && Contains("names no modifier"));
  fs::remove_all(dir);
}
