#pragma once
// What the faces of an OBJ model (geometry/obj_model.hpp) do to light, from their .mtl materials
// and the user's map (geometry/obj_material_map.hpp), as the RadContent that assemble_scene()
// turns into a Scene: each face gets a Radiance material that does what its role says, so that
// every later stage (visibility, glass, reflections, reports) treats OBJ and .rad models alike.
//
// A face's rule is its group rule, else its material rule (obj_material_map.hpp). Then:
//   opaque    plastic (r g b 0 0): the rule's reflectance as grey, else the .mtl's Kd as written
//             (so ρ = 0.265 r + 0.670 g + 0.065 b, Radiance's luminance weights, exactly as for a
//             .rad plastic of that colour), else 0.5 (below).
//   aperture  trans (T T T 0 0 1 1) among the apertures: a sky opening of constant transmittance T
//             (Radiance's trans passes (1 − spec)·trans·grey(T T T) = T, all of it specular, and
//             reflects (1 − spec)(1 − trans)·grey + spec = 0: an opening, not a diffusing sheet,
//             which trans 1 1 1 0 0 T 1 would be, sending 1 − T back).
//   glass     glass (t t t [n]): Radiance's angular model; t = the rule's transmissivity, or the t
//             whose normal-incidence transmittance is the rule's (else the .mtl's) transmittance.
//   ignore    no polygon.
// Without a rule, a face is an aperture when its .mtl material is transparent (below), opaque with
// its Kd otherwise. A face without a material daylit knows (no usemtl, a usemtl that no .mtl
// defines, or a material without Kd) is opaque with reflectance 0.5, Honeybee's generic wall
// (generic_wall_0.50: between its floor's 0.2 and ceiling's 0.8), counted in a notice.
//
// Transparent in the .mtl: a dissolve d < 1 (or Tr > 0), transmittance (1 − d)·grey(Tf), Tf white
// where absent; or an illum of 6 or 7 (the refraction models, whose transmitted light is Tf) with
// a Tf that is not black, transmittance grey(Tf). Tf alone on a material with d = 1 and another
// illum is ignored, with a notice (3ds Max writes Tf 1 1 1 on every opaque material). Ks and Ns
// (a Phong highlight) are not added to Kd: exporters write them for display (Blender's default
// Ks 0.5 on Kd 0.8 would reflect 1.3), and a notice says the surface is diffuse with Kd alone;
// map_Kd textures are not read (Kd is used), nor is emission (Ke).
//
// A mtllib that could not be read is an error when some face takes a value from the .mtl (no
// rule, or a rule that leaves a value to it); when the map gives every face all its values, it is
// a notice.

#include <optional>

#include "geometry/obj_material_map.hpp"
#include "geometry/obj_model.hpp"
#include "geometry/rad_reader.hpp"

namespace daylit {

// Transmittance at normal incidence of a material transparent in the .mtl (above); nullopt if opaque.
std::optional<double> mtl_transmittance(const MtlMaterial& material);

// The model's faces with their Radiance materials (`map` may be null). Throws daylit::Error for a
// mtllib that a face needs and that could not be read, a glass rule whose transmittance glass
// cannot reach, or a glass rule on a material with no transmittance to take.
RadContent obj_rad_content(const ObjModel& model, const ObjMaterialMap* map = nullptr);

}  // namespace daylit
