#pragma once
// The diffuse reflectance of an opaque surface, from its Radiance material: what the reflected
// components (DESIGN.md §4) take as the surface's ρ. Radiance's materials reflect in parts
// (diffuse, specular); a radiosity solution carries Lambertian exitance only, so every part is
// either reflected diffusely or counted as lost, and the description says which.
//
//   plastic  R G B spec rough: diffuse (1 − spec)·grey(RGB), specular spec (uncoloured). Both are
//            reflected diffusely: ρ = (1 − spec)·grey + spec. The energy is Radiance's; only the
//            direction of the specular lobe is not kept (exact for spec = 0, the common case).
//   metal    R G B spec rough: diffuse (1 − spec)·grey, specular spec·grey (coloured): ρ = grey,
//            reflected diffusely as plastic's specular part is.
//   trans    is not an opaque surface: wherever it is filed it is a pane of transmittance
//            (1 − spec)·τ·grey (materials/scene_materials.cpp), so it never reaches this function;
//            its reflectance (1 − spec)(1 − τ)·grey + spec is the pane's (Aperture::reflectance),
//            as is glass's diffuse reflectance; scene_reflectances lists both.
//   void     (the null modifier) and glow/light (emitters: the sky comes from --sky): black.
//   mirror   specular only: not representable; an error when reflections are computed.
//
// grey(RGB) is Radiance's luminance weighting (radiance_luminance.hpp).

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "geometry/rad_reader.hpp"
#include "geometry/scene.hpp"

namespace daylit {

struct SurfaceReflectance {
  double reflectance = 0;          // diffuse, in [0, 1)
  double specular_as_diffuse = 0;  // the specular part folded into `reflectance`
  std::string description;         // one line for notices and the summary: how ρ was obtained
};

// The surface's reflectance from its material (nullptr: no material, or the null modifier `void`).
// Throws daylit::Error naming the material's file and line for a mirror (not representable), and
// for a reflectance outside [0, 1) (a surface reflecting all the light it receives makes the
// radiosity equation singular; Radiance's materials above 1 create light).
SurfaceReflectance surface_reflectance(const Material* material);

// Every occluder's reflectance (Scene::occluders order) from its material, and what was used,
// by material name ("void" for polygons without one), the reflecting panes' materials included:
// the reflected components' input.
struct SceneReflectances {
  std::vector<double> reflectance;
  std::map<std::string, SurfaceReflectance> materials;
};
SceneReflectances scene_reflectances(const Scene& scene);

}  // namespace daylit
