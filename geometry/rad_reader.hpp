#pragma once
// Reader for Radiance scene descriptions (.rad): the subset a daylighting model needs.
//
// A primitive is "modifier type identifier", then three argument lists, each preceded by its
// count: strings, integers, reals. '#' starts a comment that runs to the end of the line.
// Geometry: `polygon` only. Materials are kept by type (plastic, metal, trans, glass, mirror,
// glow, light, illum, BSDF, aBSDF; `alias` for renaming); `void` is the null modifier. Sky and light-source
// primitives (`source`, and the `brightfunc`/`colorfunc` patterns a sky is made of) are skipped
// with a notice, since the sky comes from the command line. `!command` lines and every other
// primitive are an error naming the file and line.

#include <map>
#include <set>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/polygon.hpp"

namespace daylit {

struct Material {
  std::string name;
  std::string type;
  std::vector<std::string> strings;
  std::vector<double> reals;
  SourceLocation where;
};

// Everything read from one or more .rad files, in order. Material definitions accumulate across
// files, as with Radiance's oconv.
struct RadContent {
  std::map<std::string, Material> materials;
  struct Entry {
    Polygon polygon;
    bool from_aperture_file = false;
    // Known to separate two rooms (HBJSON: an aperture on a Surface boundary condition): glass
    // here lets no sky in directly. A .rad file cannot tell, so its polygons leave it false.
    bool interior = false;
  };
  // How far apart (a fraction of its extent) the two copies of an interior window may lie to be
  // one pane (same_outline): Honeybee's 2 × tolerance is 0.02 m at its default tolerance of
  // 0.01 m, 1.4 % of a 1 m square window's extent; 5 % leaves room for smaller windows and coarser
  // tolerances and stays far below the depth of a room.
  static constexpr double kInteriorCopyGap = 0.05;
  std::vector<Entry> polygons;
  std::vector<std::string> notices;
  // Names of skipped sky patterns and sources: materials may still name them as modifiers.
  std::set<std::string> skipped_modifiers;
};

// Planarity tolerance for polygons: the largest distance of a vertex from the polygon's mean
// plane, relative to the polygon's extent. Beyond it a polygon is rejected (CAD exports in single
// precision sit near 1e-7; a visibly warped quad is well above 1e-4).
inline constexpr double kPlanarityTolerance = 1e-4;

// Throws daylit::Error at `poly.where` if the polygon has zero area or is warped beyond
// kPlanarityTolerance of its extent (the checks every reader applies).
void check_polygon(const Polygon& poly);

// Throws daylit::Error at `material.where` if a kept material type has the wrong number of reals,
// or if glass or trans reals are unphysical (they enter the apertures' transmittance).
void check_material(const Material& material);

// Reads `path` and appends its content. Throws daylit::Error with file:line on bad input.
void read_rad_file(const std::string& path, bool aperture_file, RadContent& content);

// The same for text already in memory; `name` is used in messages.
void read_rad_text(const std::string& text, const std::string& name, bool aperture_file,
                   RadContent& content);

}  // namespace daylit
