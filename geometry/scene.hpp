#pragma once
// A daylighting model: opaque occluders and apertures (sky openings), assembled from .rad files.

#include <string>
#include <vector>

#include "geometry/polygon.hpp"
#include "geometry/rad_reader.hpp"

namespace daylit {

struct Aperture {
  Polygon polygon;
  // Fraction of the sky's light that passes, at normal incidence (1 for an open hole).
  double transmittance = 1;
  // For glass: T(μ) = Σ_k angular_transmittance[k] μ^k, μ the cosine of incidence on the pane
  // (illumination/glass_transmittance.hpp), and the fit's maximum error; empty: T is constant.
  std::vector<double> angular_transmittance{};
  double angular_fit_error = 0;
};

struct Scene {
  std::vector<Polygon> occluders;
  std::vector<Aperture> apertures;
  std::vector<std::string> notices;
};

// Polygons in aperture files are sky openings: transmittance 1 for `void`, Radiance's angle-
// dependent transmittance for `glass` (fitted by a polynomial in the cosine of incidence), (1 − spec)·trans·luminance(colour) for `trans` (its diffuse part
// treated as if it were clear). `glass` polygons in scene files are apertures as well; every other
// polygon in a scene file is an opaque occluder.
Scene assemble_scene(const RadContent& content);

Scene load_scene(const std::vector<std::string>& scene_files, const std::vector<std::string>& aperture_files);

// Normal-incidence transmittance of Radiance's `glass` from its transmissivities t (per channel)
// and refractive index n (default 1.52): T = t(1 − R)² / (1 − R²t²), R = ((n − 1)/(n + 1))²,
// the inverse of the conversion in Radiance's glass documentation; channels are weighted by
// Radiance's luminance coefficients (0.265, 0.670, 0.065).
double glass_normal_transmittance(const Material& glass);

}  // namespace daylit
