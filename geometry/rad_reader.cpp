#include "geometry/rad_reader.hpp"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

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
const std::set<std::string, std::less<>> kMaterialTypes = {"plastic", "metal", "trans", "glass",
                                                           "mirror",  "glow",  "light"};
// Patterns and sources that make up a Radiance sky: skipped with a notice.
const std::set<std::string, std::less<>> kSkyTypes = {"source", "brightfunc", "colorfunc"};

// Expected number of real arguments for each material type (glass takes 3 or 4).
bool material_arity_ok(const std::string& type, std::size_t n) {
  if (type == "plastic" || type == "metal") return n == 5;
  if (type == "trans") return n == 7;
  if (type == "glass") return n == 3 || n == 4;
  if (type == "mirror" || type == "light") return n == 3;
  if (type == "glow") return n == 4;
  return true;
}

void check_polygon(const Polygon& poly) {
  const auto& v = poly.vertices;
  const Vec3 normal = newell_normal(v);
  double extent = 0;
  for (const Vec3& p : v) extent = std::max(extent, norm(p - v[0]));
  const double area2 = norm(normal);
  if (!(area2 > 0) || area2 <= 1e-24 * extent * extent)
    throw input_error(poly.where, "polygon '" + poly.name + "' has zero area (collinear or repeated vertices)");
  const Vec3 unit = normal / area2;
  double deviation = 0;
  Vec3 centroid;
  for (const Vec3& p : v) centroid += p - v[0];
  centroid = centroid / double(v.size());
  for (const Vec3& p : v) deviation = std::max(deviation, std::abs(dot(unit, p - v[0] - centroid)));
  if (deviation > kPlanarityTolerance * extent) {
    std::ostringstream msg;
    msg << "polygon '" << poly.name << "' is not planar: a vertex lies " << deviation
        << " from its mean plane, more than " << kPlanarityTolerance << " of its extent " << extent;
    throw input_error(poly.where, msg.str());
  }
}

}  // namespace

void read_rad_text(const std::string& text, const std::string& name, bool aperture_file,
                   RadContent& content) {
  TextScanner scan(text, name);
  while (!scan.at_end()) {
    const int line = scan.peek_line();
    const SourceLocation where = scan.where(line);
    const Token modifier = scan.next();
    if (modifier.text.front() == '!')
      throw input_error(where, "commands ('" + std::string(modifier.text) + std::string(scan.rest_of_line()) +
                                   "') are not supported: run them first and pass their output as a file");
    const Token type_tok = scan.next();
    const Token id_tok = scan.next();
    if (type_tok.text.empty() || id_tok.text.empty())
      throw input_error(where, "unexpected end of file inside a primitive");
    const std::string type(type_tok.text);
    const std::string id(id_tok.text);

    if (type == "alias") {
      // "modifier alias new_id old_id": new_id names the same material as old_id.
      const Token target = scan.next();
      if (target.text.empty()) throw input_error(where, "alias '" + id + "' lacks the name it refers to");
      const auto it = content.materials.find(std::string(target.text));
      if (it == content.materials.end())
        throw input_error(where, "alias '" + id + "' refers to undefined material '" + std::string(target.text) + "'");
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
      if (t.text.empty()) throw input_error(where, "unexpected end of file in the string arguments of '" + id + "'");
      strings.emplace_back(t.text);
    }
    const long nint = parse_count(scan.next(), where, "the number of integer arguments");
    for (long i = 0; i < nint; ++i) {
      const Token t = scan.next();
      if (t.text.empty()) throw input_error(where, "unexpected end of file in the integer arguments of '" + id + "'");
    }
    const long nreal = parse_count(scan.next(), where, "the number of real arguments");
    std::vector<double> reals;
    reals.reserve(std::size_t(std::min<long>(nreal, 1 << 16)));
    for (long i = 0; i < nreal; ++i) {
      const Token t = scan.next();
      if (t.text.empty())
        throw input_error(where, "unexpected end of file in '" + id + "': " + std::to_string(nreal) +
                                     " real arguments announced, " + std::to_string(i) + " found");
      reals.push_back(parse_real(t, scan.where(t.line), "real argument " + std::to_string(i + 1) + " of '" + id + "'"));
    }

    const std::string modifier_name(modifier.text);
    if (modifier_name != "void" && !content.materials.count(modifier_name) &&
        !content.skipped_modifiers.count(modifier_name))
      throw input_error(where, "undefined modifier '" + modifier_name + "' for '" + id + "'");

    if (type == "polygon") {
      if (nreal % 3 != 0)
        throw input_error(where, "polygon '" + id + "' has " + std::to_string(nreal) +
                                     " real arguments, which is not a multiple of 3");
      if (nreal < 9)
        throw input_error(where, "polygon '" + id + "' has " + std::to_string(nreal / 3) +
                                     " vertices; a polygon needs at least 3");
      Polygon poly;
      poly.name = id;
      poly.material = std::string(modifier.text);
      poly.where = where;
      for (long i = 0; i < nreal; i += 3) {
        const Vec3 v{reals[i], reals[i + 1], reals[i + 2]};
        // Exactly repeated consecutive vertices carry no geometry; drop them here.
        if (poly.vertices.empty() || !(poly.vertices.back() == v)) poly.vertices.push_back(v);
      }
      while (poly.vertices.size() > 1 && poly.vertices.front() == poly.vertices.back()) poly.vertices.pop_back();
      if (poly.vertices.size() < 3)
        throw input_error(where, "polygon '" + id + "' has fewer than 3 distinct vertices");
      check_polygon(poly);
      content.polygons.push_back({std::move(poly), aperture_file});
    } else if (kMaterialTypes.count(type)) {
      if (!material_arity_ok(type, reals.size()))
        throw input_error(where, type + " material '" + id + "' has " + std::to_string(reals.size()) +
                                     " real arguments, which is wrong for its type");
      content.materials[id] = Material{id, type, std::move(strings), std::move(reals), where};
    } else if (kSkyTypes.count(type)) {
      content.skipped_modifiers.insert(id);
      content.notices.push_back(where.str() + ": skipped " + type + " '" + id +
                                "' (the sky comes from --sky, not from scene files)");
    } else {
      throw input_error(where, "unsupported primitive type '" + type + "' ('" + id +
                                   "'); daylit reads polygon geometry and the materials plastic, metal, "
                                   "trans, glass, mirror, glow, light");
    }
  }
}

void read_rad_file(const std::string& path, bool aperture_file, RadContent& content) {
  read_rad_text(read_text_file(path), path, aperture_file, content);
}

}  // namespace daylit
