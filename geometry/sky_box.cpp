#include "geometry/sky_box.hpp"

#include <numbers>
#include <utility>
#include <vector>

namespace daylit {

Scene sky_box_scene(const Scene& scene, Box around) {
  Scene box;
  for (const Polygon& p : scene.occluders) {
    box.occluders.push_back(p);
    for (const Vec3& v : p.vertices) around.add(v);
  }
  for (const Aperture& a : scene.apertures) {
    box.occluders.push_back(a.polygon);
    for (const Vec3& v : a.polygon.vertices) around.add(v);
  }
  if (around.empty()) around.add(Vec3{0, 0, 0});
  // A box edge is parallel to the scene's bounding-box edge it surrounds (often a wall's top); a
  // receiver in the plane through both sees them as one line, and there the box edge bounds the
  // region in the surface edge's stead: no region changes, but the gradient
  // (sky_component_with_gradient) takes the box edge's term for the surface's. With equal margins
  // that plane is the 45° one (a sensor 7 m from a courtyard wall 7 m below its top); margins in
  // irrational ratios put it where no receiver of round coordinates lies.
  const double m = 2 * around.longest_side() + 1;
  const Vec3 margin{m, m * (1 + 1 / std::numbers::pi), m * (1 + 1 / std::numbers::e)};
  const Vec3 lo = around.lo - margin, hi = around.hi + margin;
  const auto face = [&](std::vector<Vec3> v) {
    Polygon p;
    p.vertices = std::move(v);
    p.name = "sky box";
    box.apertures.push_back({p, 1.0});
  };
  // Each face wound so that its Newell normal points into the box.
  face({{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z}});
  face({{lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z}});
  face({{lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, lo.y, lo.z}});
  face({{lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}});
  face({{lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {lo.x, lo.y, hi.z}});
  face({{hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}});
  return box;
}

DirectSky::DirectSky(const Scene& model, const Box& around, GeometryMode mode, SubtractionOrder order)
    : scene(sky_box_scene(model, around)), engine(scene, mode, order, AperturesAre::independent) {}

std::unique_ptr<DirectSky> direct_sky(const Scene& scene, const std::vector<SensorGrid>& grids, GeometryMode mode,
                                      SubtractionOrder order) {
  bool any = false;
  Box around;
  for (const SensorGrid& g : grids) {
    any = any || g.sees_sky_directly;
    for (const Sensor& s : g.sensors) around.add(s.position);
  }
  if (!any) return nullptr;
  return std::make_unique<DirectSky>(scene, around, mode, order);
}

}  // namespace daylit
