#include "simulation/sky_patches.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/error.hpp"
#include "illumination/cap_clip.hpp"
#include "illumination/hemisphere_clip.hpp"
#include "illumination/moments.hpp"
#include "materials/glass_transmittance.hpp"
#include "simulation/pane_transmittance.hpp"

namespace daylit {

namespace {

constexpr double kDeg = std::numbers::pi / 180;

// The horizontal unit vector at azimuth φ (clockwise from true north), in the model frame.
Vec3 horizontal(const Site& site, double azimuth_deg) { return site.model_direction(azimuth_deg, 0); }

// ∫ (n·u) dσ over the part of `region` above altitude α (the whole region for α ≤ 0: it lies above
// the horizon already; none for α ≥ 90°).
double above_altitude(const SphericalRegion& region, double altitude_deg, const Vec3& n) {
  if (altitude_deg <= 0) return lambert(region, n);
  if (altitude_deg >= 90) return 0;
  return cap_lambert(region, {0, 0, 1}, (90 - altitude_deg) * kDeg, n);
}

}  // namespace

std::vector<SkyPatch> reinhart_patches(int mf, const Site& site) {
  if (mf < 1 || mf > 6) throw Error("the Reinhart subdivision MF must lie in 1..6");
  constexpr int kTregenzaRow[7] = {30, 30, 24, 24, 18, 12, 6};
  const double row = 90.0 / (7 * mf + 0.5);
  std::vector<SkyPatch> patches;
  for (int r = 0; r < 7 * mf; ++r) {
    const int count = kTregenzaRow[r / mf] * mf;
    const double width = 360.0 / count, a0 = r * row, a1 = (r + 1) * row;
    for (int k = 0; k < count; ++k) {
      SkyPatch p;
      p.altitude0_deg = a0;
      p.altitude1_deg = a1;
      p.azimuth0_deg = (k - 0.5) * width;
      p.azimuth1_deg = (k + 0.5) * width;
      p.centre = site.model_direction(k * width, (r + 0.5) * row);
      // Clockwise seen from above is a negative turn about +z: u is past h0 when (h0 × u)·z ≤ 0,
      // i.e. (h0 × z)·u ≥ 0, and before h1 when (z × h1)·u ≥ 0 (the wedge is below 180°).
      const Vec3 z{0, 0, 1};
      p.from = cross(horizontal(site, p.azimuth0_deg), z);
      p.to = cross(z, horizontal(site, p.azimuth1_deg));
      p.solid_angle = width * kDeg * (std::sin(a1 * kDeg) - std::sin(a0 * kDeg));
      patches.push_back(p);
    }
  }
  SkyPatch cap;
  cap.altitude0_deg = 7 * mf * row;
  cap.altitude1_deg = 90;
  cap.azimuth0_deg = 0;
  cap.azimuth1_deg = 360;
  cap.centre = {0, 0, 1};
  cap.solid_angle = 2 * std::numbers::pi * (1 - std::sin(cap.altitude0_deg * kDeg));
  patches.push_back(cap);
  return patches;
}

void add_patch_coefficients(const std::vector<SkyPatch>& patches, const SphericalRegion& region, const Vec3& n,
                            const Aperture& transmitting, std::vector<double>& coefficients, double& spread, double sign) {
  if (region.empty()) return;
  const bool glazed = !transmitting.angular_transmittance.empty();
  const Vec3 pane = glazed ? normalized(newell_normal(transmitting.polygon.vertices)) : Vec3{};
  // The region's altitude range prunes the bands it cannot meet.
  double lo = 1, hi = -1;
  std::tie(lo, hi) = cosine_range(region, {0, 0, 1});
  const double top = std::asin(std::clamp(hi, -1.0, 1.0)) / kDeg, bottom = std::asin(std::clamp(lo, -1.0, 1.0)) / kDeg;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const SkyPatch& p = patches[i];
    if (p.altitude0_deg > top || p.altitude1_deg < bottom) continue;
    const bool cap = p.altitude1_deg >= 90;
    const SphericalRegion wedge = cap ? region : clip_to_hemisphere(clip_to_hemisphere(region, p.from), p.to);
    if (wedge.empty()) continue;
    const double e = above_altitude(wedge, p.altitude0_deg, n) - (cap ? 0.0 : above_altitude(wedge, p.altitude1_deg, n));
    if (e == 0) continue;
    double t = transmitting.transmittance;
    if (glazed) {
      // T at the part's centroid direction, ∫_part u dσ (the same two caps' integrals with n the
      // three axes), and its range over the wedge's directions (which contain the part's).
      const auto part = [&](const Vec3& axis) {
        return above_altitude(wedge, p.altitude0_deg, axis) - (cap ? 0.0 : above_altitude(wedge, p.altitude1_deg, axis));
      };
      const Vec3 centroid{part({1, 0, 0}), part({0, 1, 0}), part({0, 0, 1})};
      const auto T = [&](double mu) { return evaluate_polynomial(transmitting.angular_transmittance, std::abs(mu)); };
      t = norm(centroid) > 0 ? T(dot(pane, normalized(centroid))) : 0.0;
      auto [c0, c1] = cosine_range(wedge, pane);
      if (c1 <= 0) std::swap(c0, c1), c0 = -c0, c1 = -c1;
      const double t0 = T(std::clamp(c0, 0.0, 1.0)), t1 = T(std::clamp(c1, 0.0, 1.0));
      if (t > 0) spread = std::max(spread, 0.5 * std::abs(t1 - t0) / t);
    }
    coefficients[i] += sign * t * e;
  }
}

std::vector<double> patch_luminances(const std::vector<SkyPatch>& patches, const PerezSky& sky, double diffuse_horizontal_lux) {
  std::vector<double> L(patches.size());
  double horizontal = 0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    L[i] = sky.luminance_function(patches[i].centre);
    horizontal += L[i] * patches[i].solid_angle * patches[i].centre.z;
  }
  const double scale = horizontal > 0 ? diffuse_horizontal_lux / horizontal : 0;
  for (double& l : L) l *= scale;
  return L;
}

}  // namespace daylit
