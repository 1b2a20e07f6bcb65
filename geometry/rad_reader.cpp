#include "geometry/rad_reader.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <fstream>
#include <set>
#include <sstream>

#include "geometry/input_checks.hpp"
#include "geometry/obj_model.hpp"
#include "geometry/rad_tessellation.hpp"
#include "geometry/rad_transform.hpp"
#include "geometry/text_scanner.hpp"

namespace daylit {

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw Error(path + ": read error");
  return buffer.str();
}

namespace {

// Material types kept by type; their argument counts are checked where they are used.
// BSDF and aBSDF (Honeybee's dynamic aperture states and WINDOW's data) are kept with their
// strings (thickness, XML file, up vector, function file): scene_materials.cpp decides their role.
const std::set<std::string, std::less<>> kMaterialTypes = {"plastic", "metal", "trans", "glass", "mirror",
                                                           "glow",    "light", "illum", "BSDF",  "aBSDF"};
// Patterns and sources that make up a Radiance sky: skipped with a notice.
const std::set<std::string, std::less<>> kSkyTypes = {"source", "brightfunc", "colorfunc"};

// Expected number of real arguments for each material type (glass takes 3 or 4).
bool material_arity_ok(const std::string& type, std::size_t n) {
  if (type == "plastic" || type == "metal") return n == 5;
  if (type == "trans") return n == 7;
  if (type == "glass") return n == 3 || n == 4;
  if (type == "mirror" || type == "light" || type == "illum") return n == 3;
  if (type == "glow") return n == 4;
  return true;
}

// The reals of glass and trans enter the computation (an aperture's transmittance): they must be
// physical, or the daylight factors come out negative, above the sky's, or NaN. Transmissivities,
// reflectances and specularities are fractions; glass's refractive index lies in [1, 100] (at
// n → 0 or ∞ its surface reflectance rounds to 1 and the transmittance to 0/0). The reals of
// other materials are kept as read: occluders are black. Returns what is wrong, or "".
std::string material_range_problem(const std::string& type, const std::vector<double>& r) {
  const auto outside = [](double x, double lo, double hi) { return !(x >= lo && x <= hi); };
  const auto describe = [](const char* what, double x, const char* range) {
    std::ostringstream msg;
    msg << what << " " << x << " is outside " << range;
    return msg.str();
  };
  if (type == "glass") {
    for (int c = 0; c < 3; ++c)
      if (outside(r[c], 0, 1)) return describe("transmissivity", r[c], "[0, 1]");
    if (r.size() > 3 && outside(r[3], 1, 100)) return describe("refractive index", r[3], "[1, 100]");
  } else if (type == "trans") {
    static const char* const kNames[7] = {"red reflectance", "green reflectance", "blue reflectance", "specularity",
                                          "roughness", "transmissivity", "transmitted specularity"};
    for (int i = 0; i < 7; ++i)
      if (i != 4 && outside(r[i], 0, 1)) return describe(kNames[i], r[i], "[0, 1]");
  }
  return "";
}

// A `!command` line: daylit runs no commands. Say which program it is and what to do instead.
std::string command_message(std::string_view first, std::string_view rest) {
  const std::string command = std::string(first.substr(1)) + std::string(rest);  // without the '!'
  const std::size_t start = command.find_first_not_of(" \t");
  const std::string program =
      start == std::string::npos ? std::string() : command.substr(start, command.find_first_of(" \t", start) - start);
  if (program == "gensky" || program == "gendaylit" || program == "genskyvec")
    return "the command " + printable("!" + command, 80) + " generates a sky, which daylit does not read: the sky "
           "comes from --sky; leave this line out";
  return "daylit does not run commands (" + printable("!" + command, 80) + "): run " +
         (program.empty() ? std::string("it") : "the Radiance program " + printable(program)) +
         " yourself, its output to a file (" + printable(command.substr(start == std::string::npos ? 0 : start) + " > out.rad", 80) +
         "), and give daylit that file";
}

// What a file that is not a Radiance scene description is, when it can be told from its first
// bytes; empty otherwise. Octrees and pictures start with a Radiance header ("#?RADIANCE" and a
// FORMAT line); a Wavefront OBJ has vertex ("v x y z") and face ("f …") lines.
std::string foreign_file_kind(std::string_view text) {
  const std::string_view head = text.substr(0, 4096);
  if (head.substr(0, 10) == "#?RADIANCE") {
    if (head.find("FORMAT=Radiance_octree") != std::string_view::npos)
      return "a Radiance octree (the output of oconv): give daylit the .rad files it was made from";
    if (head.find("FORMAT=32-bit_rle_") != std::string_view::npos) return "a Radiance picture (HDR image), not a scene";
    return "a binary Radiance file (its header starts with #?RADIANCE), not a scene description";
  }
  bool vertex = false, face = false;
  std::size_t start = 0;
  for (int lines = 0; lines < 200 && start < head.size(); ++lines) {
    const std::size_t end = std::min(head.find('\n', start), head.size());
    const std::string_view line = head.substr(start, end - start);
    vertex |= line.substr(0, 2) == "v ";
    face |= line.substr(0, 2) == "f ";
    start = end + 1;
  }
  if (vertex && face)
    return "a Wavefront OBJ model ('v' and 'f' lines), not a Radiance scene: give it with --model (a name ending "
           "in .obj; its .mtl is read, --obj-materials maps materials and groups to openings and occluders, "
           "--obj-scale and --obj-up give its units and up axis)";
  // Mostly control bytes (not white space): a binary file. A few stray bytes in a text file are
  // left to the parser, which names their line.
  const auto control = std::count_if(head.begin(), head.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u < 0x20 && u != '\t' && u != '\n' && u != '\r' && u != '\f' && u != '\v';
  });
  if (control >= 16 && control * 20 > std::ptrdiff_t(head.size()))
    return "a binary file (" + std::to_string(control) + " of its first " + std::to_string(head.size()) +
           " bytes are control characters), not a scene description";
  return "";
}

}  // namespace

// Zero-area polygons are rejected (in a scene they are modelling slips, and they have no side to
// block light with); so are polygons warped beyond kPlanarityTolerance of their extent. Boundaries
// that cross themselves are found by the exact decomposition (convex_pieces), which knows seams.
void check_polygon(const Polygon& poly) {
  const PolygonShape shape = polygon_shape(poly.vertices);
  if (shape.zero_area)
    throw input_error(poly.where, "polygon " + printable(poly.name) +
                                      " has zero area (collinear or repeated vertices, or lobes that cancel)");
  if (shape.deviation > kPlanarityTolerance * shape.extent) {
    std::ostringstream msg;
    msg << "polygon " << printable(poly.name) << " is not planar: a vertex lies " << shape.deviation
        << " from its mean plane, more than " << kPlanarityTolerance << " of its extent " << shape.extent;
    throw input_error(poly.where, msg.str());
  }
}

void check_material(const Material& m) {
  if (!material_arity_ok(m.type, m.reals.size()))
    throw input_error(m.where, m.type + " material " + printable(m.name) + " has " + std::to_string(m.reals.size()) +
                                   " real arguments, which is wrong for its type");
  if (const std::string problem = material_range_problem(m.type, m.reals); !problem.empty())
    throw input_error(m.where, m.type + " material " + printable(m.name) + ": " + problem);
}

namespace {

// A `mesh` primitive ("modifier mesh id / 1+ file.rtm [transform] / 0 / 0") from the OBJ it was
// compiled from (obj2mesh): Radiance's .rtm is a binary octree of its own, which daylit does not
// read. The OBJ is the named file itself where that ends in .obj, else the same path with the
// extension .obj; a relative path is taken from the working directory, as Radiance does, or
// else from the folder of the file that names it. As in Radiance, a modifier other than void
// applies to every face; with void each face takes the modifier its `usemtl` names, which must
// be defined before the mesh (obj2mesh maps OBJ materials to the scene's modifiers).
void read_mesh(const std::string& modifier, const std::string& id, const std::vector<std::string>& strings,
               const std::string& name, const SourceLocation& where, bool aperture_file, RadContent& content) {
  namespace fs = std::filesystem;
  if (strings.empty()) throw input_error(where, "mesh " + printable(id) + " lacks its file name (1 string argument at least)");
  const RadTransform transform =
      parse_rad_transform(std::vector<std::string>(strings.begin() + 1, strings.end()), where);
  fs::path source(strings[0]);
  if (!is_obj_path(strings[0])) source.replace_extension(".obj");
  std::vector<fs::path> tried{source};
  if (source.is_relative()) tried.push_back(fs::path(name).parent_path() / source);
  std::string found;
  for (const fs::path& p : tried) {
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) {
      found = p.string();
      break;
    }
  }
  if (found.empty()) {
    std::string message = "mesh " + printable(id) + ": daylit reads a mesh from the OBJ file it was made from (obj2mesh), "
                          "not from Radiance's compiled " + printable(strings[0]) + "; no OBJ found at ";
    for (std::size_t i = 0; i < tried.size(); ++i) message += (i ? " or " : "") + printable(tried[i].string());
    throw input_error(where, message);
  }
  const ObjModel obj = read_obj_model(found);
  for (const std::string& notice : obj.notices) content.notices.push_back(notice);
  std::size_t faces = 0;
  for (const ObjFace& face : obj.faces) {
    Polygon poly = face.polygon;
    poly.name = id + "." + std::to_string(faces++);
    if (modifier != "void") {
      poly.material = modifier;
    } else if (poly.material.empty()) {
      throw input_error(poly.where, "this face has no usemtl, and mesh " + printable(id) + " (" + where.str() +
                                        ") has the modifier void: give the mesh a modifier, or the face a usemtl");
    } else if (poly.material != "void" && !content.materials.count(poly.material) &&
               !content.skipped_modifiers.count(poly.material)) {
      throw input_error(poly.where, "usemtl " + printable(poly.material) + " names no modifier defined before mesh " +
                                        printable(id) + " (" + where.str() + "); obj2mesh takes the OBJ's materials "
                                        "from the scene's modifiers");
    }
    for (Vec3& v : poly.vertices) v = transform.apply(v);
    if (transform.mirrors) std::reverse(poly.vertices.begin(), poly.vertices.end());
    check_polygon(poly);
    content.polygons.push_back({std::move(poly), aperture_file});
  }
  content.notices.push_back(where.str() + ": mesh " + printable(id) + " read from its OBJ source " + found + ": " +
                            std::to_string(faces) + (faces == 1 ? " face" : " faces") +
                            (strings.size() > 1 ? ", transformed" : ""));
}

}  // namespace

void read_rad_text(const std::string& text, const std::string& name, bool aperture_file,
                   RadContent& content) {
  if (const std::string kind = foreign_file_kind(text); !kind.empty()) throw input_error({name, 1}, "this is " + kind);
  TextScanner scan(text, name);
  // Polygons that had repeated consecutive vertices: counted, and reported once per file.
  long polygons_with_repeats = 0;
  SourceLocation first_with_repeats;
  struct CurvedTally {
    long count = 0;
    std::size_t facets = 0;
    double max_deviation = 0;
    int segments = 0;
    SourceLocation first;
  };
  std::map<std::string, CurvedTally> curved;  // by primitive type
  while (!scan.at_end()) {
    const int line = scan.peek_line();
    const SourceLocation where = scan.where(line);
    const Token modifier = scan.next();
    if (modifier.text.front() == '!') throw input_error(where, command_message(modifier.text, scan.rest_of_line()));
    const Token type_tok = scan.next();
    const Token id_tok = scan.next();
    if (type_tok.text.empty() || id_tok.text.empty())
      throw input_error(where, "unexpected end of file inside a primitive");
    const std::string type(type_tok.text);
    const std::string id(id_tok.text);

    if (type == "alias") {
      // "modifier alias new_id old_id": new_id names the same material as old_id.
      const Token target = scan.next();
      if (target.text.empty()) throw input_error(where, "alias " + printable(id) + " lacks the name it refers to");
      const auto it = content.materials.find(std::string(target.text));
      if (it == content.materials.end())
        throw input_error(where, "alias " + printable(id) + " refers to undefined material " + printable(target.text));
      Material m = it->second;
      m.name = id;
      m.where = where;
      content.materials[id] = m;
      continue;
    }

    std::vector<std::string> strings;
    const long nstr = parse_count(scan.next(), where, "the number of string arguments");
    for (long i = 0; i < nstr; ++i) {
      const Token t = scan.next();
      if (t.text.empty()) throw input_error(where, "unexpected end of file in the string arguments of " + printable(id));
      strings.emplace_back(t.text);
    }
    const long nint = parse_count(scan.next(), where, "the number of integer arguments");
    for (long i = 0; i < nint; ++i) {
      const Token t = scan.next();
      if (t.text.empty()) throw input_error(where, "unexpected end of file in the integer arguments of " + printable(id));
    }
    const long nreal = parse_count(scan.next(), where, "the number of real arguments");
    std::vector<double> reals;
    std::vector<int> real_lines;  // for messages about single coordinates
    reals.reserve(std::size_t(std::min<long>(nreal, 1 << 16)));
    for (long i = 0; i < nreal; ++i) {
      const Token t = scan.next();
      if (t.text.empty())
        throw input_error(where, "unexpected end of file in " + printable(id) + ": " + std::to_string(nreal) +
                                     " real arguments announced, " + std::to_string(i) + " found");
      reals.push_back(parse_real(t, scan.where(t.line), "real argument " + std::to_string(i + 1) + " of " + printable(id)));
      real_lines.push_back(t.line);
    }

    const std::string modifier_name(modifier.text);
    if (modifier_name != "void" && !content.materials.count(modifier_name) &&
        !content.skipped_modifiers.count(modifier_name))
      throw input_error(where, "undefined modifier " + printable(modifier_name) + " for " + printable(id));

    if (type == "polygon") {
      if (nreal % 3 != 0)
        throw input_error(where, "polygon " + printable(id) + " has " + std::to_string(nreal) +
                                     " real arguments, which is not a multiple of 3");
      if (nreal < 9)
        throw input_error(where, "polygon " + printable(id) + " has " + std::to_string(nreal / 3) +
                                     " vertices; a polygon needs at least 3");
      for (std::size_t i = 0; i < reals.size(); ++i)
        if (!(std::abs(reals[i]) <= kMaxCoordinate))
          throw input_error(scan.where(real_lines[i]), "vertex coordinate " + std::to_string(i + 1) + " of polygon " +
                                                           printable(id) + " is beyond 1e12 in magnitude: move the "
                                                           "model's origin nearer (or use larger units)");
      Polygon poly;
      poly.name = id;
      poly.material = std::string(modifier.text);
      poly.where = where;
      // Exactly repeated consecutive vertices (and a last vertex repeating the first) carry no
      // geometry and are common in exported models: they are dropped, with one notice per file.
      // Repeats that are not consecutive stay: they are the seams of holes, or a crossing that
      // convex_pieces reports.
      for (long i = 0; i < nreal; i += 3) {
        const Vec3 v{reals[i], reals[i + 1], reals[i + 2]};
        if (poly.vertices.empty() || !(poly.vertices.back() == v)) poly.vertices.push_back(v);
      }
      while (poly.vertices.size() > 1 && poly.vertices.front() == poly.vertices.back()) poly.vertices.pop_back();
      if (poly.vertices.size() < 3)
        throw input_error(where, "polygon " + printable(id) + " has fewer than 3 distinct vertices");
      if (long(poly.vertices.size()) != nreal / 3 && polygons_with_repeats++ == 0) first_with_repeats = where;
      check_polygon(poly);
      content.polygons.push_back({std::move(poly), aperture_file});
    } else if (kMaterialTypes.count(type)) {
      Material material{id, type, std::move(strings), std::move(reals), where};
      check_material(material);
      content.materials[id] = std::move(material);
    } else if (type == "mesh") {
      read_mesh(modifier_name, id, strings, name, where, aperture_file, content);
    } else if (is_curved_primitive(type)) {
      const Tessellation t = tessellate_primitive(type, id, std::string(modifier.text), reals, where);
      for (const Polygon& facet : t.facets) {
        check_polygon(facet);
        content.polygons.push_back({facet, aperture_file});
      }
      auto& tally = curved[type];
      if (tally.count++ == 0) tally.first = where;
      tally.facets += t.facets.size();
      tally.max_deviation = std::max(tally.max_deviation, t.max_deviation);
      tally.segments = t.segments;
    } else if (kSkyTypes.count(type)) {
      content.skipped_modifiers.insert(id);
      content.notices.push_back(where.str() + ": skipped " + type + " " + printable(id) +
                                " (the sky comes from --sky, not from scene files)");
    } else {
      throw input_error(where, "unsupported primitive type " + printable(type) + " (" + printable(id) +
                                   "); daylit reads the geometry polygon, sphere, ring, cylinder, tube, cone, cup and mesh (from its OBJ) "
                                   "and the materials plastic, metal, trans, glass, mirror, glow, light, illum, BSDF, aBSDF");
    }
  }
  for (const auto& [type, tally] : curved) {
    char deviation[64];
    std::snprintf(deviation, sizeof deviation, "%.3g", tally.max_deviation);
    content.notices.push_back(tally.first.str() + ": " + std::to_string(tally.count) + " " + type + (tally.count > 1 ? "s" : "") +
                              " of " + name + " (this one first) tessellated into " + std::to_string(tally.facets) +
                              " planar facets inscribed in the surface, " + std::to_string(tally.segments) +
                              " segments around each circle: every facet within " + deviation +
                              " model units of the true surface (1 % of the radius)");
  }
  if (polygons_with_repeats > 0)
    content.notices.push_back(first_with_repeats.str() + ": dropped repeated consecutive vertices from " +
                              std::to_string(polygons_with_repeats) + " polygon" + (polygons_with_repeats > 1 ? "s" : "") +
                              " of " + name + " (this one first)");
}

void read_rad_file(const std::string& path, bool aperture_file, RadContent& content) {
  read_rad_text(read_text_file(path), path, aperture_file, content);
}

}  // namespace daylit
