#include "geometry/rad_transform.hpp"

#include <cmath>
#include <numbers>

#include "geometry/text_scanner.hpp"

namespace daylit {

namespace {

double number(const std::vector<std::string>& args, std::size_t i, const std::string& option, const SourceLocation& where) {
  if (i >= args.size()) throw input_error(where, "transform option " + option + " lacks its number");
  return parse_real({args[i], where.line}, where, "transform option " + option);
}

// cos and sin of `degrees`: exact at multiples of 90.
std::array<double, 2> cos_sin(double degrees) {
  const double quarter = degrees / 90;
  if (quarter == std::round(quarter)) {
    static constexpr std::array<std::array<double, 2>, 4> exact{{{1, 0}, {0, 1}, {-1, 0}, {0, -1}}};
    const long k = ((long(std::fmod(quarter, 4.0)) % 4) + 4) % 4;
    return exact[std::size_t(k)];
  }
  const double radians = degrees * std::numbers::pi / 180;
  return {std::cos(radians), std::sin(radians)};
}

// Applies `next` after `t`.
RadTransform then(const RadTransform& t, const std::array<Vec3, 3>& m, const Vec3& shift, bool mirror) {
  RadTransform out;
  for (int r = 0; r < 3; ++r) {
    const Vec3& row = m[std::size_t(r)];
    const Vec3 col0{t.m[0].x, t.m[1].x, t.m[2].x}, col1{t.m[0].y, t.m[1].y, t.m[2].y}, col2{t.m[0].z, t.m[1].z, t.m[2].z};
    out.m[std::size_t(r)] = {dot(row, col0), dot(row, col1), dot(row, col2)};
  }
  out.t = Vec3{dot(m[0], t.t), dot(m[1], t.t), dot(m[2], t.t)} + shift;
  out.mirrors = t.mirrors != mirror;
  return out;
}

}  // namespace

RadTransform parse_rad_transform(const std::vector<std::string>& args, const SourceLocation& where) {
  RadTransform t;
  const std::array<Vec3, 3> identity{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& option = args[i];
    if (option == "-t") {
      const Vec3 shift{number(args, i + 1, option, where), number(args, i + 2, option, where),
                       number(args, i + 3, option, where)};
      t = then(t, identity, shift, false);
      i += 3;
    } else if (option == "-rx" || option == "-ry" || option == "-rz") {
      const auto [c, s] = cos_sin(number(args, ++i, option, where));
      std::array<Vec3, 3> m;
      if (option == "-rx") m = {Vec3{1, 0, 0}, Vec3{0, c, -s}, Vec3{0, s, c}};
      if (option == "-ry") m = {Vec3{c, 0, s}, Vec3{0, 1, 0}, Vec3{-s, 0, c}};
      if (option == "-rz") m = {Vec3{c, -s, 0}, Vec3{s, c, 0}, Vec3{0, 0, 1}};
      t = then(t, m, {}, false);
    } else if (option == "-s") {
      const double s = number(args, ++i, option, where);
      if (!(s > 0)) throw input_error(where, "transform option -s: the scale must be positive");
      t = then(t, {Vec3{s, 0, 0}, Vec3{0, s, 0}, Vec3{0, 0, s}}, {}, false);
    } else if (option == "-mx" || option == "-my" || option == "-mz") {
      std::array<Vec3, 3> m = identity;
      if (option == "-mx") m[0].x = -1;
      if (option == "-my") m[1].y = -1;
      if (option == "-mz") m[2].z = -1;
      t = then(t, m, {}, true);
    } else if (option == "-i" || option == "-a") {
      throw input_error(where, "transform option " + option +
                                   " (arrays of copies) is not applied by daylit: expand the copies first (xform)");
    } else {
      throw input_error(where, "unknown transform option '" + option + "' (daylit applies -t, -rx, -ry, -rz, -s, -mx, -my, -mz)");
    }
  }
  return t;
}

}  // namespace daylit
