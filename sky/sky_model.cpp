#include "sky/sky_model.hpp"

#include <algorithm>
#include <numbers>
#include <string>

#include "geometry/error.hpp"
#include "illumination/moments.hpp"

namespace daylit {

SkyName parse_sky_name(std::string_view name) {
  if (name == "uniform") return {SkyName::Kind::uniform, 0};
  if (name == "cie-overcast") return {SkyName::Kind::cie_overcast, 0};
  if (name == "perez") return {SkyName::Kind::perez, 0};
  if (name.substr(0, 4) == "cie-") {
    const std::string_view n = name.substr(4);
    if (!n.empty() && n.size() <= 2 && std::all_of(n.begin(), n.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      const int type = std::stoi(std::string(n));
      if (type >= 1 && type <= 15) return {SkyName::Kind::cie_general, type};
    }
  }
  throw Error("unknown sky '" + std::string(name) + "': use uniform, cie-overcast, cie-1 … cie-15 (ISO 15469 types) or perez");
}

SkyModel parse_sky_model(std::string_view name) {
  if (name == "cie-overcast") return SkyModel::cie_overcast;
  if (name == "uniform") return SkyModel::uniform;
  throw Error("unknown sky '" + std::string(name) + "': use cie-overcast or uniform");
}

std::string_view sky_model_name(SkyModel sky) noexcept {
  return sky == SkyModel::cie_overcast ? "cie-overcast" : "uniform";
}

double sky_irradiance(const SphericalRegion& region, const Vec3& n, SkyModel sky) {
  if (region.empty()) return 0;
  if (sky == SkyModel::uniform) return lambert(region, n);
  const CosineMoments m = cosine_moments(region, n, {0, 0, 1});
  return (m.cosine + 2 * m.cosine_linear) / 3;
}

double sky_irradiance_through_glazing(const SphericalRegion& region, const Vec3& n, SkyModel sky, Vec3 a,
                                      const std::vector<double>& c) {
  if (region.empty()) return 0;
  Vec3 inside{};
  for (const Vec3& u : region.loops.front()) inside += normalized(u);
  if (dot(a, inside) < 0) a = -1.0 * a;
  const PolynomialCosineMoments m = polynomial_cosine_moments(region, a, n, {0, 0, 1}, c);
  return sky == SkyModel::uniform ? m.cosine : (m.cosine + 2 * m.cosine_linear) / 3;
}

double sky_relative_luminance(SkyModel sky, const Vec3& u) noexcept {
  return sky == SkyModel::cie_overcast ? (1 + 2 * u.z) / 3 : 1.0;
}

double unobstructed_horizontal_irradiance(SkyModel sky) noexcept {
  return sky == SkyModel::cie_overcast ? 7 * std::numbers::pi / 9 : std::numbers::pi;
}

}  // namespace daylit
