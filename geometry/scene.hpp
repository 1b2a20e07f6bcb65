#pragma once
// A daylighting model: opaque occluders and apertures (sky openings). Plain data: what each material
// does to light is decided in materials/ (scene_materials.hpp), which assembles a Scene from .rad content.

#include <map>
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
  // (materials/glass_transmittance.hpp), and the fit's maximum error; empty: T is constant.
  std::vector<double> angular_transmittance{};
  double angular_fit_error = 0;
  // The pane's diffuse reflectance, the same from both sides: what the reflected components take
  // it to send back as Lambertian exitance (glass: 2∫R(μ)μ dμ of Radiance's model; trans: its
  // reflected parts; materials/scene_materials.cpp). 0: the light that meets it passes or is lost.
  double reflectance = 0;
};

struct Scene {
  std::vector<Polygon> occluders;
  std::vector<Aperture> apertures;
  // Of the apertures, those known to lie between two rooms (HBJSON interior windows): panes that
  // let the sky in only through another aperture.
  std::size_t interior_apertures = 0;
  std::vector<std::string> notices;
  // The material definitions read with the scene, by name (Polygon::material names one): what the
  // reflected components ask of a surface (materials/surface_reflectance.hpp).
  std::map<std::string, Material> materials;
};

}  // namespace daylit
