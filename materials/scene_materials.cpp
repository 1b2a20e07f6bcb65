#include "materials/scene_materials.hpp"

#include <algorithm>
#include <cstdio>
#include <map>

#include "geometry/text_scanner.hpp"

#include "materials/glass_transmittance.hpp"
#include "materials/radiance_luminance.hpp"

namespace daylit {

namespace {

std::string format_fraction(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", x);
  return buf;
}

}  // namespace

GlassOptics glass_optics(const Material& glass) {
  const auto& r = glass.reals;
  return {{r[0], r[1], r[2]}, r.size() > 3 ? r[3] : 1.52};
}

namespace {

// Polygons given one role for one reason: counted, reported once with the first of them.
struct Tally {
  long count = 0;
  const Polygon* first = nullptr;
  void add(const Polygon& p) {
    if (count++ == 0) first = &p;
  }
  std::string notice(const std::string& what, const std::string& why) const {
    return first->where.str() + ": " + std::to_string(count) + " " + what + (count > 1 ? "s" : "") + " (" +
           printable(first->name) + " first) " + why;
  }
};

}  // namespace

Scene assemble_scene(const RadContent& content, const SceneOptions& options) {
  Scene scene;
  scene.notices = content.notices;
  scene.materials = content.materials;
  std::vector<std::string> described;
  auto describe_once = [&](const Material& m, const std::string& text) {
    for (const auto& d : described)
      if (d == m.name) return;
    described.push_back(m.name);
    scene.notices.push_back(text);
  };
  Tally void_in_scene, opaque_in_apertures, sources, interior_glass, interior_copies;
  std::vector<const Polygon*> interior_panes;
  struct GlassFit {
    double transmittance = 0;                 // at normal incidence
    double reflectance = 0, normal_reflectance = 0;  // for diffuse light; at normal incidence
    TransmittancePolynomial fit;
  };
  std::map<std::string, GlassFit> glass_fits;  // by material name
  for (const auto& entry : content.polygons) {
    const Polygon& poly = entry.polygon;
    const auto it = content.materials.find(poly.material);
    const Material* material = it == content.materials.end() ? nullptr : &it->second;
    const std::string type = material ? material->type : "void";
    if (type == "light" || type == "glow" || type == "illum") {
      sources.add(poly);
    } else if (type == "glass" && entry.interior && std::any_of(interior_panes.begin(), interior_panes.end(), [&](const Polygon* q) {
                 return same_outline(*q, poly, RadContent::kInteriorCopyGap);
               })) {
      // The adjacent room's copy of an interior window (Honeybee writes it once per room): one pane.
      interior_copies.add(poly);
    } else if (type == "glass") {
      if (entry.interior) {
        interior_glass.add(poly);
        interior_panes.push_back(&poly);
        ++scene.interior_apertures;
      }
      // One fit per material: a model's windows share a few glass materials, and the fit's least
      // squares cost 9 ms each (1.5 s of Honeybee's lab_building, 168 windows, when done per polygon).
      auto fitted = glass_fits.find(material->name);
      if (fitted == glass_fits.end()) {
        const GlassOptics optics = glass_optics(*material);
        fitted = glass_fits
                     .emplace(material->name, GlassFit{glass_transmittance(optics, 1.0), glass_diffuse_reflectance(optics),
                                                       glass_reflectance(optics, 1.0), fit_glass_transmittance(optics)})
                     .first;
      }
      const GlassFit& g = fitted->second;
      char text[512];
      std::snprintf(text, sizeof text,
                    "': transmittance %.4f at normal incidence, falling with the angle of incidence as Radiance's "
                    "glass model, fitted by a degree-%zu polynomial in cos θ (max error %.1e); it reflects %.4f of "
                    "diffuse light (%.4f at normal incidence), which the reflected components send back diffusely",
                    g.transmittance, g.fit.coefficients.size() - 1, g.fit.max_error, g.reflectance,
                    g.normal_reflectance);
      describe_once(*material, "glass '" + material->name + text);
      scene.apertures.push_back({poly, g.transmittance, g.fit.coefficients, g.fit.max_error, g.reflectance});
    } else if (type == "BSDF" || type == "aBSDF") {
      const std::string data = material->strings.size() > 1 ? " (data " + printable(material->strings[1]) + ")" : "";
      if (!entry.from_aperture_file) {
        describe_once(*material, material->where.str() + ": " + type + " " + printable(material->name) + data +
                                     " in a scene file is an opaque occluder: the light it transmits is left out");
        scene.occluders.push_back(poly);
      } else if (!options.bsdf_transmittance) {
        throw input_error(poly.where, "aperture " + printable(poly.name) + " has the " + type + " material " +
                                          printable(material->name) + data +
                                          ", whose angular data daylit does not read: give the uniform visible "
                                          "transmittance to use for it with --bsdf-transmittance (0 to 1)");
      } else {
        describe_once(*material, type + " " + printable(material->name) + data + ": the stated uniform transmittance " +
                                     format_fraction(*options.bsdf_transmittance) + " (--bsdf-transmittance), not its "
                                     "angular data");
        scene.apertures.push_back({poly, *options.bsdf_transmittance});
      }
    } else if (type == "trans") {
      // Radiance's trans (ray/src/rt/normal.c): of what the surface does not reflect specularly
      // (1 − spec), the fraction trans passes through, tspec of that specularly and the rest
      // diffusely, all of it tinted by the colour. Wherever it is filed (a translucent pane, a
      // foliage shade, Honeybee's air boundary, trans 1 1 1 0 0 1 1) it is a pane of the total
      // transmittance: what lies beyond is seen through it, attenuated, and light through several
      // panes counts once (AperturesAre::panes). Its diffuse part is treated as clear, the stated
      // approximation. What it reflects, (1 − spec)(1 − trans)·grey diffusely and spec specularly,
      // the reflected components send back diffusely (as plastic's specular part).
      const auto& a = material->reals;
      const double grey = radiance_luminance(a[0], a[1], a[2]);
      const double t = (1 - a[3]) * a[5] * grey, reflected = (1 - a[3]) * (1 - a[5]) * grey + a[3];
      // A transmitted specularity of 1 leaves no diffuse part to treat (OBJ apertures of constant
      // transmittance are such trans: materials/obj_materials.hpp).
      describe_once(*material, (entry.from_aperture_file ? "" : material->where.str() + ": ") + "trans " +
                                   printable(material->name) + ": a pane of transmittance " + format_fraction(t) +
                                   (a[6] < 1 ? ", its diffuse part (" + format_fraction(t * (1 - a[6])) + ") treated as clear" : std::string()) +
                                   (reflected > 0 ? "; it reflects " + format_fraction(reflected) +
                                                        ", which the reflected components send back diffusely"
                                                  : std::string()));
      scene.apertures.push_back({poly, t, {}, 0, reflected});
    } else if (entry.from_aperture_file) {
      if (type == "void") {
        scene.apertures.push_back({poly, 1.0});
      } else {
        opaque_in_apertures.add(poly);
        scene.occluders.push_back(poly);
      }
    } else if (type == "void") {
      void_in_scene.add(poly);
    } else {
      scene.occluders.push_back(poly);
    }
  }
  if (void_in_scene.count)
    scene.notices.push_back(void_in_scene.notice("void polygon", "in scene files left out: in Radiance a surface "
                                                                 "modified by void does not exist"));
  if (opaque_in_apertures.count)
    scene.notices.push_back(opaque_in_apertures.notice(
        "polygon", "of opaque materials in aperture files taken as occluders, not openings (Honeybee writes doors "
                   "there); openings are void, glass, trans or BSDF"));
  if (sources.count)
    scene.notices.push_back(sources.notice("light, glow or illum polygon",
                                           "left out: light sources (or Radiance's secondary sources standing in for "
                                           "windows) are neither sky openings nor occluders here; the sky comes from "
                                           "--sky, openings are void, glass or trans polygons in --apertures"));
  if (interior_glass.count)
    scene.notices.push_back(interior_glass.notice(
        "glass polygon", "between two rooms (interior windows) taken as panes: the sky seen through one and then "
                         "a neighbouring room's window is counted once, with both transmittances"));
  if (interior_copies.count)
    scene.notices.push_back(interior_copies.notice(
        "glass polygon", "left out as the adjacent room's copy of an interior window already read (the same "
                         "outline within 1e-6 of its extent, facing the other way up to 5 % of it apart, as "
                         "Honeybee's Radiance folders move it): one pane"));
  return scene;
}

Scene load_scene(const std::vector<std::string>& scene_files, const std::vector<std::string>& aperture_files,
                 const SceneOptions& options) {
  RadContent content;
  for (const auto& f : scene_files) read_rad_file(f, false, content);
  for (const auto& f : aperture_files) read_rad_file(f, true, content);
  return assemble_scene(content, options);
}

}  // namespace daylit
