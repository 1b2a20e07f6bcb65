#pragma once
// What each Radiance material of a model does to light, and the Scene assembled from .rad content:
// which polygons are apertures (sky openings, with their transmittance) and which are occluders.

#include <string>
#include <vector>

#include "geometry/rad_reader.hpp"
#include "geometry/scene.hpp"
#include "materials/glass_transmittance.hpp"

namespace daylit {

// Polygons in aperture files are sky openings: transmittance 1 for `void`, Radiance's angle-
// dependent transmittance for `glass` (fitted by a polynomial in the cosine of incidence),
// (1 − spec)·trans·luminance(colour) for `trans` (its diffuse part treated as if it were clear).
// `glass` polygons in scene files are apertures as well; every other polygon in a scene file is
// an opaque occluder. Throws daylit::Error naming file and line for an aperture of another material.
Scene assemble_scene(const RadContent& content);

// Reads the scene and aperture files (materials accumulate across them, as with oconv) and
// assembles the Scene.
Scene load_scene(const std::vector<std::string>& scene_files, const std::vector<std::string>& aperture_files);

// The optics of Radiance's `glass` from its reals: transmissivities per channel and the optional
// refractive index (default 1.52).
GlassOptics glass_optics(const Material& glass);

}  // namespace daylit
