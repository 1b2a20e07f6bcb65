#include "materials/scene_materials.hpp"

#include <cstdio>

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

Scene assemble_scene(const RadContent& content) {
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
  for (const auto& entry : content.polygons) {
    const Polygon& poly = entry.polygon;
    const auto it = content.materials.find(poly.material);
    const Material* material = it == content.materials.end() ? nullptr : &it->second;
    const std::string type = material ? material->type : "void";
    if (type == "glass") {
      const GlassOptics optics = glass_optics(*material);
      const double t = glass_transmittance(optics, 1.0);
      const TransmittancePolynomial fit = fit_glass_transmittance(optics);
      char text[256];
      std::snprintf(text, sizeof text,
                    "': transmittance %.4f at normal incidence, falling with the angle of incidence as Radiance's "
                    "glass model, fitted by a degree-%zu polynomial in cos θ (max error %.1e)",
                    t, fit.coefficients.size() - 1, fit.max_error);
      describe_once(*material, "glass '" + material->name + text);
      scene.apertures.push_back({poly, t, fit.coefficients, fit.max_error});
    } else if (entry.from_aperture_file) {
      if (type == "void") {
        scene.apertures.push_back({poly, 1.0});
      } else if (type == "trans") {
        const auto& a = material->reals;
        const double t = (1 - a[3]) * a[5] * radiance_luminance(a[0], a[1], a[2]);
        describe_once(*material, "trans '" + material->name + "': transmittance " + format_fraction(t) +
                                     ", its diffuse part treated as clear");
        scene.apertures.push_back({poly, t});
      } else {
        throw input_error(poly.where, "aperture '" + poly.name + "' has material '" + poly.material + "' of type " +
                                          type + "; apertures must be void, glass or trans");
      }
    } else {
      scene.occluders.push_back(poly);
    }
  }
  return scene;
}

Scene load_scene(const std::vector<std::string>& scene_files, const std::vector<std::string>& aperture_files) {
  RadContent content;
  for (const auto& f : scene_files) read_rad_file(f, false, content);
  for (const auto& f : aperture_files) read_rad_file(f, true, content);
  return assemble_scene(content);
}

}  // namespace daylit
