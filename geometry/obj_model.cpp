#include "geometry/obj_model.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "geometry/input_checks.hpp"
#include "geometry/rad_reader.hpp"
#include "geometry/text_scanner.hpp"

namespace daylit {

namespace {

// ---------------------------------------------------------------------------------------------
// Statements: one logical line (a trailing `\` joins the next), its comment ('#' at the start of
// the line or after white space) cut, split into words at white space.

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

struct Statement {
  int line = 0;                         // where it starts
  std::string_view text;                // comment cut, trimmed
  std::vector<std::string_view> words;  // words[0]: the keyword
  // The text after the keyword, trimmed: names that may hold spaces (usemtl, o, newmtl, mtllib).
  std::string_view rest() const {
    return words.empty() ? std::string_view() : trim(text.substr(std::size_t(words[0].data() - text.data()) + words[0].size()));
  }
};

class StatementReader {
 public:
  explicit StatementReader(std::string_view text) : text_(text) {}

  // The next non-empty statement; false at the end.
  bool next(Statement& s) {
    while (pos_ < text_.size()) {
      s.line = line_;
      std::string_view line = take_line();
      if (!line.empty() && line.back() == '\\') {
        // Continued: copy the pieces into a buffer of their own (rare; the common case stays a view).
        joined_.assign(line.substr(0, line.size() - 1));
        while (pos_ < text_.size()) {
          std::string_view more = take_line();
          const bool again = !more.empty() && more.back() == '\\';
          joined_ += ' ';
          joined_.append(again ? more.substr(0, more.size() - 1) : more);
          if (!again) break;
        }
        line = joined_;
      }
      for (std::size_t i = 0; i < line.size(); ++i)
        if (line[i] == '#' && (i == 0 || is_blank(line[i - 1]))) {
          line = line.substr(0, i);
          break;
        }
      s.text = trim(line);
      if (s.text.empty()) continue;
      s.words.clear();
      std::size_t i = 0;
      while (i < s.text.size()) {
        while (i < s.text.size() && is_blank(s.text[i])) ++i;
        const std::size_t begin = i;
        while (i < s.text.size() && !is_blank(s.text[i])) ++i;
        if (i > begin) s.words.push_back(s.text.substr(begin, i - begin));
      }
      return true;
    }
    return false;
  }

 private:
  // One physical line without its end, trailing blanks cut (so that a `\` before them continues).
  std::string_view take_line() {
    const std::size_t end = std::min(text_.find('\n', pos_), text_.size());
    std::string_view line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_;
    while (!line.empty() && is_blank(line.back())) line.remove_suffix(1);
    return line;
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 1;
  std::string joined_;
};

// A file that is not text (a compiler's object file shares the extension .obj), told from its
// first bytes as the .rad reader tells binary files: mostly control characters.
bool looks_binary(std::string_view text) {
  const std::string_view head = text.substr(0, 4096);
  const auto control = std::count_if(head.begin(), head.end(), [](char c) {
    const auto u = static_cast<unsigned char>(c);
    return u == 0 || (u < 0x20 && u != '\t' && u != '\n' && u != '\r' && u != '\f' && u != '\v');
  });
  return control >= 16 && control * 20 > std::ptrdiff_t(head.size());
}

std::string plural(const char* what) {
  const std::string w = what;
  return w == "vertex" ? "vertices" : w + "s";
}

double number(std::string_view word, const SourceLocation& where, const std::string& what) {
  // Exports from programs set to a European locale write "0,5".
  if (word.find(',') != std::string_view::npos && word.find_first_not_of("+-.0123456789,eE") == std::string_view::npos)
    throw input_error(where, "expected a number for " + what + ", found " + printable(word) +
                                 " (a decimal comma: OBJ and .mtl numbers take a decimal point)");
  return parse_real(Token{word, where.line}, where, what);
}

// ---------------------------------------------------------------------------------------------
// The .obj reader.

const std::set<std::string, std::less<>> kIgnored = {
    // No geometry: smoothing and merging groups, level of detail, render attributes, and the
    // free-form settings that only curves and surfaces (refused below) use.
    "s", "mg", "lod", "bevel", "c_interp", "d_interp", "maplib", "usemap", "shadow_obj", "trace_obj", "ctech", "stech",
    "vp", "cstype", "deg", "bmat", "step", "parm", "trim", "hole", "scrv", "sp", "end", "con"};
const std::set<std::string, std::less<>> kSilentlyIgnored = {"s", "mg"};

class ObjReader {
 public:
  ObjReader(const std::string& name, const ObjOptions& options, const MtlLibraryReader& read_library)
      : name_(name), options_(options), read_library_(read_library) {
    if (!(options.metres_per_unit > 0) || !std::isfinite(options.metres_per_unit))
      throw Error(name + ": the scale (metres per unit) must be a positive number");
    // 1/s an integer k that s is the nearest double to 1/k of (0.001 → 1000): divide by k.
    const double k = std::round(1 / options.metres_per_unit);
    if (options.metres_per_unit < 1 && k <= 9007199254740992.0 && 1 / k == options.metres_per_unit) divisor_ = k;
    model_.path = name;
    model_.options = options;
    const std::string stem = std::filesystem::path(name).stem().string();
    stem_ = stem.empty() ? "face" : stem;
  }

  ObjModel read(std::string_view text) {
    if (looks_binary(text))
      throw input_error({name_, 1}, "this is a binary file, not a Wavefront OBJ model (text with v and f lines; a "
                                    "compiler's object file also ends in .obj)");
    StatementReader reader(text);
    Statement s;
    while (reader.next(s)) statement(s);
    finish();
    return std::move(model_);
  }

 private:
  SourceLocation at(const Statement& s) const { return {name_, s.line}; }

  void statement(const Statement& s) {
    const std::string_view key = s.words[0];
    const SourceLocation where = at(s);
    if (key == "v") {
      vertex(s, where);
    } else if (key == "vt" || key == "vn") {
      const std::size_t lo = key == "vt" ? 1 : 3, hi = 3;
      if (s.words.size() - 1 < lo || s.words.size() - 1 > hi)
        throw input_error(where, std::string(key) + " takes " + (key == "vt" ? "1 to 3 numbers" : "3 numbers") + ", found " +
                                     std::to_string(s.words.size() - 1));
      for (std::size_t i = 1; i < s.words.size(); ++i)
        number(s.words[i], where, std::string(key == "vt" ? "a texture coordinate" : "a normal's component"));
      (key == "vt" ? texcoords_ : normals_) += 1;
    } else if (key == "f") {
      face(s, where);
    } else if (key == "l" || key == "p") {
      if (lines_and_points_++ == 0) first_line_or_point_ = where;
    } else if (key == "g") {
      groups_.assign(s.words.begin() + 1, s.words.end());
      if (groups_.empty()) groups_ = {"default"};
    } else if (key == "o") {
      object_ = std::string(s.rest());
    } else if (key == "usemtl") {
      if (s.rest().empty()) throw input_error(where, "usemtl without a material name");
      material_ = std::string(s.rest());
    } else if (key == "mtllib") {
      library(s, where);
    } else if (key == "curv" || key == "curv2" || key == "surf") {
      throw input_error(where, "free-form geometry (" + std::string(key) + ") is not read: export the model as "
                               "polygons (triangles or quads)");
    } else if (key == "call" || key == "csh") {
      throw input_error(where, std::string(key) == "call"
                                   ? "call (reading another .obj into this one) is not followed: merge the files"
                                   : "daylit does not run commands (csh): leave this line out");
    } else if (kIgnored.count(key)) {
      if (!kSilentlyIgnored.count(key) && ignored_++ == 0) first_ignored_ = where;
    } else {
      throw input_error(where, "unknown OBJ statement " + printable(key) +
                                   "; daylit reads v, vt, vn, f, g, o, usemtl and mtllib (and skips l, p, s and "
                                   "render settings)");
    }
  }

  void vertex(const Statement& s, const SourceLocation& where) {
    // x y z, then an optional weight w or an r g b colour (an extension many exporters write).
    const std::size_t n = s.words.size() - 1;
    if (n < 3 || n > 7)
      throw input_error(where, "a vertex (v) takes x y z, optionally followed by w or r g b; found " + std::to_string(n) +
                                   " number" + (n == 1 ? "" : "s"));
    static const char* const kAxis[3] = {"x", "y", "z"};
    const std::string index = std::to_string(positions_.size() + 1);
    double c[3];
    for (std::size_t i = 1; i <= n; ++i) {
      const double x = number(s.words[i], where,
                              i <= 3 ? "the " + std::string(kAxis[i - 1]) + " coordinate of vertex " + index
                                     : "value " + std::to_string(i) + " of vertex " + index);
      if (i <= 3) c[i - 1] = divisor_ > 0 ? x / divisor_ : x * options_.metres_per_unit;
    }
    const Vec3 p = options_.up == ObjUpAxis::y ? Vec3{c[0], -c[2], c[1]} : Vec3{c[0], c[1], c[2]};
    for (int i = 0; i < 3; ++i)
      if (!(std::abs(p[i]) <= kMaxCoordinate))
        throw input_error(where, "vertex " + index + " lies beyond 1e12 in magnitude (in metres): move the model's "
                                 "origin nearer, or check --obj-scale");
    positions_.push_back(p);
  }

  // One index of a face's vertex reference: from 1, or negative counting back from the last of
  // the `count` defined so far.
  long index(std::string_view word, long count, const char* what, const SourceLocation& where) const {
    long i = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), i);
    if (word.empty() || ec != std::errc() || end != word.data() + word.size())
      throw input_error(where, std::string("expected an integer ") + what + " index, found " + printable(word));
    if (i == 0)
      throw input_error(where, std::string(what) + " index 0: OBJ indices start at 1 (negative ones count back from the "
                               "last defined)");
    const long resolved = i > 0 ? i - 1 : count + i;
    if (resolved < 0 || resolved >= count)
      throw input_error(where, std::string(what) + " index " + std::string(word) + " is out of range: " +
                                   std::to_string(count) + " " + (count == 1 ? std::string(what) + " is" : plural(what) + " are") +
                                   " defined before this line");
    return resolved;
  }

  void face(const Statement& s, const SourceLocation& where) {
    ++face_number_;
    std::vector<Vec3> v;
    for (std::size_t k = 1; k < s.words.size(); ++k) {
      // v, v/vt, v//vn or v/vt/vn.
      const std::string_view w = s.words[k];
      const std::size_t a = w.find('/');
      const std::size_t b = a == std::string_view::npos ? a : w.find('/', a + 1);
      if (b != std::string_view::npos && w.find('/', b + 1) != std::string_view::npos)
        throw input_error(where, "vertex reference " + printable(w) + " has more than three parts (v/vt/vn)");
      const long iv = index(w.substr(0, a), long(positions_.size()), "vertex", where);
      if (a != std::string_view::npos) {
        const std::string_view vt = w.substr(a + 1, b == std::string_view::npos ? std::string_view::npos : b - a - 1);
        if (!vt.empty()) index(vt, texcoords_, "texture coordinate", where);
        else if (b == std::string_view::npos)
          throw input_error(where, "vertex reference " + printable(w) + " ends in '/' (forms: v, v/vt, v//vn, v/vt/vn)");
        if (b != std::string_view::npos) index(w.substr(b + 1), normals_, "normal", where);
      }
      v.push_back(positions_[std::size_t(iv)]);
    }
    // Repeated consecutive vertices (and a last repeating the first) carry no geometry.
    std::vector<Vec3> distinct;
    for (const Vec3& p : v)
      if (distinct.empty() || !(distinct.back() == p)) distinct.push_back(p);
    while (distinct.size() > 1 && distinct.front() == distinct.back()) distinct.pop_back();
    if (distinct.size() < 3) return skip_degenerate(where);
    const PolygonShape shape = polygon_shape(distinct);
    if (shape.zero_area) return skip_degenerate(where);
    const std::string label = face_label();
    if (!(shape.deviation > kPlanarityTolerance * shape.extent)) return add(std::move(distinct), label, where);
    if (distinct.size() != 4) {
      std::ostringstream msg;
      msg << "face " << printable(label) << " is not planar: a vertex lies " << shape.deviation
          << " from its mean plane, more than " << kPlanarityTolerance << " of its extent " << shape.extent
          << "; daylit splits warped quads only: export this face as triangles";
      throw input_error(where, msg.str());
    }
    split_quad(distinct, shape.normal, label, where);
  }

  // The two triangles of a warped quad: along the diagonal whose triangles both face the quad's
  // way (Newell's normal), the shorter diagonal if both do (tinyobjloader's choice, the more
  // compact triangles); a quad that neither keeps (a bow tie) crosses itself.
  void split_quad(const std::vector<Vec3>& q, const Vec3& normal, const std::string& label, const SourceLocation& where) {
    const auto faces_along = [&](const Vec3& a, const Vec3& b, const Vec3& c) { return dot(cross(b - a, c - a), normal) > 0; };
    const bool along02 = faces_along(q[0], q[1], q[2]) && faces_along(q[0], q[2], q[3]);
    const bool along13 = faces_along(q[0], q[1], q[3]) && faces_along(q[1], q[2], q[3]);
    if (!along02 && !along13)
      throw input_error(where, "face " + printable(label) + " (a warped quad) crosses itself");
    const bool use02 = along02 && (!along13 || norm(q[2] - q[0]) <= norm(q[3] - q[1]));
    if (model_.split_quads++ == 0) first_split_ = where;
    if (use02) {
      add_piece({q[0], q[1], q[2]}, label + "a", where);
      add_piece({q[0], q[2], q[3]}, label + "b", where);
    } else {
      add_piece({q[0], q[1], q[3]}, label + "a", where);
      add_piece({q[1], q[2], q[3]}, label + "b", where);
    }
  }

  void add_piece(std::vector<Vec3> triangle, const std::string& label, const SourceLocation& where) {
    if (polygon_shape(triangle).zero_area) return skip_degenerate(where);
    add(std::move(triangle), label, where);
  }

  void add(std::vector<Vec3> vertices, const std::string& label, const SourceLocation& where) {
    ObjFace f;
    f.polygon.vertices = std::move(vertices);
    f.polygon.name = label;
    f.polygon.material = material_;
    f.polygon.where = where;
    f.groups = groups_;
    f.object = object_;
    model_.faces.push_back(std::move(f));
  }

  void skip_degenerate(const SourceLocation& where) {
    if (model_.skipped_degenerate++ == 0) first_degenerate_ = where;
  }

  // Faces are named by their group (else object, else file), and their number in the file.
  std::string face_label() const {
    const std::string& base = groups_.front() != "default" ? groups_.front() : !object_.empty() ? object_ : stem_;
    return base + "#" + std::to_string(face_number_);
  }

  void library(const Statement& s, const SourceLocation& where) {
    const std::string_view rest = s.rest();
    if (rest.empty()) throw input_error(where, "mtllib without a file name");
    // A name with spaces is taken whole when such a file exists (exporters write it so);
    // otherwise the words are several libraries, as the format says.
    if (s.words.size() > 2 && !libraries_.count(std::string(rest))) {
      if (const auto found = read_library_(std::string(rest))) {
        load(std::string(rest), *found, where);
        return;
      }
    }
    for (std::size_t i = 1; i < s.words.size(); ++i) {
      const std::string n(s.words[i]);
      if (libraries_.count(n)) continue;
      if (const auto found = read_library_(n)) load(n, *found, where);
      else model_.missing_libraries.push_back({n, n, where});
      libraries_.insert(n);
    }
  }

  void load(const std::string& name, const std::pair<std::string, std::string>& found, const SourceLocation&) {
    libraries_.insert(name);
    parse_mtl(found.second, found.first, model_.materials, model_.notices);
    model_.mtl_files.push_back(found.first);
  }

  void finish() {
    model_.vertices = long(positions_.size());
    if (model_.skipped_degenerate)
      model_.notices.push_back(first_degenerate_.str() + ": skipped " + std::to_string(model_.skipped_degenerate) + " face" +
                               (model_.skipped_degenerate > 1 ? "s" : "") +
                               " with fewer than 3 distinct vertices or zero area (this one first)");
    if (model_.split_quads) {
      std::ostringstream msg;
      msg << first_split_.str() << ": split " << model_.split_quads << " warped quad" << (model_.split_quads > 1 ? "s" : "")
          << " (a vertex beyond " << kPlanarityTolerance << " of its extent from the mean plane) into two triangles each"
          << " (this one first)";
      model_.notices.push_back(msg.str());
    }
    if (lines_and_points_)
      model_.notices.push_back(first_line_or_point_.str() + ": skipped " + std::to_string(lines_and_points_) +
                               " line and point elements (l, p): they have no area (this one first)");
    if (ignored_)
      model_.notices.push_back(first_ignored_.str() + ": skipped " + std::to_string(ignored_) +
                               " statements that carry no polygon geometry (render settings, free-form "
                               "parameters; this one first)");
  }

  std::string name_, stem_;
  ObjOptions options_;
  const MtlLibraryReader& read_library_;
  double divisor_ = 0;
  ObjModel model_;
  std::vector<Vec3> positions_;
  long texcoords_ = 0, normals_ = 0, face_number_ = 0, lines_and_points_ = 0, ignored_ = 0;
  std::vector<std::string> groups_{"default"};
  std::string object_, material_;
  std::set<std::string> libraries_;
  SourceLocation first_degenerate_, first_split_, first_line_or_point_, first_ignored_;
};

// ---------------------------------------------------------------------------------------------
// The .mtl reader.

// Kd, Ks, Ke, Tf (or Kt): r [g b] (g and b default to r, as the format says). The spectral and
// CIE XYZ forms are refused.
std::array<double, 3> colour(const Statement& s, const SourceLocation& where, bool fraction) {
  const std::string key(s.words[0]);
  if (s.words.size() > 1 && (s.words[1] == "spectral" || s.words[1] == "xyz"))
    throw input_error(where, key + " " + std::string(s.words[1]) + ": spectral and CIE XYZ colours are not read; give " +
                                 key + " as r g b");
  if (s.words.size() != 2 && s.words.size() != 4)
    throw input_error(where, key + " takes r g b (or one grey value), found " + std::to_string(s.words.size() - 1) +
                                 " values");
  std::array<double, 3> c;
  static const char* const kChannel[3] = {"red", "green", "blue"};
  for (int i = 0; i < 3; ++i) {
    const std::size_t w = s.words.size() == 2 ? 1 : std::size_t(i + 1);
    c[i] = number(s.words[w], where, "the " + std::string(kChannel[i]) + " value of " + key);
    if (fraction && !(c[i] >= 0 && c[i] <= 1))
      throw input_error(where, key + " " + kChannel[i] + " value " + std::string(s.words[w]) + " is outside [0, 1]");
  }
  return c;
}

double fraction_value(const Statement& s, std::size_t word, const SourceLocation& where) {
  const std::string key(s.words[0]);
  if (s.words.size() != word + 1) throw input_error(where, key + " takes one number");
  const double x = number(s.words[word], where, "the value of " + key);
  if (!(x >= 0 && x <= 1)) throw input_error(where, key + " " + std::string(s.words[word]) + " is outside [0, 1]");
  return x;
}

}  // namespace

void parse_mtl(const std::string& text, const std::string& name, std::map<std::string, MtlMaterial>& materials,
               std::vector<std::string>& notices) {
  if (looks_binary(text)) throw input_error({name, 1}, "this is a binary file, not a material library (.mtl)");
  StatementReader reader(text);
  Statement s;
  MtlMaterial* m = nullptr;
  bool has_d = false;
  long unknown = 0;
  SourceLocation first_unknown;
  while (reader.next(s)) {
    const std::string key(s.words[0]);
    const SourceLocation where{name, s.line};
    if (key == "newmtl") {
      if (s.rest().empty()) throw input_error(where, "newmtl without a material name");
      const std::string id(s.rest());
      materials[id] = MtlMaterial{};
      m = &materials[id];
      m->name = id;
      m->where = where;
      has_d = false;
      continue;
    }
    static const std::set<std::string, std::less<>> kKnown = {"Kd", "Ks", "Ke", "Ka", "Tf", "Kt", "d", "Tr", "Ns", "Ni",
                                                              "illum", "sharpness"};
    if (!m && kKnown.count(key)) throw input_error(where, key + " before any newmtl: it belongs to no material");
    if (key == "Kd") {
      m->kd = colour(s, where, true);
    } else if (key == "Ks") {
      m->ks = colour(s, where, false);
    } else if (key == "Ke") {
      m->ke = colour(s, where, false);
    } else if (key == "Ka") {
      colour(s, where, false);  // checked, not used: ambient light is not daylight
    } else if (key == "Tf" || key == "Kt") {
      m->tf = colour(s, where, true);
      m->tf_where = where;
    } else if (key == "d") {
      // d [-halo] factor; the halo form (dissolve depending on the view) is read as its factor.
      const std::size_t w = s.words.size() > 1 && s.words[1] == "-halo" ? 2 : 1;
      m->dissolve = fraction_value(s, w, where);
      m->dissolve_where = where;
      has_d = true;
    } else if (key == "Tr") {
      // Transparency, 1 − d (not in the format's specification; exporters write it). d wins
      // where both are given, as in tinyobjloader.
      const double tr = fraction_value(s, 1, where);
      if (!has_d) {
        m->dissolve = 1 - tr;
        m->dissolve_where = where;
      }
    } else if (key == "Ns" || key == "Ni" || key == "sharpness") {
      if (s.words.size() != 2) throw input_error(where, key + " takes one number");
      const double x = number(s.words[1], where, "the value of " + key);
      if (key == "Ns") m->ns = x;
    } else if (key == "illum") {
      long model = -1;
      const std::string_view w = s.words.size() == 2 ? s.words[1] : std::string_view();
      const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), model);
      if (w.empty() || ec != std::errc() || end != w.data() + w.size() || model < 0 || model > 10)
        throw input_error(where, "illum takes an illumination model from 0 to 10, found " + printable(s.rest()));
      m->illum = int(model);
    } else if (key == "map_Kd") {
      if (m) m->texture = true;
    } else if (key == "map_d") {
      if (m) m->alpha_texture = true;
    } else if (key.rfind("map_", 0) == 0 || key == "bump" || key == "disp" || key == "decal" || key == "refl" ||
               key == "norm" || key == "Pr" || key == "Pm" || key == "Ps" || key == "Pc" || key == "Pcr" ||
               key == "aniso" || key == "anisor") {
      // Textures and the PBR extension: not what a diffuse surface needs.
    } else if (unknown++ == 0) {
      first_unknown = where;
    }
  }
  if (unknown)
    notices.push_back(first_unknown.str() + ": skipped " + std::to_string(unknown) + " statement" + (unknown > 1 ? "s" : "") +
                      " of " + name + " that daylit does not know (this one first)");
}

ObjModel parse_obj(const std::string& text, const std::string& name, const ObjOptions& options,
                   const MtlLibraryReader& read_library) {
  return ObjReader(name, options, read_library).read(text);
}

ObjModel read_obj_model(const std::string& path, const ObjOptions& options) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  const MtlLibraryReader read_library = [&](const std::string& lib) -> std::optional<std::pair<std::string, std::string>> {
    const std::string file = (folder / lib).string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
    return std::pair{file, read_text_file(file)};
  };
  ObjModel model = parse_obj(read_text_file(path), path, options, read_library);
  for (auto& missing : model.missing_libraries) missing.path = (folder / missing.name).string();
  return model;
}

bool is_obj_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".obj";
}

}  // namespace daylit
