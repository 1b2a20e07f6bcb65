#pragma once
// What each Radiance material of a model does to light, and the Scene assembled from .rad content:
// which polygons are apertures (sky openings, with their transmittance), which are occluders, and
// which are nothing to the sky component.

#include <optional>
#include <string>
#include <vector>

#include "geometry/rad_reader.hpp"
#include "geometry/scene.hpp"
#include "materials/glass_transmittance.hpp"

namespace daylit {

struct SceneOptions {
  // The uniform transmittance (0 to 1) given to apertures of Radiance's `BSDF`/`aBSDF` type
  // (tensor-tree or Klems data whose angular detail the sky component does not use). Unset: such
  // an aperture is an error that says how to give it.
  std::optional<double> bsdf_transmittance;
};

// The roles, as Radiance and Honeybee give them (every decision that is not Radiance's own is
// said in a notice):
// - Aperture files: `void` is an opening (transmittance 1), `glass` Radiance's angle-dependent
//   transmittance (fitted by a polynomial in the cosine of incidence), `trans`
//   (1 − spec)·trans·luminance(colour) (its diffuse part treated as clear), `BSDF`/`aBSDF` the
//   stated SceneOptions::bsdf_transmittance. Opaque materials there (Honeybee writes doors into
//   the aperture folder) are occluders.
// - Scene files: `void` polygons are nothing (Radiance: a void-modified surface does not exist);
//   `glass` is an aperture unless the model says it separates two rooms (RadContent::Entry::
//   interior), when it is an occluder and the light through it is left out; every other material
//   is an opaque occluder.
// - Anywhere: `light`, `glow` and `illum` polygons are light sources (or Radiance's secondary
//   sources standing in for windows), not sky openings or occluders: they are left out.
// Throws daylit::Error naming file and line for a BSDF aperture without a stated transmittance.
Scene assemble_scene(const RadContent& content, const SceneOptions& options = {});

// Reads the scene and aperture files (materials accumulate across them, as with oconv) and
// assembles the Scene.
Scene load_scene(const std::vector<std::string>& scene_files, const std::vector<std::string>& aperture_files,
                 const SceneOptions& options = {});

// The optics of Radiance's `glass` from its reals: transmissivities per channel and the optional
// refractive index (default 1.52).
GlassOptics glass_optics(const Material& glass);

}  // namespace daylit
