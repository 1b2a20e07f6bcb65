#include "materials/surface_reflectance.hpp"

#include <cstdio>

#include "geometry/error.hpp"
#include "materials/radiance_luminance.hpp"

namespace daylit {

namespace {

std::string fraction(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

// Radiance's colour channels and specularity are fractions; outside [0, 1] a surface creates
// light or reflects negatively.
void check_fraction(const Material& m, double x, const char* what) {
  if (!(x >= 0 && x <= 1))
    throw input_error(m.where, m.type + " '" + m.name + "': " + what + " " + fraction(x) + " is outside [0, 1]");
}

}  // namespace

SurfaceReflectance surface_reflectance(const Material* material) {
  SurfaceReflectance out;
  if (!material || material->type == "void") {
    out.description = "black (the null modifier void)";
    return out;
  }
  const Material& m = *material;
  const auto& r = m.reals;
  if (m.type == "glow" || m.type == "light") {
    out.description = "black: a light source's emission is not daylight (the sky comes from --sky)";
    return out;
  }
  if (m.type == "mirror")
    throw input_error(m.where, "mirror '" + m.name +
                                   "' reflects specularly, which diffuse radiosity cannot represent; give the surface a "
                                   "plastic or metal material, or compute the sky component alone (--components sc)");
  if (m.type != "plastic" && m.type != "metal")
    throw input_error(m.where, m.type + " '" + m.name + "' is not an opaque surface material");
  const char* const channel[3] = {"red reflectance", "green reflectance", "blue reflectance"};
  for (int c = 0; c < 3; ++c) check_fraction(m, r[c], channel[c]);
  check_fraction(m, r[3], "specularity");
  const double grey = radiance_luminance(r[0], r[1], r[2]);
  const double spec = r[3];
  if (m.type == "plastic") {
    out.reflectance = (1 - spec) * grey + spec;
    out.specular_as_diffuse = spec;
    out.description = "plastic: diffuse " + fraction((1 - spec) * grey) +
                      (spec > 0 ? " and specular " + fraction(spec) + " reflected diffusely" : std::string());
  } else {  // metal
    out.reflectance = grey;
    out.specular_as_diffuse = spec * grey;
    out.description = "metal: diffuse " + fraction((1 - spec) * grey) +
                      (spec > 0 ? " and specular " + fraction(spec * grey) + " reflected diffusely" : std::string());
  }
  if (!(out.reflectance < 1))
    throw input_error(m.where, m.type + " '" + m.name + "': reflectance " + fraction(out.reflectance) +
                                   " is not below 1; a surface that reflects all it receives makes the reflected "
                                   "components diverge");
  out.description = "reflectance " + fraction(out.reflectance) + " (" + out.description + ")";
  return out;
}

SceneReflectances scene_reflectances(const Scene& scene) {
  SceneReflectances out;
  for (const Polygon& p : scene.occluders) {
    const auto it = scene.materials.find(p.material);
    const Material* m = it == scene.materials.end() ? nullptr : &it->second;
    const SurfaceReflectance r = surface_reflectance(m);
    out.reflectance.push_back(r.reflectance);
    out.materials.emplace(m ? m->name : p.material.empty() ? "void" : p.material, r);
  }
  // The panes that reflect (glass, trans: scene_materials.cpp set their reflectance), once per material.
  for (const Aperture& a : scene.apertures) {
    if (!(a.reflectance > 0) || out.materials.count(a.polygon.material)) continue;
    const auto it = scene.materials.find(a.polygon.material);
    const std::string type = it == scene.materials.end() ? "pane" : it->second.type;
    SurfaceReflectance r;
    r.reflectance = a.reflectance;
    r.description = type == "glass"
                        ? "glass: a pane reflecting 2∫R(μ)μ dμ of Radiance's glass model, both sides, diffusely "
                          "(Radiance reflects it specularly, R from about 0.08 at normal incidence to 1 at grazing: "
                          "the energy for diffuse light is kept, its direction is not); it transmits as for the sky"
                        : type + ": a pane reflecting (1 - spec)(1 - trans) grey + spec, both sides, diffusely "
                                 "(its specular part too, as plastic's); it transmits as for the sky";
    out.materials.emplace(a.polygon.material, r);
  }
  return out;
}

}  // namespace daylit
