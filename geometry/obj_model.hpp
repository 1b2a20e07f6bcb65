#pragma once
// Wavefront OBJ models (.obj) with their material libraries (.mtl), read into plain data: faces as
// polygons with their group, object and material names, and the .mtl materials as written. What
// each material does to light (opaque, aperture, glass, nothing) is decided in materials/
// (obj_materials.hpp), with the user's map (geometry/obj_material_map.hpp).
//
// Why daylit reads OBJ itself instead of through tinyobjloader or assimp (both in Debian): the
// visibility is exact on the input doubles, so a coordinate must become the double nearest to its
// decimal text, as the .rad and .pts readers make it (std::from_chars); and every error must name
// its file and line. Debian's assimp is built in single precision (ai_real = float). Debian's
// tinyobjloader ships a double build (tinyobjloader::tinyobjloader_double), but its number parser
// sums digit × 10^-k, which is not correctly rounded ("0.3" becomes 0.30000000000000004; on a third
// of millimetre-rounded coordinates it differs from the nearest double), reads "abc" as 0 and
// "1.5x" as 1.5 without a word, reports out-of-range face indices as a warning with the file's
// last line, and forgets a `usemtl` name that no .mtl defines. The OBJ statements a building needs
// are few, so the reader is small; tests/geometry/test_obj_model.cpp holds its faces, groups and
// materials to tinyobjloader's on the test models.
//
// Read: `v` (x y z, an optional weight or an r g b colour after them ignored), `vt`, `vn` (counted,
// for the indices), `f` with any number of vertices in the forms v, v/vt, v//vn, v/vt/vn, indices
// from 1 or negative (relative to the vertices defined so far), `g` (one or more group names),
// `o`, `usemtl`, `mtllib` (one or more files relative to the .obj's folder; a name with spaces is
// taken whole when such a file exists), and `\` line continuation. Skipped: `l` and `p` (no area,
// counted in a notice), `s`, `mg`, `lod`, render and free-form settings. Refused: free-form
// geometry (`curv`, `curv2`, `surf`), `call` and `csh`, and any other statement.
//
// Faces: repeated consecutive vertices are dropped (as in .rad). A face left with fewer than 3
// distinct vertices or with zero area is skipped and counted (CAD tessellations leave slivers;
// the .rad reader refuses them, since a hand-written scene means every polygon). A face warped
// beyond kPlanarityTolerance of its extent is split into two triangles when it is a quad (along
// the diagonal that keeps both triangles facing the quad's way, the shorter if both do), counted
// in a notice; a warped face of 5 or more vertices is an error naming its line (which of its many
// triangulations is meant cannot be told).

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "geometry/error.hpp"
#include "geometry/polygon.hpp"

namespace daylit {

// The file's axes and units, applied to every vertex as it is read: first the scale (metres per
// unit), then the up axis. OBJ has neither; daylit's frame is z up, in metres (that of --grid,
// --site and --context).
enum class ObjUpAxis {
  z,  // as written
  y,  // (x, y, z) → (x, −z, y): the inverse of the turn Blender applies on export (Y up, −Z forward)
};
struct ObjOptions {
  double metres_per_unit = 1;  // > 0. Exact when 1/metres_per_unit is an integer (0.001, 0.01): the
                               // coordinate is divided by it, so 1234 mm becomes the double nearest
                               // to 1.234, as if written in metres; otherwise multiplied (one rounding)
  ObjUpAxis up = ObjUpAxis::z;
};

// One material of a .mtl file, as written (absent statements stay unset).
struct MtlMaterial {
  std::string name;
  SourceLocation where;                    // its newmtl line
  std::optional<std::array<double, 3>> kd; // diffuse colour, each in [0, 1]
  std::optional<std::array<double, 3>> ks; // specular colour (a Phong highlight)
  std::optional<std::array<double, 3>> tf; // transmission filter, each in [0, 1]
  std::optional<std::array<double, 3>> ke; // emission
  std::optional<double> dissolve;          // d, in [0, 1] (1: opaque); or 1 − Tr where only Tr is given
  std::optional<double> ns;                // specular exponent
  std::optional<int> illum;                // illumination model, 0 … 10
  SourceLocation dissolve_where, tf_where;
  bool texture = false;        // map_Kd: the colour comes from an image (not read)
  bool alpha_texture = false;  // map_d: the dissolve comes from an image (not read)
};

struct ObjFace {
  Polygon polygon;                  // material: the usemtl name in force ("" before any); where: the f line
  std::vector<std::string> groups;  // the names of the last `g` ("default" before any)
  std::string object;               // the name of the last `o` ("" before any)
};

struct ObjModel {
  std::string path;
  ObjOptions options;  // as read with
  std::vector<ObjFace> faces;
  std::map<std::string, MtlMaterial> materials;  // every .mtl read; a later definition replaces
  std::vector<std::string> mtl_files;            // the .mtl files read, in order
  // mtllib files that could not be read: whether that is an error depends on whether some face's
  // role needs them (materials/obj_materials.hpp).
  struct MissingLibrary {
    std::string name, path;
    SourceLocation where;
  };
  std::vector<MissingLibrary> missing_libraries;
  long vertices = 0;
  long skipped_degenerate = 0;  // faces with < 3 distinct vertices or zero area
  long split_quads = 0;         // warped quads split into two triangles
  std::vector<std::string> notices;
};

// Reads the .obj at `path` and the .mtl files it names (relative to its folder). Throws
// daylit::Error naming the file and line of bad input (a bad number, an index out of range, a
// warped face of 5 or more vertices, an unknown statement, …).
ObjModel read_obj_model(const std::string& path, const ObjOptions& options = {});

// The same for text in memory; `read_library(name)` returns the text of the .mtl that a `mtllib`
// names (its path, resolved by the caller, in the second member), or nullopt when it cannot be read.
using MtlLibraryReader = std::function<std::optional<std::pair<std::string, std::string>>(const std::string& name)>;
ObjModel parse_obj(const std::string& text, const std::string& name, const ObjOptions& options,
                   const MtlLibraryReader& read_library);

// Parses one .mtl text into `materials` (`name` in messages). Throws daylit::Error with file:line.
void parse_mtl(const std::string& text, const std::string& name, std::map<std::string, MtlMaterial>& materials,
               std::vector<std::string>& notices);

// True for a path that names an OBJ file (extension .obj, any case).
bool is_obj_path(const std::string& path);

}  // namespace daylit
