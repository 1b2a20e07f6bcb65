#include "simulation/reflected_components.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <string>

#include <Eigen/Dense>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "geometry/box.hpp"
#include "geometry/closed_shells.hpp"
#include "geometry/ray_crossing.hpp"
#include "geometry/sky_box.hpp"
#include "illumination/moments.hpp"
#include "illumination/orthonormal_basis.hpp"
#include "simulation/dense_lu.hpp"
#include "simulation/element_transport.hpp"
#include "simulation/pane_transmittance.hpp"
#include "simulation/radiosity_solver.hpp"
#include "simulation/reciprocal_transport.hpp"
#include "simulation/sensor_loop.hpp"
#include "simulation/sunlit_elements.hpp"

namespace daylit {

namespace {

constexpr double kPi = std::numbers::pi;
// Distances to a plane below this fraction of the model's size count as on either side of it
// when deciding which sides are live: far above the roundoff of points on a surface (1e-16 of
// the model), far below any gap that separates surfaces.
constexpr double kSideMargin = 1e-9;

// ---- Apertures grouped by transmittance ------------------------------------------------------
// Light seen through an aperture is weighted by its transmittance; apertures that transmit alike
// share one "through" engine, so the engines grow with the kinds of glazing, not the windows.
// Glass transmits by the cosine μ of the direction about its pane's normal, so glazed apertures
// alike share a group only where their panes are parallel (either way round: T depends on |μ|).
// Grouped by material alone, a room's east window took μ about its south window's normal: the
// light of a building opposite the east window, seen through it nearly normally, was weighted as
// if at grazing incidence (ERC 34 % low on the grid's mean, 40 % at the sensors facing it,
// against a path tracer and a hand estimate).
struct ApertureGroup {
  std::vector<std::size_t> apertures;
  double transmittance = 1;
  std::vector<double> angular;  // T(μ) = Σ c_k μ^k, empty: constant
  Vec3 pane_normal{};           // unit; every glazed aperture of the group is parallel to it
  // T at the cosine μ (|μ|: both directions through the pane).
  double at(double mu) const {
    if (angular.empty()) return transmittance;
    mu = std::min(1.0, std::abs(mu));
    double t = 0;
    for (std::size_t k = angular.size(); k-- > 0;) t = t * mu + angular[k];
    return std::max(0.0, t);
  }
};

// Whether two unit normals are parallel or opposite to rounding: the panes' T(μ) then agree to
// about 1e-9 of the fit's slope.
bool parallel_panes(const Vec3& a, const Vec3& b) { return norm(cross(a, b)) <= 1e-9; }

std::vector<ApertureGroup> group_apertures(const Scene& scene) {
  std::vector<ApertureGroup> groups;
  for (std::size_t a = 0; a < scene.apertures.size(); ++a) {
    const Aperture& ap = scene.apertures[a];
    const Vec3 normal = normalized(newell_normal(ap.polygon.vertices));
    auto it = std::find_if(groups.begin(), groups.end(), [&](const ApertureGroup& g) {
      return g.transmittance == ap.transmittance && g.angular == ap.angular_transmittance &&
             (g.angular.empty() || parallel_panes(g.pane_normal, normal));
    });
    if (it == groups.end()) {
      groups.push_back({{}, ap.transmittance, ap.angular_transmittance, normal});
      it = groups.end() - 1;
    }
    it->apertures.push_back(a);
  }
  return groups;
}

Box box_of(const std::vector<Vec3>& v) {
  Box b;
  for (const Vec3& p : v) b.add(p);
  return b;
}

// The visible region above the horizon. A receiver facing straight down sees nothing above it;
// the engine, asked for that (its tangent plane the horizon turned over), returns loops of
// non-zero Lambert integral (measured: 0.32 sr on a box face), so the case is answered here.
SphericalRegion above_horizon(const VisibilityEngine& engine, const Vec3& x, const Vec3& n, std::size_t a,
                              VisibilityCounters& c, const VisibilityOptions& options) {
  if (n.x == 0 && n.y == 0 && n.z < 0) return {};
  return engine.visible_region(x, n, a, c, options);
}

// The same with the directions through other panes in front of the aperture (aperture_view).
ApertureView above_horizon_view(const VisibilityEngine& engine, const Vec3& x, const Vec3& n, std::size_t a,
                                VisibilityCounters& c, const VisibilityOptions& options) {
  if (n.x == 0 && n.y == 0 && n.z < 0) return {};
  return engine.aperture_view(x, n, a, c, options);
}

// An element seen from x through panes of transmittance T(u) along direction u: T taken at the
// centroid's direction, and its spread over the vertices' directions relative to it, which
// bounds the error of that (for T monotone over the element, as Fresnel's is).
struct ElementTransmittance {
  double value = 1, spread = 0;
};
template <class T>
ElementTransmittance element_transmittance(const RadiosityElement& el, const Vec3& x, const T& transmittance) {
  const double t = transmittance(normalized(el.point(1.0 / 3, 1.0 / 3, 1.0 / 3) - x));
  double lo = t, hi = t;
  for (const Vec3& v : el.vertices) {
    const double tv = transmittance(normalized(v - x));
    lo = std::min(lo, tv);
    hi = std::max(hi, tv);
  }
  return {t, t > 0 ? (hi - lo) / t : 0};
}

// ---- The transport model ----------------------------------------------------------------------
class Transport {
 public:
  // `coarsening`: the first mesh's elements are that many times the asked size. `every_side`:
  // solve both sides of every surface, whether light from them reaches a sensor or not.
  Transport(const Scene& scene, const std::vector<double>& reflectance, const VisibilityEngine& engine,
            const std::vector<const SensorGrid*>& grids, const ReflectionOptions& options, double coarsening,
            bool every_side)
      : scene_(scene), engine_(engine), options_(options), groups_(group_apertures(scene)),
        coarsening_(coarsening) {
    e_out_ = options.light ? options.light_horizontal : unobstructed_horizontal_irradiance(options.sky);
    ground_luminance_ = options.ground_reflectance * e_out_ / kPi;
    // What the mesh is graded towards: the apertures and the sensors.
    for (const Aperture& a : scene.apertures) aperture_boxes_.push_back(box_of(a.polygon.vertices));
    for (const SensorGrid* g : grids)
      for (const Sensor& s : g->sensors) sensor_box_.add(s.position);
    Box all = sensor_box_;
    for (const Polygon& p : scene.occluders)
      for (const Vec3& v : p.vertices) all.add(v);
    for (const Aperture& a : scene.apertures)
      for (const Vec3& v : a.polygon.vertices) all.add(v);
    scale_ = all.empty() ? 1 : std::max(all.longest_side(), 1e-300);
    // The reflecting surfaces: the opaque polygons, then every aperture's pane at index
    // (occluders + aperture), as the luminaire engines and the sky box list them as occluders, so
    // that one index names a surface's polygon in each. Panes of reflectance 0 are not meshed.
    polygons_ = scene.occluders;
    std::vector<double> reflect = reflectance;
    for (const Aperture& a : scene.apertures) {
      polygons_.push_back(a.polygon);
      reflect.push_back(a.reflectance);
    }
    mesh_ = mesh_surfaces(polygons_, reflect, [&](const RadiosityElement& e) { return max_edge(e); });
    if (every_side)
      live_.assign(mesh_.surfaces.size(), {true, true});
    else
      find_live_sides(grids);
    build_luminaire_engines();
    build_sky_box(all);
    if (options.sun && options.sun->direct_normal > 0 && options.sun->direction.z > 0) {
      sun_pieces_ = sun_blocker_pieces(polygons_);
      sunlit_ = std::make_unique<SunlitElements>(sun_pieces_, sun_transmittances(scene, options.sun->direction),
                                                 options.sun->direction, scale_);
    }
  }

  // The sun's first bounce at the three nodes of side `side` of element `el` (sunlit_elements.hpp:
  // the L² projection of the light over the element); zeros without a sun.
  std::array<double, 3> sun_first_bounce(const RadiosityElement& el, int side) const {
    if (!sunlit_) return {0, 0, 0};
    const Vec3 n = side == 0 ? el.normal : -1.0 * el.normal;
    std::array<double, 3> e = sunlit_->basis_integrals(el, n, mesh_.surfaces[el.surface].occluder);
    const double scale = sunlit_->node_factor(el, n, options_.sun->direct_normal);
    for (double& v : e) v *= scale;
    return e;
  }

  // Whether side `side` (0 along the surface's normal) of surface s can send light to a sensor,
  // directly or by way of other sides: the others are left out (no unknowns, no rows).
  bool live(std::size_t s, int side) const { return live_[s][std::size_t(side)]; }
  std::size_t live_side_count() const {
    std::size_t n = 0;
    for (const auto& l : live_) n += l[0] + l[1];
    return n;
  }

  const RadiosityMesh& mesh() const { return mesh_; }
  double scale() const { return scale_; }
  double e_out() const { return e_out_; }
  std::size_t unknowns() const { return 6 * mesh_.elements.size(); }
  std::size_t surface_count() const { return mesh_.surfaces.size(); }

  double max_edge(const RadiosityElement& e) const {
    const Vec3 c = e.point(1.0 / 3, 1.0 / 3, 1.0 / 3);
    double d = sensor_box_.empty() ? std::numeric_limits<double>::infinity() : sensor_box_.distance(c);
    for (const Box& b : aperture_boxes_) d = std::min(d, b.distance(c));
    if (!std::isfinite(d)) d = 0;
    return coarsening_ * std::max(options_.element_size, options_.grading * d);
  }

  // First bounce at (x, n) through the apertures: the sky above the horizon and the far ground
  // below it, times the transmittance. Glass: the sky and the ground (a uniform luminance) through
  // the glazing moments of T(μ), exact.
  struct ThroughApertures {
    double sky = 0, ground = 0;
  };
  // `own`: the occluder the receiver lies on (kNoOccluder for a sensor; occluders + a for a node
  // on aperture a's pane, which sees nothing through that aperture), which must not hide what
  // the receiver sees.
  ThroughApertures through_apertures(const Vec3& x, const Vec3& n, std::size_t own, bool with_sky,
                                     VisibilityCounters& c) const {
    ThroughApertures out;
    if (!with_sky && ground_luminance_ == 0) return out;
    VisibilityOptions full, half;
    full.clip_to_horizon = false;
    full.receiver_occluder = half.receiver_occluder = own;
    // What is seen through aperture `ap` in `all`, of which `above` is above the horizon.
    const auto add = [&](const Aperture& ap, const SphericalRegion& all, const SphericalRegion& above, double sign = 1) {
      const ThroughApertures before = out;
      const bool glazed = !ap.angular_transmittance.empty();
      const Vec3 pane = glazed ? normalized(newell_normal(ap.polygon.vertices)) : Vec3{};
      if (with_sky && !above.empty())
        out.sky += options_.light ? options_.light(above, n, &ap)
                   : glazed       ? sky_irradiance_through_glazing(above, n, options_.sky, pane, ap.angular_transmittance)
                                  : ap.transmittance * sky_irradiance(above, n, options_.sky);
      if (ground_luminance_ > 0) {
        // The far ground: what is seen through the aperture minus what of it is above the horizon.
        const auto seen = [&](const SphericalRegion& r) {
          if (r.empty()) return 0.0;
          return glazed ? sky_irradiance_through_glazing(r, n, SkyModel::uniform, pane, ap.angular_transmittance)
                        : ap.transmittance * lambert(r, n);
        };
        out.ground += ground_luminance_ * (seen(all) - seen(above));
      }
      if (sign != 1) {  // a count taken back (PaneView)
        out.sky = before.sky + sign * (out.sky - before.sky);
        out.ground = before.ground + sign * (out.ground - before.ground);
      }
    };
    for (std::size_t a = 0; a < engine_.aperture_count(); ++a) {
      if (own == scene_.occluders.size() + a) continue;  // a node on this pane: it is in the pane's plane
      // As in direct(): nothing of the aperture visible at all, nothing above the horizon.
      const ApertureView all = engine_.aperture_view(x, n, a, c, full);
      if (all.empty()) continue;
      const ApertureView above = above_horizon_view(engine_, x, n, a, c, half);
      if (!all.region.empty()) add(scene_.apertures[a], all.region, above.region);
      // Through other panes in front as well (pane_transmittance.hpp), pane set by pane set.
      for (const PaneView& behind : all.behind) {
        const auto it = std::find_if(above.behind.begin(), above.behind.end(),
                                     [&](const PaneView& b) { return b.panes == behind.panes; });
        for (const PaneTerm& term : pane_terms(scene_, a, behind))
          add(term.transmittance.combined, behind.region, it == above.behind.end() ? SphericalRegion{} : it->region, term.sign);
      }
    }
    return out;
  }

  // The sky and far ground seen directly (not through an aperture): the six inward faces of the
  // box around the model as apertures, every opaque and aperture polygon as an occluder
  // (geometry/sky_box.hpp). `total`: both; `ground`: the far ground's part; `empty`: nothing seen.
  struct Direct {
    double total = 0, ground = 0;
    bool empty = true;
    bool enclosed = false;  // empty, known from the closed shells without the box's queries
  };
  Direct direct(const Vec3& x, const Vec3& n, std::size_t own, VisibilityCounters& c) const {
    Direct out;
    if (closed_.encloses(x, n, own)) {
      out.enclosed = true;
      return out;
    }
    VisibilityOptions full, half;
    full.clip_to_horizon = false;
    full.receiver_occluder = half.receiver_occluder = own;  // the box's occluders start with the scene's
    for (std::size_t f = 0; f < sky_box_->aperture_count(); ++f) {
      // The region above the horizon is part of the whole one: where that is empty (every
      // receiver inside a closed room), the second query is left out, exactly.
      const SphericalRegion all = sky_box_->visible_region(x, n, f, c, full);
      if (all.empty()) continue;
      out.empty = false;
      const SphericalRegion above = above_horizon(*sky_box_, x, n, f, c, half);
      if (!above.empty()) out.total += options_.light ? options_.light(above, n, nullptr) : sky_irradiance(above, n, options_.sky);
      if (ground_luminance_ > 0) {
        const double ground = ground_luminance_ * (lambert(all, n) - (above.empty() ? 0.0 : lambert(above, n)));
        out.total += ground;
        out.ground += ground;
      }
    }
    return out;
  }

  // What (x, n) sees of the sky and far ground, view by view: through each aperture, then directly
  // (the sky box's faces), as through_apertures() and direct() integrate them, kept as regions so
  // that any light can be put on them later (reflection_operator).
  std::vector<LightView> views(const Vec3& x, const Vec3& n, std::size_t own, bool with_direct,
                               VisibilityCounters& c) const {
    std::vector<LightView> out;
    VisibilityOptions full, half;
    full.clip_to_horizon = false;
    full.receiver_occluder = half.receiver_occluder = own;
    // One view: `all` seen through `ap` (nullptr: directly), `above` of it above the horizon;
    // `through`, where panes lie in front of the aperture, their combined transmittance.
    const auto add_view = [&](SphericalRegion all, SphericalRegion above, const Aperture* ap, std::int32_t index,
                              std::shared_ptr<const Aperture> through, std::vector<std::uint32_t> panes, double sign) {
      if (all.empty()) return;
      LightView v;
      v.aperture = index;
      v.through = std::move(through);
      v.panes = std::move(panes);
      v.sign = sign;
      v.above = std::move(above);
      const bool glazed = ap != nullptr && !ap->angular_transmittance.empty();
      const Vec3 pane = glazed ? normalized(newell_normal(ap->polygon.vertices)) : Vec3{};
      const auto seen = [&](const SphericalRegion& r) {
        if (r.empty()) return 0.0;
        return glazed ? sky_irradiance_through_glazing(r, n, SkyModel::uniform, pane, ap->angular_transmittance)
                      : (ap != nullptr ? ap->transmittance : 1.0) * lambert(r, n);
      };
      v.ground = seen(all) - seen(v.above);
      if (v.above.empty() && v.ground == 0) return;
      out.push_back(std::move(v));
    };
    for (std::size_t a = 0; a < engine_.aperture_count(); ++a) {
      if (own == scene_.occluders.size() + a) continue;  // a node on this pane (through_apertures)
      ApertureView all = engine_.aperture_view(x, n, a, c, full);
      if (all.empty()) continue;
      ApertureView above = above_horizon_view(engine_, x, n, a, c, half);
      add_view(std::move(all.region), std::move(above.region), &scene_.apertures[a], std::int32_t(a), nullptr, {}, 1.0);
      for (PaneView& behind : all.behind) {
        const auto it = std::find_if(above.behind.begin(), above.behind.end(),
                                     [&](const PaneView& b) { return b.panes == behind.panes; });
        for (PaneTerm& term : pane_terms(scene_, a, behind)) {
          auto combined = std::make_shared<const Aperture>(std::move(term.transmittance.combined));
          // The term's own pane (its aperture) keeps the window group of the light: the last pane's.
          add_view(behind.region, it == above.behind.end() ? SphericalRegion{} : it->region, combined.get(),
                   std::int32_t(term.aperture), combined, std::move(term.panes), term.sign);
        }
      }
    }
    if (with_direct && !closed_.encloses(x, n, own))
      for (std::size_t f = 0; f < sky_box_->aperture_count(); ++f) {
        SphericalRegion all = sky_box_->visible_region(x, n, f, c, full);
        if (!all.empty()) add_view(std::move(all), above_horizon(*sky_box_, x, n, f, c, half), nullptr, -1, nullptr, {}, 1.0);
      }
    return out;
  }

  // Every element's coefficients at (x, n): sink(element, side, c, through, spread), c such that
  // the irradiance is Σ_k c_k M_k (through: already weighted by the transmittance, as the
  // difference of the two occluder sets), spread: the relative spread of T(μ) over the element's
  // directions (glass), for the error estimate. `mesh`: this model's mesh or an earlier one of
  // the same surfaces.
  template <class Sink>
  void transport(const RadiosityMesh& mesh, const Vec3& x, const Vec3& n, std::size_t own_surface,
                 VisibilityCounters& counters, Sink&& sink, const std::vector<bool>* only = nullptr) const {
    const RadiosityMesh* meshes[] = {&mesh};
    transport(
        meshes, x, n, own_surface, counters,
        [&](std::size_t, std::size_t e, int side, const std::array<double, 3>& c, bool through, double spread) {
          sink(e, side, c, through, spread);
        },
        only);
  }

  // The same for several meshes of the same surfaces at once (a coarse mesh and its split, for the
  // error estimate): sink(m, element, side, c, through, spread) for meshes[m]. What is visible of a
  // surface does not depend on how it is meshed, so each surface's regions are found once.
  // `only`, where given: the surfaces s with (*only)[s] alone (a row brought up to date after
  // some surfaces were refined).
  template <std::size_t N, class Sink>
  void transport(const RadiosityMesh* const (&meshes)[N], const Vec3& x, const Vec3& n, std::size_t own_surface,
                 VisibilityCounters& counters, Sink&& sink, const std::vector<bool>* only = nullptr) const {
    // The surface is a luminaire: nothing beyond its plane hides it, and it does not hide itself.
    // Nor does the receiver's own polygon, in whose plane it lies: a node is a rounding off it,
    // and one behind it would otherwise see nothing but its own polygon (VisibilityOptions).
    VisibilityOptions opt;
    opt.clip_to_horizon = false;
    opt.occluders_beyond = false;
    const std::vector<RadiositySurface>& surfaces = meshes[0]->surfaces;
    const std::size_t receiver = own_surface < surfaces.size() ? surfaces[own_surface].occluder : VisibilityOptions::kNoOccluder;
    opt.receiver_occluder = receiver;
    for (std::size_t s = 0; s < surfaces.size(); ++s) {
      if (s == own_surface || (only != nullptr && !(*only)[s])) continue;
      const RadiositySurface& surf = surfaces[s];
      const double facing = dot(surf.normal, x - surf.point);
      // In the surface's plane, up to roundoff (coplanar surfaces): nothing passes between them.
      if (std::abs(facing) <= kSideMargin * scale_) continue;
      const int side = facing > 0 ? 0 : 1;
      if (!live_[s][std::size_t(side)]) continue;  // never so for a receiver that is live itself
      const Polygon& poly = polygons_[surf.occluder];
      bool in_front = false;
      for (const Vec3& v : poly.vertices) in_front |= dot(n, v - x) > 0;
      if (!in_front) continue;
      opt.excluded_occluder = surf.occluder;
      const std::uint64_t clipped = counters.pairs_clipped;
      const SphericalRegion inside = inside_->visible_region(x, n, s, counters, opt);
      const bool inside_free = counters.pairs_clipped == clipped;
      // Seen whole (nothing clipped): the elements' shared edges are computed once.
      thread_local std::vector<std::array<double, 3>> inside_cs[N];
      for (std::size_t m = 0; m < N; ++m) {
        const RadiosityMesh& mesh = *meshes[m];
        const std::vector<std::size_t>& elements = mesh.surfaces[s].elements;
        std::vector<std::array<double, 3>>& inside_c = inside_cs[m];
        if (inside.empty()) {
          inside_c.assign(elements.size(), {0.0, 0.0, 0.0});
        } else if (inside_free) {
          unobstructed_surface_coefficients(mesh, s, x, n, inside_c);
        } else {
          inside_c.resize(elements.size());
          thread_local SphericalRegion part;
          for (std::size_t i = 0; i < elements.size(); ++i) {
            const RadiosityElement& el = mesh.elements[elements[i]];
            element_region(inside, false, el, x, n, part);
            inside_c[i] = element_irradiance_coefficients(part, el, x, n);
          }
        }
        for (std::size_t i = 0; i < elements.size(); ++i) sink(m, elements[i], side, inside_c[i], false, 0.0);
      }
      // Through each group of apertures: only where one of its apertures may stand between x
      // and the surface (boxes, conservatively: a group that cannot is left out exactly).
      Box reach = surf_boxes_[s];
      reach.add(x);
      // Pairs of groups whose panes may both lie on one line from x to the surface (an interior
      // window, then the façade): their directions are seen by neither group's view (each
      // takes the other's panes as opaque) and are added below by the pair's own.
      thread_local std::vector<std::pair<std::size_t, std::size_t>> pairs;
      series_pairs(x, poly, reach, pairs);
      // Triples of groups each two of which are such a pair: a line may cross panes of all three
      // (a partition, another, then the façade), added likewise by the triple's own view.
      thread_local std::vector<std::array<std::size_t, 3>> triples;
      series_triples(pairs, triples);
      // Sets of four or more such groups, each two a pair (series_cliques), by their own views.
      thread_local std::vector<std::vector<std::size_t>> cliques;
      series_cliques(pairs, triples, cliques);
      thread_local std::vector<std::vector<std::array<double, 3>>> raw[N];  // [m][g][i]: E(through g) per element
      thread_local std::vector<std::vector<std::array<double, 3>>> raw_pair[N];  // [m][p][i]: E(through pair p)
      thread_local std::vector<std::vector<std::array<double, 3>>> raw_triple[N];  // [m][t][i]: E(past triple t)
      thread_local std::vector<std::vector<std::array<double, 3>>> raw_clique[N];  // [m][q][i]: E(past clique q)
      if (!cliques.empty())
        for (std::size_t m = 0; m < N; ++m) {
          raw_triple[m].resize(triples.size());
          for (auto& r : raw_triple[m]) r.assign(meshes[m]->surfaces[s].elements.size(), {0.0, 0.0, 0.0});
          raw_clique[m].resize(cliques.size());
          for (auto& r : raw_clique[m]) r.assign(meshes[m]->surfaces[s].elements.size(), {0.0, 0.0, 0.0});
        }
      if (!pairs.empty())
        for (std::size_t m = 0; m < N; ++m) {
          raw[m].resize(groups_.size());
          for (auto& r : raw[m]) r.assign(meshes[m]->surfaces[s].elements.size(), {0.0, 0.0, 0.0});
        }
      if (!triples.empty())
        for (std::size_t m = 0; m < N; ++m) {
          raw_pair[m].resize(pairs.size());
          for (auto& r : raw_pair[m]) r.assign(meshes[m]->surfaces[s].elements.size(), {0.0, 0.0, 0.0});
        }
      // What a view past the panes of several groups (pair_view, group_set_view) shows of the
      // surface; `free`: nothing in it was clipped.
      const auto seen_past = [&](const PairView& view, bool& free) {
        VisibilityOptions past = opt;
        past.excluded_occluder = view_occluder(view.index, surf.occluder);
        past.receiver_occluder = view_occluder(view.index, receiver);
        const std::uint64_t clipped = counters.pairs_clipped;
        SphericalRegion region = view.engine->visible_region(x, n, s, counters, past);
        free = counters.pairs_clipped == clipped;
        return region;
      };
      // Every element of the surface (in each mesh) of which `region` shows some part:
      // f(m, i, element index, element, c), c its coefficients over that part (`free`: the region
      // is the surface's whole, unclipped).
      const auto for_each_seen = [&](const SphericalRegion& region, bool free, auto&& f) {
        for (std::size_t m = 0; m < N; ++m) {
          const RadiosityMesh& mesh = *meshes[m];
          const std::vector<std::size_t>& elements = mesh.surfaces[s].elements;
          for (std::size_t i = 0; i < elements.size(); ++i) {
            const RadiosityElement& el = mesh.elements[elements[i]];
            thread_local SphericalRegion part;
            element_region(region, free, el, x, n, part);
            if (part.empty()) continue;
            f(m, i, elements[i], el, element_irradiance_coefficients(part, el, x, n));
          }
        }
      };
      for (std::size_t g = 0; g < groups_.size(); ++g) {
        bool may_cross = false;
        for (std::size_t a : groups_[g].apertures) may_cross |= reach.meets(aperture_boxes_[a], 1e-9 * scale_);
        if (!may_cross) continue;
        const std::uint64_t clipped_t = counters.pairs_clipped;
        VisibilityOptions through_opt = opt;  // the panes' indices as this engine lists them
        through_opt.excluded_occluder = through_occluder(g, surf.occluder);
        through_opt.receiver_occluder = through_occluder(g, receiver);
        const SphericalRegion through = through_[g].visible_region(x, n, s, counters, through_opt);
        if (through.empty()) continue;
        const bool through_free = counters.pairs_clipped == clipped_t;
        // Both seen whole: the same region, nothing seen through the group.
        if (through_free && inside_free && !inside.empty()) {
          if (!pairs.empty())
            for (std::size_t m = 0; m < N; ++m) raw[m][g] = inside_cs[m];
          continue;
        }
        const ApertureGroup& group = groups_[g];
        for_each_seen(through, through_free, [&](std::size_t m, std::size_t i, std::size_t e, const RadiosityElement& el,
                                                 std::array<double, 3> c) {
          // What is seen inside, by the same function as what is seen through, so that where the
          // two regions are the same (nothing of the group in the way) the difference is 0
          // exactly: inside_c[i] where it came from that function, again where the shared edges
          // gave it.
          const std::array<double, 3> c_in =
              !inside_free || inside.empty()
                  ? inside_cs[m][i]
                  : element_irradiance_coefficients(element_region(inside, true, el, x, n), el, x, n);
          const ElementTransmittance ts =
              group.angular.empty()
                  ? ElementTransmittance{group.transmittance, 0}
                  : element_transmittance(el, x, [&](const Vec3& u) { return group.at(dot(u, group.pane_normal)); });
          const double t = ts.value, spread = ts.spread;
          if (!pairs.empty()) raw[m][g][i] = c;
          for (int k = 0; k < 3; ++k) c[k] = t * (c[k] - c_in[k]);
          sink(m, e, side, c, true, spread);
        });
      }
      // Through panes of two groups: with both transparent, what neither alone nor nothing
      // shows, E(g, h) − E(g) − E(h) + E(none), under T_g·T_h (each at the centroid's direction
      // about its own pane; the product's spread over the vertices' directions as for one).
      for (std::size_t p = 0; p < pairs.size(); ++p) {
        const std::size_t g = pairs[p].first, h = pairs[p].second;  // not a structured binding: the lambdas below use them
        bool both_free = false;
        const SphericalRegion both = seen_past(pair_view(g, h), both_free);
        if (both.empty()) continue;
        // Seen whole, as inside: the four regions are one, nothing passes both groups.
        if (both_free && inside_free && !inside.empty()) {
          if (!triples.empty())
            for (std::size_t m = 0; m < N; ++m) raw_pair[m][p] = inside_cs[m];
          continue;
        }
        const std::array<std::size_t, 2> both_groups{g, h};
        const auto product = [&](const Vec3& u) { return transmittance_product(both_groups, u); };
        for_each_seen(both, both_free, [&](std::size_t m, std::size_t i, std::size_t e, const RadiosityElement& el,
                                           std::array<double, 3> c) {
          if (!triples.empty()) raw_pair[m][p][i] = c;
          const auto [t, spread] = element_transmittance(el, x, product);
          const std::array<double, 3>& c_in = inside_cs[m][i];
          for (int k = 0; k < 3; ++k) c[k] = t * (c[k] - raw[m][g][i][k] - raw[m][h][i][k] + c_in[k]);
          sink(m, e, side, c, true, spread);
        });
      }
      // Through panes of three groups: E(g, h, k) − the three pairs' + the three groups' − E(none)
      // (inclusion and exclusion: what passes all three and no other), under T_g·T_h·T_k.
      for (std::size_t tr = 0; tr < triples.size(); ++tr) {
        const std::array<std::size_t, 3>& triple = triples[tr];
        bool all3_free = false;
        const SphericalRegion all3 = seen_past(group_set_view({triple.begin(), triple.end()}), all3_free);
        if (all3.empty()) continue;
        if (all3_free && inside_free && !inside.empty()) {  // the eight regions are one
          if (!cliques.empty())
            for (std::size_t m = 0; m < N; ++m) raw_triple[m][tr] = inside_cs[m];
          continue;
        }
        const auto pair_at = [&](std::size_t a, std::size_t b) {
          return std::size_t(std::find(pairs.begin(), pairs.end(), std::pair{a, b}) - pairs.begin());
        };
        const std::size_t g = triple[0], h = triple[1], k3 = triple[2];
        const std::size_t gh = pair_at(g, h), gk = pair_at(g, k3), hk = pair_at(h, k3);
        const auto product = [&](const Vec3& u) { return transmittance_product(triple, u); };
        for_each_seen(all3, all3_free, [&](std::size_t m, std::size_t i, std::size_t e, const RadiosityElement& el,
                                           std::array<double, 3> c) {
          if (!cliques.empty()) raw_triple[m][tr][i] = c;
          const auto [t, spread] = element_transmittance(el, x, product);
          const std::array<double, 3>& c_in = inside_cs[m][i];
          for (int k = 0; k < 3; ++k)
            c[k] = t * (c[k] - raw_pair[m][gh][i][k] - raw_pair[m][gk][i][k] - raw_pair[m][hk][i][k] + raw[m][g][i][k] +
                        raw[m][h][i][k] + raw[m][k3][i][k] - c_in[k]);
          sink(m, e, side, c, true, spread);
        });
      }
      // Through panes of four or more groups S: Σ over the subsets T of S of (−1)^{|S|−|T|} E(T)
      // (inclusion and exclusion, as above: what passes every group of S and no other), under
      // the product of their T; E(T) by the size of T: inside, raw, raw_pair, raw_triple,
      // raw_clique (the cliques come by size, so every smaller one is found first).
      for (std::size_t q = 0; q < cliques.size(); ++q) {
        const std::vector<std::size_t>& set = cliques[q];
        bool all_free = false;
        const SphericalRegion all = seen_past(group_set_view(set), all_free);
        if (all.empty()) continue;
        if (all_free && inside_free && !inside.empty()) {  // every subset's region is the same
          for (std::size_t m = 0; m < N; ++m) raw_clique[m][q] = inside_cs[m];
          continue;
        }
        // Each proper subset's sign and coefficients, per mesh.
        thread_local std::vector<std::pair<double, const std::vector<std::array<double, 3>>*>> terms[N];
        const std::size_t full = (std::size_t(1) << set.size()) - 1;
        for (std::size_t m = 0; m < N; ++m) {
          terms[m].clear();
          for (std::size_t mask = 0; mask < full; ++mask) {
            std::vector<std::size_t> subset;
            for (std::size_t b = 0; b < set.size(); ++b)
              if (mask & (std::size_t(1) << b)) subset.push_back(set[b]);
            const double sign = (set.size() - subset.size()) % 2 == 0 ? 1.0 : -1.0;
            const std::vector<std::array<double, 3>>* e = nullptr;
            if (subset.empty()) {
              e = &inside_cs[m];
            } else if (subset.size() == 1) {
              e = &raw[m][subset[0]];
            } else if (subset.size() == 2) {
              e = &raw_pair[m][std::size_t(std::find(pairs.begin(), pairs.end(), std::pair{subset[0], subset[1]}) - pairs.begin())];
            } else if (subset.size() == 3) {
              const std::array<std::size_t, 3> key{subset[0], subset[1], subset[2]};
              e = &raw_triple[m][std::size_t(std::find(triples.begin(), triples.end(), key) - triples.begin())];
            } else {
              e = &raw_clique[m][std::size_t(std::find(cliques.begin(), cliques.end(), subset) - cliques.begin())];
            }
            terms[m].emplace_back(sign, e);
          }
        }
        const auto product = [&](const Vec3& u) { return transmittance_product(set, u); };
        for_each_seen(all, all_free, [&](std::size_t m, std::size_t i, std::size_t e, const RadiosityElement& el,
                                         std::array<double, 3> c) {
          raw_clique[m][q][i] = c;
          const auto [t, spread] = element_transmittance(el, x, product);
          for (const auto& [sign, coefficients] : terms[m])
            for (int k = 0; k < 3; ++k) c[k] += sign * (*coefficients)[i][k];
          for (int k = 0; k < 3; ++k) c[k] *= t;
          sink(m, e, side, c, true, spread);
        });
      }
    }
  }

  // The product of the groups' transmittances along u, each at the cosine about its own pane.
  template <class Groups>
  double transmittance_product(const Groups& groups, const Vec3& u) const {
    double t = 1;
    for (const std::size_t g : groups) t *= groups_[g].at(dot(u, groups_[g].pane_normal));
    return t;
  }

  // The sets of four or more groups each two of which are in `pairs` (series_pairs, sorted), by
  // size and then in order: each extends one of the size below (from the triples) by a later
  // group in series with all of its members. A line crosses panes of all of them only then.
  static void series_cliques(const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
                             const std::vector<std::array<std::size_t, 3>>& triples,
                             std::vector<std::vector<std::size_t>>& out) {
    out.clear();
    if (triples.size() < 4) return;  // four groups in series make four triples
    const auto has = [&](std::size_t a, std::size_t b) {
      return std::find(pairs.begin(), pairs.end(), std::pair{a, b}) != pairs.end();
    };
    std::vector<std::vector<std::size_t>> level;
    for (const auto& t : triples) level.push_back({t.begin(), t.end()});
    while (!level.empty()) {
      std::vector<std::vector<std::size_t>> next;
      for (const std::vector<std::size_t>& set : level)
        for (const auto& [g, k] : pairs) {
          if (g != set.back()) continue;  // k > every member, in series with the last...
          bool all = true;                // ...and with every other
          for (std::size_t i = 0; i + 1 < set.size() && all; ++i) all = has(set[i], k);
          if (!all) continue;
          next.push_back(set);
          next.back().push_back(k);
        }
      out.insert(out.end(), next.begin(), next.end());
      level = std::move(next);
    }
  }

  // The triples (g < h < k) all three of whose pairs are in `pairs` (series_pairs, sorted):
  // a line crosses panes of three groups only if it crosses panes of each two of them.
  static void series_triples(const std::vector<std::pair<std::size_t, std::size_t>>& pairs,
                             std::vector<std::array<std::size_t, 3>>& out) {
    out.clear();
    if (pairs.size() < 3) return;
    const auto has = [&](std::size_t a, std::size_t b) {
      return std::find(pairs.begin(), pairs.end(), std::pair{a, b}) != pairs.end();
    };
    for (const auto& [g, h] : pairs)
      for (const auto& [a, k] : pairs)
        if (a == h && has(g, k)) out.push_back({g, h, k});
  }

  // The pairs of groups (g < h) with panes a of g and b of h that may both stand between x and
  // the polygon: each box meets the reach, each plane has x strictly on one side and a vertex of
  // the polygon strictly on the other, and one pane has a vertex strictly beyond the other's
  // plane from x (else no line from x crosses both). Conservative: a pair kept here may still
  // show nothing, which the pair's view finds exactly.
  void series_pairs(const Vec3& x, const Polygon& poly, const Box& reach,
                    std::vector<std::pair<std::size_t, std::size_t>>& out) const {
    out.clear();
    if (groups_.size() < 2) return;
    const double margin = kSideMargin * scale_;
    const auto beyond = [&](std::size_t a, const std::vector<Vec3>& vertices) {
      const double side_x = dot(pane_normals_[a], x - pane_points_[a]);
      if (std::abs(side_x) <= margin) return false;
      for (const Vec3& v : vertices) {
        const double side_v = dot(pane_normals_[a], v - pane_points_[a]);
        if (std::abs(side_v) > margin && (side_v > 0) != (side_x > 0)) return true;
      }
      return false;
    };
    thread_local std::vector<std::vector<std::size_t>> crossing;
    crossing.assign(groups_.size(), {});
    std::size_t groups_crossed = 0;
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      for (std::size_t a : groups_[g].apertures)
        if (reach.meets(aperture_boxes_[a], 1e-9 * scale_) && beyond(a, poly.vertices)) crossing[g].push_back(a);
      groups_crossed += !crossing[g].empty();
    }
    if (groups_crossed < 2) return;
    for (std::size_t g = 0; g < groups_.size(); ++g)
      for (std::size_t h = g + 1; h < groups_.size(); ++h) {
        bool series = false;
        for (std::size_t a : crossing[g]) {
          for (std::size_t b : crossing[h]) {
            series = beyond(a, scene_.apertures[b].polygon.vertices) || beyond(b, scene_.apertures[a].polygon.vertices);
            if (series) break;
          }
          if (series) break;
        }
        if (series) out.emplace_back(g, h);
      }
  }

  // The elements flagged split in four at their edges' midpoints; returns refine_mesh's parents.
  std::vector<std::size_t> refine(const std::vector<bool>& split) {
    std::vector<std::size_t> parent = refine_mesh(mesh_, split);
    remesh_boxes();
    return parent;
  }
  std::vector<std::size_t> split_all() { return refine(std::vector<bool>(mesh_.elements.size(), true)); }

  void remesh_boxes() {
    surf_boxes_.clear();
    for (const auto& s : mesh_.surfaces) surf_boxes_.push_back(box_of(polygons_[s.occluder].vertices));
  }

 private:
  // The live sides, by a closure over surfaces that only uses the two tests transport() applies
  // before it asks for visibility (the receiver on the source's side of its plane, a vertex of
  // the source in front of the receiver's tangent plane), each made conservative: a receiver point
  // lies inside its surface's polygon, so a sign it has at some point is had by some vertex; and
  // distances within kSideMargin of a plane count as either sign where roundoff in the points
  // could give transport() either, so that it never asks for a side found dead. Seeds: the
  // sensors. Since every live receiver's sources are live, the live unknowns take the values of
  // the whole system (to roundoff: the solver's stopping test looks at the largest exitance);
  // the dead sides (the outside of a room's walls, for one) neither receive from nor send to them.
  void find_live_sides(const std::vector<const SensorGrid*>& grids) {
    const std::size_t ns = mesh_.surfaces.size();
    live_.assign(ns, {false, false});
    const double margin = kSideMargin * scale_;
    // Which sides of surface t a receiver at x, facing n, may receive from.
    const auto sides_seen = [&](std::size_t t, const std::vector<Vec3>& xs, const Vec3& n, std::size_t own,
                                std::array<bool, 2>& seen) {
      if (t == own) return;
      const RadiositySurface& surf = mesh_.surfaces[t];
      const Polygon& poly = polygons_[surf.occluder];
      bool in_front = false;
      for (const Vec3& v : poly.vertices)
        for (const Vec3& x : xs) in_front |= dot(n, v - x) > -margin;
      if (!in_front) return;
      // A sensor within the margin of the plane may see either side. A surface's receiver points
      // lie strictly inside its elements, so where the surface touches the plane only along an
      // edge or at a vertex (a wall meeting the floor) they are all on the side of its other
      // vertices; only a surface lying in the plane may see either side.
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const Vec3& x : xs) {
        const double facing = dot(surf.normal, x - surf.point);
        lo = std::min(lo, facing);
        hi = std::max(hi, facing);
      }
      const bool point = xs.size() == 1, in_plane = hi <= margin && lo >= -margin;
      seen[0] = seen[0] || (point ? hi > -margin : hi > margin || in_plane);
      seen[1] = seen[1] || (point ? lo < margin : lo < -margin || in_plane);
    };
    std::vector<std::pair<std::size_t, int>> todo;
    // Back to back: where another surface lies in the same plane facing the other way over this
    // one's centroid (the two faces of one interior wall, as Honeybee writes adjacent rooms),
    // this surface's back is the other's front. Solving both would count that light twice (the
    // luminaire visibility does not let a polygon in the luminaire's own plane hide it), so the
    // back side is left out, and the front of the other carries it.
    std::vector<bool> back_covered(ns, false);
    for (std::size_t s = 0; s < ns; ++s)
      for (std::size_t t = 0; t < ns && !back_covered[s]; ++t) back_covered[s] = t != s && covers_back(t, s, margin);
    const auto mark = [&](std::size_t t, const std::array<bool, 2>& seen) {
      for (int side = 0; side < 2; ++side)
        if (seen[std::size_t(side)] && !live_[t][std::size_t(side)] && (side == 0 || !back_covered[t])) {
          live_[t][std::size_t(side)] = true;
          todo.emplace_back(t, side);
        }
    };
    for (const SensorGrid* g : grids)
      for (const Sensor& sensor : g->sensors)
        for (std::size_t t = 0; t < ns; ++t) {
          std::array<bool, 2> seen{false, false};
          sides_seen(t, {sensor.position}, sensor.normal, ns, seen);
          mark(t, seen);
        }
    while (!todo.empty()) {
      const auto [s, side] = todo.back();
      todo.pop_back();
      const RadiositySurface& surf = mesh_.surfaces[s];
      const Vec3 n = side == 0 ? surf.normal : -1.0 * surf.normal;
      const std::vector<Vec3>& xs = polygons_[surf.occluder].vertices;
      for (std::size_t t = 0; t < ns; ++t) {
        std::array<bool, 2> seen{false, false};
        sides_seen(t, xs, n, s, seen);
        mark(t, seen);
      }
    }
  }

  // Whether surface t lies in surface s's plane, facing the other way, over s's area centroid.
  bool covers_back(std::size_t t, std::size_t s, double margin) const {
    const RadiositySurface &a = mesh_.surfaces[s], &b = mesh_.surfaces[t];
    // A pane is no wall face: a window in its wall's plane covers the wall's hole, not its back.
    if (a.occluder >= scene_.occluders.size() || b.occluder >= scene_.occluders.size()) return false;
    if (!(dot(a.normal, b.normal) < -1 + 1e-12)) return false;
    const Polygon& pb = polygons_[b.occluder];
    for (const Vec3& v : pb.vertices)
      if (std::abs(dot(a.normal, v - a.point)) > margin) return false;
    // The centroid of s's elements (area-weighted), tested against t's polygon by crossings in
    // its plane (seams of holes cancel).
    Vec3 c{0, 0, 0};
    double area = 0;
    for (std::size_t e : a.elements) {
      const RadiosityElement& el = mesh_.elements[e];
      c = c + el.area * el.point(1.0 / 3, 1.0 / 3, 1.0 / 3);
      area += el.area;
    }
    if (!(area > 0)) return false;
    c = c / area;
    Vec3 e1, e2;
    orthonormal_basis(b.normal, e1, e2);
    const double cx = dot(c, e1), cy = dot(c, e2);
    bool inside = false;
    const std::size_t m = pb.vertices.size();
    for (std::size_t i = 0, j = m - 1; i < m; j = i++) {
      const double xi = dot(pb.vertices[i], e1), yi = dot(pb.vertices[i], e2);
      const double xj = dot(pb.vertices[j], e1), yj = dot(pb.vertices[j], e2);
      if ((yi > cy) != (yj > cy) && cx < (xj - xi) * (cy - yi) / (yj - yi) + xi) inside = !inside;
    }
    return inside;
  }

  // The surfaces as luminaires (aperture s: surface s), seen past the opaque polygons, which keep
  // their indices in Scene::occluders so that the luminaire's own can be excluded by index:
  // `inside_` also past every aperture (what is seen inside), `through_[g]` past the apertures
  // of the other groups only, so that through_[g] − inside_ is what is seen through group g, and
  // a pair's view past the panes of two groups (pair_view). The cut to the receiver's side of the
  // luminaire's plane is the engine's, exact (VisibilityOptions::occluders_beyond), so one engine
  // serves every surface and both sides.
  void build_luminaire_engines() {
    Scene inside = luminaire_scene();
    for (const Aperture& a : scene_.apertures) inside.occluders.push_back(a.polygon);
    inside_ = std::make_unique<VisibilityEngine>(inside, options_.mode, engine_.order(), AperturesAre::independent);
    for (std::size_t g = 0; g < groups_.size(); ++g) through_.push_back(view_engine({g}, through_index_.emplace_back()));
    const std::size_t n = groups_.size();
    pair_views_ = std::vector<PairView>(n > 1 ? n * (n - 1) / 2 : 0);
    for (const Aperture& a : scene_.apertures) {
      pane_normals_.push_back(normalized(newell_normal(a.polygon.vertices)));
      pane_points_.push_back(a.polygon.vertices.front());
    }
    remesh_boxes();
  }

  // The surfaces as luminaires past the opaque polygons: every view's common part.
  Scene luminaire_scene() const {
    Scene base;
    for (const RadiositySurface& s : mesh_.surfaces) base.apertures.push_back({polygons_[s.occluder], 1.0});
    base.occluders = scene_.occluders;
    return base;
  }

  // The engine that sees past the panes of the groups `transparent`, the other groups' panes
  // being occluders; `index`: per aperture, its occluder index there (none where transparent).
  VisibilityEngine view_engine(const std::vector<std::size_t>& transparent, std::vector<std::size_t>& index) const {
    Scene t = luminaire_scene();
    index.assign(scene_.apertures.size(), VisibilityOptions::kNoOccluder);
    for (std::size_t h = 0; h < groups_.size(); ++h)
      if (std::find(transparent.begin(), transparent.end(), h) == transparent.end())
        for (std::size_t a : groups_[h].apertures) {
          index[a] = t.occluders.size();
          t.occluders.push_back(scene_.apertures[a].polygon);
        }
    return VisibilityEngine(t, options_.mode, engine_.order(), AperturesAre::independent);
  }

  // The view past the panes of groups g < h, built on first use: most pairs of a model never
  // have panes on one line (series_pairs), and each view is an engine over the whole scene.
  struct PairView {
    std::once_flag built;
    std::unique_ptr<VisibilityEngine> engine;
    std::vector<std::size_t> index;
  };
  const PairView& pair_view(std::size_t g, std::size_t h) const {
    PairView& view = pair_views_[h * (h - 1) / 2 + g];
    std::call_once(view.built, [&] { view.engine = std::make_unique<VisibilityEngine>(view_engine({g, h}, view.index)); });
    return view;
  }
  // The same past the panes of three or more groups (series_triples, series_cliques), kept by
  // the set (ascending).
  const PairView& group_set_view(const std::vector<std::size_t>& groups) const {
    PairView* view = nullptr;
    {
      const std::lock_guard lock(group_set_views_mutex_);
      std::unique_ptr<PairView>& slot = group_set_views_[groups];
      if (!slot) slot = std::make_unique<PairView>();
      view = slot.get();
    }
    std::call_once(view->built, [&] { view->engine = std::make_unique<VisibilityEngine>(view_engine(groups, view->index)); });
    return *view;
  }

  // Occluder `i` of `inside_` and the sky box (a pane: occluders + aperture) as a view's engine
  // lists it: the opaque polygons keep their index, a pane has another or is none (transparent).
  std::size_t view_occluder(const std::vector<std::size_t>& index, std::size_t i) const {
    const std::size_t n = scene_.occluders.size();
    return i < n || i == VisibilityOptions::kNoOccluder ? i : index[i - n];
  }
  std::size_t through_occluder(std::size_t g, std::size_t i) const { return view_occluder(through_index_[g], i); }

  void build_sky_box(const Box& all) {
    sky_box_ = std::make_unique<VisibilityEngine>(sky_box_scene(scene_, all), options_.mode, engine_.order(),
                                                  AperturesAre::independent);
    // The sky box's occluders are polygons_ in its order, so `own` names the same polygon in both.
    closed_ = ClosedShells(polygons_);
  }

  const Scene& scene_;
  const VisibilityEngine& engine_;
  ReflectionOptions options_;
  std::vector<ApertureGroup> groups_;
  double e_out_ = 1, ground_luminance_ = 0, scale_ = 1;
  std::vector<Box> aperture_boxes_, surf_boxes_;
  Box sensor_box_;
  RadiosityMesh mesh_;
  std::unique_ptr<VisibilityEngine> inside_;
  std::vector<VisibilityEngine> through_;  // per aperture group
  std::vector<std::vector<std::size_t>> through_index_;  // per group and aperture: its occluder index there
  mutable std::vector<PairView> pair_views_;              // per pair of groups g < h: at h(h − 1)/2 + g
  mutable std::map<std::vector<std::size_t>, std::unique_ptr<PairView>> group_set_views_;  // built on first use
  mutable std::mutex group_set_views_mutex_;
  std::vector<Vec3> pane_normals_, pane_points_;          // per aperture: its plane
  std::vector<Polygon> polygons_;  // per surface's `occluder`: the opaque polygons, then the apertures' panes
  std::unique_ptr<VisibilityEngine> sky_box_;
  // The polygons that close (the room's walls, floor, ceiling and panes): a receiver they enclose
  // sees nothing of the sky box, known without its six queries (geometry/closed_shells.hpp).
  ClosedShells closed_;
  std::vector<ConvexPiece> sun_pieces_;     // with options.sun: every polygon_'s convex pieces
  std::unique_ptr<SunlitElements> sunlit_;  // with options.sun
  std::vector<std::array<bool, 2>> live_;  // per surface and side
  double coarsening_ = 1;
};

std::size_t unknown(std::size_t element, int side, int k) { return 6 * element + 3 * std::size_t(side) + std::size_t(k); }

// Appends element e's coefficients c (side `side`, one per node) to a row of K, leaving out zeros.
void add_coefficients(TransportRow& row, std::size_t e, int side, const std::array<double, 3>& c) {
  for (int k = 0; k < 3; ++k)
    if (c[k] != 0) row.emplace_back(std::uint32_t(unknown(e, side, k)), c[k]);
}

// What a receiver on an element side needs: its first bounce and its row of K.
struct ReceiverRow {
  double first_bounce = 0;
  TransportRow row;
  bool direct_empty = true;
  bool direct_enclosed = false;
};

// `scratch`: where the row is gathered (a thread's, reused), so that the row kept is allocated
// once at its size: grown in place, the rows of a mesh (K, hundreds of MB) took twice their
// memory and as much again in page faults.
ReceiverRow receiver_row(const Transport& t, const Vec3& x, const Vec3& n, std::size_t own_surface,
                         VisibilityCounters& counters, TransportRow& scratch) {
  ReceiverRow r;
  const std::size_t own = t.mesh().surfaces[own_surface].occluder;
  const auto a = t.through_apertures(x, n, own, true, counters);
  const auto d = t.direct(x, n, own, counters);
  r.first_bounce = a.sky + a.ground + d.total;
  r.direct_empty = d.empty;
  r.direct_enclosed = d.enclosed;
  scratch.clear();
  t.transport(t.mesh(), x, n, own_surface, counters,
              [&](std::size_t e, int side, const std::array<double, 3>& c, bool, double) { add_coefficients(scratch, e, side, c); });
  r.row.assign(scratch.begin(), scratch.end());
  return r;
}

struct Local {
  VisibilityCounters counters;
  std::size_t direct_empty = 0, direct_enclosed = 0, direct = 0;
  TransportRow scratch;
};

// A stage's progress, from options.on_progress (nothing where it is unset).
ProgressCallback stage_progress(const ReflectionOptions& options, const std::string& stage, const std::string& unit,
                                std::size_t total) {
  if (!options.on_progress) return {};
  return [&options, stage, unit, total](std::size_t done) { options.on_progress(stage, unit, done, total); };
}

// The mesh with only the elements `listed` keeps in its surfaces' lists (elements and edges
// unchanged, so indices stay those of `mesh`): what transport() is to compute for, alone.
template <class Keep>
RadiosityMesh listing_only(const RadiosityMesh& mesh, Keep&& listed) {
  RadiosityMesh out = mesh;
  for (RadiositySurface& surface : out.surfaces) std::erase_if(surface.elements, [&](std::size_t e) { return !listed(e); });
  return out;
}

// A mesh's rows as the next refinement's node_rows reads them: each row's columns, and its values
// as collocated (before reciprocity), from `collocated` where that is not empty (then the rows hold
// K', the reciprocal values, in the same order), else from the rows themselves.
struct KeptRows {
  std::vector<ReceiverRow> rows;
  std::vector<std::vector<double>> collocated;
  double value(std::size_t u, std::size_t i) const { return collocated.empty() ? rows[u].row[i].second : collocated[u][i]; }
};

// What a mesh's rows can take from those of the mesh it was refined from (Transport::refine): an
// element not split keeps its nodes, so its first bounce, and its row's entries for every source
// element not split (a coefficient of K depends on the node and the source element alone); only
// the entries of the new elements (the split ones' children) are found, over the surfaces that
// have them.
struct EarlierRows {
  KeptRows kept;                      // the earlier mesh's
  std::vector<std::size_t> parent;    // per element of the current mesh: the earlier one (refine_mesh)
  std::vector<bool> split;            // per earlier element
  std::vector<bool> refined_surface;  // per surface: some of its elements split
  std::vector<std::size_t> current;   // per earlier element not split: its index now (else −1)
  RadiosityMesh fresh;                // the current mesh with only its new elements listed per surface

  // After Transport::refine(split) returned `parent_of`: the rest from them.
  void refined(std::vector<bool> split_flags, std::vector<std::size_t> parent_of, const RadiosityMesh& mesh) {
    split = std::move(split_flags);
    parent = std::move(parent_of);
    current.assign(split.size(), std::size_t(-1));
    for (std::size_t e = 0; e < parent.size(); ++e)
      if (!split[parent[e]]) current[parent[e]] = e;
    fresh = listing_only(mesh, [&](std::size_t e) { return split[parent[e]]; });
    refined_surface.clear();
    for (const RadiositySurface& surface : fresh.surfaces) refined_surface.push_back(!surface.elements.empty());
  }
};

// Rows of K and first bounce at every node, in parallel over element sides; with `earlier`, what
// the rows of the mesh before can give is taken from them.
std::vector<ReceiverRow> node_rows(const Transport& t, ReflectionResult& result, const ProgressCallback& progress = {},
                                   const EarlierRows* earlier = nullptr) {
  const RadiosityMesh& mesh = t.mesh();
  const std::size_t ne = mesh.elements.size();
  std::vector<ReceiverRow> rows(t.unknowns());
  const auto locals = for_each_sensor<Local>(2 * ne, 8, progress, [&](std::size_t i, Local& local) {
    const std::size_t e = i / 2;
    const int side = int(i % 2);
    const RadiosityElement& el = mesh.elements[e];
    if (!t.live(el.surface, side)) return;
    const Vec3 n = side == 0 ? el.normal : -1.0 * el.normal;
    const bool kept = earlier != nullptr && !earlier->split[earlier->parent[e]];
    const std::array<double, 3> sun = kept ? std::array<double, 3>{0, 0, 0} : t.sun_first_bounce(el, side);
    for (int k = 0; k < 3; ++k) {
      ReceiverRow r;
      if (kept) {
        const std::size_t u_before = unknown(earlier->parent[e], side, k);
        const ReceiverRow& before = earlier->kept.rows[u_before];
        r.first_bounce = before.first_bounce;
        r.direct_empty = before.direct_empty;
        r.direct_enclosed = before.direct_enclosed;
        TransportRow& row = local.scratch;
        row.clear();
        for (std::size_t i = 0; i < before.row.size(); ++i) {
          const std::uint32_t j = before.row[i].first;
          const std::size_t source = earlier->current[j / 6];
          if (source != std::size_t(-1))
            row.emplace_back(std::uint32_t(unknown(source, int(j / 3 % 2), int(j % 3))), earlier->kept.value(u_before, i));
        }
        t.transport(
            earlier->fresh, el.nodes[k], n, el.surface, local.counters,
            [&](std::size_t src, int src_side, const std::array<double, 3>& c, bool, double) {
              add_coefficients(row, src, src_side, c);
            },
            &earlier->refined_surface);
        r.row.assign(row.begin(), row.end());
      } else {
        r = receiver_row(t, el.nodes[k], n, el.surface, local.counters, local.scratch);
        r.first_bounce += sun[std::size_t(k)];
      }
      local.direct_empty += r.direct_empty;
      local.direct_enclosed += r.direct_enclosed;
      ++local.direct;
      rows[unknown(e, side, k)] = std::move(r);
    }
  });
  result.receivers_direct_empty = result.receivers_direct_enclosed = result.receivers_direct = 0;
  for (const auto& l : locals) {
    result.counters += l.counters;
    result.receivers_direct_empty += l.direct_empty;
    result.receivers_direct_enclosed += l.direct_enclosed;
    result.receivers_direct += l.direct;
  }
  return rows;
}

double check_inputs(const Scene& scene, const std::vector<double>& reflectance, const ReflectionOptions& options) {
  if (!(options.ground_reflectance >= 0 && options.ground_reflectance < 1))
    throw Error("ground reflectance " + std::to_string(options.ground_reflectance) + " is outside [0, 1)");
  if (reflectance.size() != scene.occluders.size()) throw Error("one reflectance per occluder is needed");
  double rho_max = 0;
  const auto check = [&](double rho, const Polygon& p) {
    if (!(rho >= 0 && rho < 1))
      throw input_error(p.where, "reflectance " + std::to_string(rho) + " of '" + p.name + "' is outside [0, 1)");
    rho_max = std::max(rho_max, rho);
  };
  for (std::size_t i = 0; i < reflectance.size(); ++i) check(reflectance[i], scene.occluders[i]);
  for (const Aperture& a : scene.apertures) check(a.reflectance, a.polygon);  // a pane's (Aperture::reflectance)
  return rho_max;
}

}  // namespace

RadiositySystem radiosity_system(const Scene& scene, const std::vector<double>& reflectance,
                                 const VisibilityEngine& engine, const std::vector<const SensorGrid*>& grids,
                                 const ReflectionOptions& options) {
  check_inputs(scene, reflectance, options);
  ReflectionOptions opt = options;
  if (opt.element_size == 0) opt.element_size = automatic_element_size(scene, grids);
  const Transport t(scene, reflectance, engine, grids, opt, 1.0, true);
  ReflectionResult scratch;
  std::vector<ReceiverRow> rows = node_rows(t, scratch);
  RadiositySystem sys;
  sys.mesh = t.mesh();
  std::vector<double> weight;
  for (std::size_t u = 0; u < rows.size(); ++u) {
    sys.first_bounce.push_back(rows[u].first_bounce);
    sys.reflectance.push_back(sys.mesh.surfaces[sys.mesh.elements[u / 6].surface].reflectance);
    sys.collocated_rows.push_back(std::move(rows[u].row));
    weight.push_back(sys.mesh.elements[u / 6].area / 3);
  }
  sys.rows = sys.collocated_rows;
  if (opt.reciprocal_transport) sys.reciprocity = make_reciprocal(sys.rows, weight);
  return sys;
}

namespace {

// The longest chord through p along the three axes between surfaces it crosses both ways (walls
// and panes alike): the room's length, width or height there; 0 where no axis meets surfaces
// both ways (a sensor outdoors).
double room_span(const std::vector<Polygon>& surfaces, const Vec3& p) {
  double span = 0;
  for (const Vec3& axis : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}) {
    const double chord = nearest_crossing(surfaces, p, axis) + nearest_crossing(surfaces, p, -1.0 * axis);
    if (std::isfinite(chord)) span = std::max(span, chord);
  }
  return span;
}

// The median room span over (at most 64 of) a grid's sensors, taken evenly through the list.
double median_room_span(const std::vector<Polygon>& surfaces, const SensorGrid& g) {
  const std::size_t n = g.sensors.size(), taken = std::min<std::size_t>(n, 64);
  std::vector<double> spans;
  for (std::size_t k = 0; k < taken; ++k) spans.push_back(room_span(surfaces, g.sensors[k * n / taken].position));
  if (spans.empty()) return 0;
  std::nth_element(spans.begin(), spans.begin() + std::ptrdiff_t(spans.size() / 2), spans.end());
  return spans[spans.size() / 2];
}

}  // namespace

double rows_bytes_estimate(double entries, double elements, double next_elements, bool earlier_kept) {
  if (!(elements > 0)) return 0;
  const double growth = next_elements / elements;
  return entries * (kRowBytesPerEntry * growth * growth + (earlier_kept ? kKeptBytesPerEntry : 0));
}

double automatic_element_size(const Scene& scene, const std::vector<const SensorGrid*>& grids) {
  std::vector<Polygon> surfaces = scene.occluders;
  for (const Aperture& a : scene.apertures) surfaces.push_back(a.polygon);
  std::vector<double> extents;
  for (const SensorGrid* g : grids) {
    Box b;
    for (const Sensor& s : g->sensors) b.add(s.position);
    const double extent = std::max(b.longest_side(), 0.5 * median_room_span(surfaces, *g));
    if (extent > 0) extents.push_back(extent);
  }
  if (extents.empty()) {
    Box b;
    for (const Aperture& a : scene.apertures)
      for (const Vec3& v : a.polygon.vertices) b.add(v);
    for (const SensorGrid* g : grids)
      for (const Sensor& s : g->sensors) b.add(s.position);
    return b.longest_side() > 0 ? b.longest_side() / 5 : 1.0;
  }
  std::nth_element(extents.begin(), extents.begin() + std::ptrdiff_t(extents.size() / 2), extents.end());
  return extents[extents.size() / 2] / 5;
}

namespace {

// One solution on one mesh: the node values, and the energy balance and solver figures.
struct MeshSolution {
  std::vector<double> exitance;
  int sweeps = 0;
  double solver_change = 0;
  double flux_first_bounce = 0, flux_absorbed = 0, flux_escaping = 0;
  ReciprocityReport reciprocity;
  std::size_t entries = 0;  // of the rows of K
};

// Bytes as gigabytes with one decimal, for the messages of the memory guard.
std::string gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
  return text;
}

// What raising --element-size can reach and no further: the first mesh `Transport` builds at an
// element size larger than the model, each surface's own triangles. A model of many surfaces (a
// building of a hundred rooms) may be over the memory or node limits even there, and the
// refusals must say so rather than send the user raising the size in vain.
Transport coarsest_transport(const Scene& scene, const std::vector<double>& reflectance, const VisibilityEngine& engine,
                             const std::vector<const SensorGrid*>& grids, ReflectionOptions opt, double model_scale) {
  opt.element_size = 1e3 * model_scale;
  return Transport(scene, reflectance, engine, grids, opt, 2.0, false);
}

// Wall seconds since `start`, restarting it.
double lap(std::chrono::steady_clock::time_point& start) {
  const auto now = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(now - start).count();
  start = now;
  return s;
}

// The solution of a mesh carried to its refinement, where the refinement's sweeps start: an
// element not split keeps its nodes and their values; a split element's children take its linear
// exitance at their nodes (Σ_k φ_k M_k). It differs from the refined solution by the mesh's own
// error, a percent or less, where the source differs from it by the interreflections, tens of
// percent; the sweeps run to roundoff all the same, so that saves about two of them (measured:
// the room sample's two rounds 17 → 15 sweeps each, the office's last 16 → 15).
std::vector<double> refined_start(const RadiosityMesh& before, const std::vector<double>& exitance,
                                  const RadiosityMesh& mesh, const std::vector<std::size_t>& parent,
                                  const std::vector<bool>& split) {
  std::vector<double> m(6 * mesh.elements.size(), 0.0);
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const std::size_t p = parent[e];
    const RadiosityElement& from = before.elements[p];
    for (int side = 0; side < 2; ++side)
      for (int k = 0; k < 3; ++k) {
        if (!split[p]) {
          m[unknown(e, side, k)] = exitance[unknown(p, side, k)];
          continue;
        }
        double value = 0;
        for (int j = 0; j < 3; ++j) value += from.basis(j, mesh.elements[e].nodes[k]) * exitance[unknown(p, side, j)];
        m[unknown(e, side, k)] = value;
      }
  }
  return m;
}

// `name`: the mesh's, for the stages' times ("coarse mesh", "round 0"). `earlier`: node_rows'.
// `keep`, where given: the rows, for the next refinement's node_rows. `start`: where the sweeps
// start (refined_start), else the source.
MeshSolution solve_mesh(const Transport& t, bool reciprocal, ReflectionResult& result, const ProgressCallback& progress,
                        const std::string& name, EarlierRows* earlier = nullptr, KeptRows* keep = nullptr,
                        std::vector<double> start = {}) {
  auto clock = std::chrono::steady_clock::now();
  const RadiosityMesh& mesh = t.mesh();
  const std::size_t nu = t.unknowns();
  std::vector<ReceiverRow> rows = node_rows(t, result, progress, earlier);
  // The earlier rows are read: what they held serves the reciprocity's arrays below, which would
  // otherwise be page-faulted in afresh.
  if (earlier != nullptr) earlier->kept = {};
  result.stages.push_back({name + ": rows (first bounce and transport at every node)", lap(clock)});
  std::vector<double> rho(nu), source(nu), weight(nu, 0.0);
  std::vector<TransportRow> k_rows(nu);
  tbb::parallel_for(std::size_t(0), nu, [&](std::size_t u) {
    const RadiosityElement& el = mesh.elements[u / 6];
    const double r = mesh.surfaces[el.surface].reflectance;
    rho[u] = r;
    source[u] = r * rows[u].first_bounce;
    k_rows[u] = std::move(rows[u].row);
    if (t.live(el.surface, int(u / 3 % 2))) weight[u] = el.area / 3;
  });
  MeshSolution out;
  for (const TransportRow& row : k_rows) out.entries += row.size();
  // Kept for the next round, the collocated values beside K' rather than a copy of K (14 million
  // entries on the office: the copy's page faults cost more than the copying).
  if (reciprocal) {
    out.reciprocity = make_reciprocal(k_rows, weight, keep != nullptr ? &keep->collocated : nullptr);
    result.stages.push_back({name + ": reciprocity", lap(clock)});
  }
  // Over-relaxed where the transport is reciprocal, which is what makes that converge
  // (radiosity_solver.hpp).
  constexpr double kOverRelaxation = 1.1;
  SweepOptions sweeps;
  sweeps.over_relaxation = reciprocal ? kOverRelaxation : 1.0;
  sweeps.start = std::move(start);
  result.over_relaxation = sweeps.over_relaxation;
  RadiositySolution sol = solve_radiosity(k_rows, rho, source, sweeps);
  result.stages.push_back({name + ": solve", lap(clock)});
  if (!sol.converged)
    throw Error("the radiosity solution did not converge (" + std::to_string(sol.sweeps) +
                " sweeps): the model's surfaces may overlap (coincident polygons facing the same way count twice)");
  out.sweeps = sol.sweeps;
  out.solver_change = sol.last_change;
  out.exitance = std::move(sol.exitance);
  const std::vector<double>& m = out.exitance;
  // Energy balance (see the header): first bounce, absorbed, escaping, by the nodes' rule; each
  // node's row in parallel, the sums over nodes in node order (the same to the last bit).
  std::vector<double> received(nu), view(nu);
  tbb::parallel_for(std::size_t(0), nu, [&](std::size_t u) {
    double e = 0, f = 0;
    for (const auto& [j, c] : k_rows[u]) {
      e += c * m[j];
      f += c;
    }
    received[u] = e;
    view[u] = f;
  });
  for (std::size_t u = 0; u < nu; ++u) {
    const double w = mesh.elements[u / 6].area / 3;
    out.flux_first_bounce += w * rows[u].first_bounce;
    out.flux_absorbed += w * (1 - rho[u]) * (rows[u].first_bounce + received[u]);
    out.flux_escaping += w * m[u] * (1 - view[u]);
  }
  if (keep != nullptr) {
    for (std::size_t u = 0; u < nu; ++u) rows[u].row = std::move(k_rows[u]);
    keep->rows = std::move(rows);
  }
  return out;
}

// ERC and IRC at every sensor from the finer of two solutions, and the estimate of their error:
// per element P of the coarser mesh that was split, what P gives the sensor against what its four
// children give (through apertures and inside each), the absolute differences summed over P.
// That is at least the difference of the two sensor values, and a sensor where the two meshes
// agree by chance (the difference changing sign across the room) keeps the estimate of its
// elements. Through glass, each element's spread of T(μ) over its directions times what it gives
// is added (the transmittance taken at the centroid's direction costs at most that). Elements
// not split this round add what earlier rounds estimated for them (`carried`, per sensor).
struct SensorTerms {
  // A split element P's part of the estimate: |P − its children| and, through glass, its
  // children's spread of T(μ) times what they give.
  struct Term {
    std::uint32_t element = 0;
    double difference = 0, spread = 0;
    // What splitting P again is expected to take off the estimate: seven eighths of the
    // difference and half of the spread (first order in the angle the element subtends: each
    // child spans half of it). Second order alone would leave a quarter of the difference; what a
    // split leaves was measured to vary (splitting every element left 1/12 of the worst estimate
    // of the room sample at its default size, 1/5 of a 2 m test room's at 0.5 m, 1/3 at 1.5 m).
    // A plan too hopeful costs another round, which keeps what it does not split; one too timid
    // costs a mesh several times too fine, whose rows grow as its square: counting on 3/4, no
    // round could plan a sensor's estimate down more than fourfold, so for 1 % of the room
    // sample's IRC it flagged every element (2,688, 13.9 s), where 7/8 flags 1,140 and meets the
    // tolerance in 3.0 s; the office at 0.02 DF points: 3,988 against 4,084 elements, both
    // ending at 0.020 in two rounds (2026-12-06).
    double reduction() const { return 0.875 * difference + 0.5 * spread; }
  };
  // The split elements' terms, largest reduction first, at most kTermsKept: the candidates for the
  // next local refinement. `total`: the differences of all split elements summed; `spread`: the
  // spread of every element this round (split or not).
  std::vector<Term> largest;
  double total = 0, spread = 0;
};
constexpr std::size_t kTermsKept = 256;

struct SensorValues {
  std::vector<std::vector<double>> erc, irc, estimate;  // per grid, per sensor
  std::vector<std::vector<SensorTerms>> terms;          // per grid, per sensor
};

struct SensorLocal {
  VisibilityCounters counters;
  std::vector<double> through, inside;  // per coarse element: coarse minus fine
  std::vector<double> spread;           // per split coarse element: its children's spread
};

// What a sensor's transport was on the finer mesh of a round, for the next local round: an
// element not split then gives the same coefficients, and a split one gives, as the coarser
// element, the coefficients it gave as the finer one; only the new elements need visibility and
// kernels again. Kept only where a further round may follow.
struct SensorEntry {
  std::uint32_t element = 0;
  std::uint8_t side = 0;
  bool through = false;
  double spread = 0;
  std::array<double, 3> c{};
};
struct SensorCache {
  std::size_t max_bytes = 0;  // ReflectionOptions::sensor_cache_bytes: beyond it, nothing is kept
  bool filled = false;  // entries are of the finer mesh of the round before
  bool keep = false;    // this round's entries are to be kept
  std::atomic<std::size_t> bytes{0};
  std::atomic<bool> overflowed{false};
  std::vector<std::vector<std::vector<SensorEntry>>> entries;  // per grid, per sensor
  std::vector<std::vector<double>> ground;                     // per grid, per sensor: the far ground
  std::vector<std::vector<char>> outdoors;                     // per grid, per sensor: sees the sky directly
};

// `parent`: per element of the finer mesh (t's), the coarser element it is or came from; `split`:
// per coarser element, whether it was split; `carried`: per grid and sensor (empty: none).
// `cache`, where given: read where filled (with `change`, the refinement since), written where kept.
SensorValues sensor_values(const Transport& t, const RadiosityMesh& coarse_mesh, const std::vector<double>& coarse,
                           const std::vector<double>& fine, const std::vector<std::size_t>& parent,
                           const std::vector<bool>& split, const std::vector<std::vector<double>>& carried,
                           const std::vector<const SensorGrid*>& grids, ReflectionResult& result,
                           const ProgressCallback& progress, SensorCache* cache = nullptr,
                           const EarlierRows* change = nullptr) {
  const bool read = cache != nullptr && cache->filled && change != nullptr;
  const bool keep = cache != nullptr && cache->keep;
  if (keep) {
    cache->bytes = 0;
    cache->overflowed = false;
  }
  if (keep && !read) {
    cache->entries.assign(grids.size(), {});
    cache->ground.assign(grids.size(), {});
    cache->outdoors.assign(grids.size(), {});
    for (std::size_t g = 0; g < grids.size(); ++g) {
      cache->entries[g].resize(grids[g]->sensors.size());
      cache->ground[g].resize(grids[g]->sensors.size());
      cache->outdoors[g].resize(grids[g]->sensors.size());
    }
  }
  SensorValues out;
  const std::size_t nc = coarse_mesh.elements.size();
  std::size_t before = 0;  // sensors of the earlier grids: progress counts over all of them
  for (std::size_t g = 0; g < grids.size(); ++g) {
    const SensorGrid* grid = grids[g];
    const std::size_t n = grid->sensors.size();
    std::vector<double> erc(n, 0.0), irc(n, 0.0), estimate(n, 0.0);
    std::vector<SensorTerms> terms(n);
    ProgressCallback grid_progress;
    if (progress) grid_progress = [&progress, before](std::size_t done) { progress(before + done); };
    before += n;
    const auto locals = for_each_sensor<SensorLocal>(n, 4, grid_progress, [&](std::size_t i, SensorLocal& local) {
      const Sensor& s = grid->sensors[i];
      local.through.assign(nc, 0.0);
      local.inside.assign(nc, 0.0);
      local.spread.assign(nc, 0.0);
      double e_through = 0, e_inside = 0, e_spread = 0;
      bool outdoors = false;  // sees the sky directly: all it sees is outside light (ERC)
      std::vector<SensorEntry> next;
      const auto coarse_sink = [&](std::size_t e, int side, const std::array<double, 3>& c, bool through) {
        if (!split[e]) return;
        double value = 0;
        for (int k = 0; k < 3; ++k) value += c[k] * coarse[unknown(e, side, k)];
        (through ? local.through : local.inside)[e] += value;
      };
      const auto fine_sink = [&](std::size_t e, int side, const std::array<double, 3>& c, bool through, double sp) {
        double value = 0;
        for (int k = 0; k < 3; ++k) value += c[k] * fine[unknown(e, side, k)];
        (through ? e_through : e_inside) += value;
        if (split[parent[e]]) {
          (through ? local.through : local.inside)[parent[e]] -= value;
          local.spread[parent[e]] += sp * std::abs(value);
        }
        e_spread += sp * std::abs(value);
        if (keep) next.push_back({std::uint32_t(e), std::uint8_t(side), through, sp, c});
      };
      if (read) {
        // The round before's entries, then the new elements alone (on the surfaces that have them).
        e_through = cache->ground[g][i];
        outdoors = cache->outdoors[g][i];
        for (const SensorEntry& en : cache->entries[g][i]) {
          if (split[en.element])
            coarse_sink(en.element, en.side, en.c, en.through);
          else
            fine_sink(change->current[en.element], en.side, en.c, en.through, en.spread);
        }
        t.transport(
            change->fresh, s.position, s.normal, std::size_t(-1), local.counters,
            [&](std::size_t e, int side, const std::array<double, 3>& c, bool through, double sp) {
              fine_sink(e, side, c, through, sp);
            },
            &change->refined_surface);
      } else {
        const auto a = t.through_apertures(s.position, s.normal, VisibilityOptions::kNoOccluder, false, local.counters);
        e_through = a.ground;
        // A grid that sees the sky directly (SensorGrid::sees_sky_directly): the far ground seen
        // past every surface too.
        if (grid->sees_sky_directly) {
          const auto d = t.direct(s.position, s.normal, VisibilityOptions::kNoOccluder, local.counters);
          e_through += d.ground;
          outdoors = !d.empty;
        }
        if (keep) {
          cache->ground[g][i] = e_through;
          cache->outdoors[g][i] = outdoors;
        }
        // Both meshes from one set of visibility queries.
        const RadiosityMesh* meshes[] = {&coarse_mesh, &t.mesh()};
        t.transport(meshes, s.position, s.normal, std::size_t(-1), local.counters,
                    [&](std::size_t m, std::size_t e, int side, const std::array<double, 3>& c, bool through, double sp) {
                      if (m == 0)
                        coarse_sink(e, side, c, through);
                      else
                        fine_sink(e, side, c, through, sp);
                    });
      }
      if (keep) {
        const std::size_t bytes = next.size() * sizeof(SensorEntry);
        if (cache->bytes.fetch_add(bytes) + bytes > cache->max_bytes) {
          cache->overflowed = true;
          next = {};
        }
        cache->entries[g][i] = std::move(next);
      }
      SensorTerms& mine = terms[i];
      std::vector<SensorTerms::Term>& largest = mine.largest;
      for (std::size_t p = 0; p < nc; ++p) {
        const double term = std::abs(local.through[p]) + std::abs(local.inside[p]);
        if (term == 0 && local.spread[p] == 0) continue;
        mine.total += term;
        largest.push_back({std::uint32_t(p), term, local.spread[p]});
      }
      const auto larger = [](const SensorTerms::Term& x, const SensorTerms::Term& y) {
        return x.reduction() > y.reduction() || (x.reduction() == y.reduction() && x.element < y.element);
      };
      const std::size_t kept = std::min(largest.size(), kTermsKept);
      std::partial_sort(largest.begin(), largest.begin() + std::ptrdiff_t(kept), largest.end(), larger);
      largest.resize(kept);
      mine.spread = e_spread;
      estimate[i] = mine.total + e_spread + (carried.empty() ? 0.0 : carried[g][i]);
      // Light is not negative: a component below 0 by less than its own estimate (the rounding of
      // what is seen through an aperture less the same seen inside: −2.7e-19 on the office's
      // sensors that see no exterior surface) is 0, which is nearer the truth; a larger negative
      // value is kept, visible, as the sign of a defect.
      const auto non_negative = [&](double v) { return v < 0 && -v <= estimate[i] ? 0.0 : v; };
      // A sensor outdoors (on a façade, in a courtyard) sees no room: every surface it sees without
      // crossing an aperture is outside, its light externally reflected.
      if (outdoors) {
        e_through += e_inside;
        e_inside = 0;
      }
      erc[i] = non_negative(e_through);
      irc[i] = non_negative(e_inside);
    });
    for (const auto& l : locals) result.counters += l.counters;
    out.erc.push_back(std::move(erc));
    out.irc.push_back(std::move(irc));
    out.estimate.push_back(std::move(estimate));
    out.terms.push_back(std::move(terms));
  }
  if (cache != nullptr) {
    cache->filled = keep && !cache->overflowed;
    if (!cache->filled) cache->entries.clear();
  }
  return out;
}

// The next local refinement (DESIGN.md §4): every sensor whose estimate exceeds `tolerance`, worst
// first, flags its terms, largest expected reduction first, until its estimate less the
// reductions of the flagged ones (its own and those flagged before it) meets the tolerance: a
// split leaves a quarter of an element's difference (second order; measured, the split elements'
// children's terms summed over all sensors against the split terms: 0.26 and 0.27 on the room
// sample's second and third rounds, 0.18 on the office's second) and half of its glass spread
// (first order in the element's angle). Counting the spread
// as irreducible instead made the sensors near the office's window, where the spread is most of
// the estimate, flag nearly all their candidates (616 elements split against 164 once the pane
// reflected and the spread grew 8 %). The flags of all sensors together are split. Each sensor then
// carries, besides what it carried, the terms of the elements not split, as they were: an
// element's estimate stays until it is refined. A term of an element split for another sensor but not among a sensor's kept
// candidates is carried too, so the carried part may count it twice, never too little. Returns
// the flags per element of the finer mesh (children of a flagged coarser element).
std::vector<bool> local_refinement(const SensorValues& values, double tolerance, const std::vector<std::size_t>& parent,
                                   std::size_t coarse_elements, std::vector<std::vector<double>>& carried) {
  std::vector<bool> flag(coarse_elements, false);
  if (carried.empty())
    for (const auto& e : values.estimate) carried.emplace_back(e.size(), 0.0);
  // The worst sensors first; each counts what the flags of those before it take off its estimate
  // before it flags more (each planning alone, the office's sensors near the window flagged 36
  // elements where 28 meet the tolerance).
  std::vector<std::pair<std::size_t, std::size_t>> over;  // (grid, sensor)
  for (std::size_t g = 0; g < values.terms.size(); ++g)
    for (std::size_t i = 0; i < values.terms[g].size(); ++i)
      if (values.estimate[g][i] > tolerance) over.emplace_back(g, i);
  std::sort(over.begin(), over.end(), [&](const auto& a, const auto& b) {
    const double ea = values.estimate[a.first][a.second], eb = values.estimate[b.first][b.second];
    return ea > eb || (ea == eb && a < b);
  });
  for (const auto& [g, i] : over) {
    const SensorTerms& terms = values.terms[g][i];
    double expected = values.estimate[g][i];
    for (const SensorTerms::Term& term : terms.largest)
      if (flag[term.element]) expected -= term.reduction();
    for (const SensorTerms::Term& term : terms.largest) {
      if (expected <= tolerance) break;
      if (flag[term.element]) continue;
      flag[term.element] = true;
      expected -= term.reduction();
    }
  }
  for (std::size_t g = 0; g < values.terms.size(); ++g)
    for (std::size_t i = 0; i < values.terms[g].size(); ++i) {
      const SensorTerms& terms = values.terms[g][i];
      double rest = terms.total;
      for (const SensorTerms::Term& term : terms.largest)
        if (flag[term.element]) rest -= term.difference;
      carried[g][i] += std::max(rest, 0.0);  // rounding of the subtractions: not below 0
    }
  std::vector<bool> split(parent.size());
  for (std::size_t j = 0; j < parent.size(); ++j) split[j] = flag[parent[j]];
  return split;
}

}  // namespace

namespace {

// The inputs checked (check_inputs, a finite element size ≥ 0 and a positive grading) and the element size resolved
// (0: automatic_element_size); rho_max: the largest reflectance.
ReflectionOptions checked_options(const Scene& scene, const std::vector<double>& reflectance,
                                  const std::vector<const SensorGrid*>& grids, const ReflectionOptions& options,
                                  double& rho_max) {
  rho_max = check_inputs(scene, reflectance, options);
  const auto refuse = [](const char* what, double value) {
    std::string message = what;  // appended: GCC 12 warns falsely (-Wrestrict) on a chain of +
    message += ' ';
    message += std::to_string(value);
    message += " is not a positive number";
    throw Error(message);
  };
  if (!(options.element_size >= 0) || !std::isfinite(options.element_size)) refuse("element size", options.element_size);
  if (!(options.grading > 0) || !std::isfinite(options.grading)) refuse("element grading", options.grading);
  ReflectionOptions opt = options;
  if (opt.element_size == 0) opt.element_size = automatic_element_size(scene, grids);
  return opt;
}

}  // namespace

ReflectionResult reflected_components(const Scene& scene, const std::vector<double>& reflectance,
                                      const VisibilityEngine& engine, const std::vector<const SensorGrid*>& grids,
                                      const ReflectionOptions& options) {
  double rho_max = 0;
  const ReflectionOptions opt = checked_options(scene, reflectance, grids, options, rho_max);
  ReflectionResult result;
  result.element_size = opt.element_size;
  result.reflectance_max = rho_max;
  for (const SensorGrid* g : grids) {
    SensorReflections s;
    s.erc_percent.assign(g->sensors.size(), 0.0);
    s.irc_percent.assign(g->sensors.size(), 0.0);
    s.error_percent.assign(g->sensors.size(), 0.0);
    result.grids.push_back(std::move(s));
  }
  if (rho_max == 0 && options.ground_reflectance == 0) {
    result.black = true;  // nothing reflects: ERC and IRC are 0 exactly, no radiosity work
    return result;
  }

  // The coarse mesh at twice the asked element size; each round solves a finer mesh (round 0:
  // its uniform split; later rounds: a local refinement of the round before's) and reports the
  // finer solution, with the element-by-element difference of the two as the error estimate.
  auto clock = std::chrono::steady_clock::now();
  Transport t(scene, reflectance, engine, grids, opt, 2.0, false);
  result.stages.push_back({"mesh and visibility engines", lap(clock)});
  const double to_percent = 100 / t.e_out();
  result.sides_solved = t.live_side_count();
  result.sides_left_out = 2 * t.surface_count() - result.sides_solved;
  const auto rows_stage = [&](const std::string& name) {
    return stage_progress(opt, name, "element sides", 2 * t.mesh().elements.size());
  };
  MeshSolution coarse =
      solve_mesh(t, opt.reciprocal_transport, result, rows_stage("radiosity: the coarse mesh's rows"), "coarse mesh");
  // Round 0 splits every element of the coarse mesh; each further round splits only what
  // local_refinement flags, and takes the rest of its rows from the round before (EarlierRows).
  RadiosityMesh coarse_mesh = t.mesh();
  if (opt.memory_bytes > 0) {
    const double elements = double(coarse_mesh.elements.size());
    const double needed = rows_bytes_estimate(double(coarse.entries), elements, 4 * elements, false);
    if (needed > double(opt.memory_bytes)) {
      std::string message = "the reflected components' mesh of ";
      message += std::to_string(4 * coarse_mesh.elements.size());
      message += " elements would need about " + gigabytes(needed);
      message += " for its transport rows, more than the " + gigabytes(double(opt.memory_bytes));
      // A larger element size helps down to each surface's own triangles, whose rows would need
      // about as much less as the square of the elements (every element seen from every other).
      const double fewest =
          double(coarsest_transport(scene, reflectance, engine, grids, opt, t.scale()).mesh().elements.size());
      const double needed_coarsest = needed * (fewest / elements) * (fewest / elements);
      if (needed_coarsest > double(opt.memory_bytes)) {
        message += " allowed, and about " + gigabytes(needed_coarsest);
        message += " at any --element-size (each surface's own triangles): use --components sc, or give the rooms (or "
                   "fewer surfaces) a run each";
      } else {
        message += " allowed: raise --element-size (now ";
        message += std::to_string(opt.element_size);
        message += ")";
      }
      throw Error(message);
    }
  }
  std::vector<bool> split(coarse_mesh.elements.size(), true);
  std::vector<std::size_t> parent = t.split_all();
  std::vector<std::vector<double>> carried;  // per grid and sensor: the estimate of elements not split since
  std::unique_ptr<EarlierRows> earlier;
  SensorCache sensor_cache;
  sensor_cache.max_bytes = opt.sensor_cache_bytes;
  for (int round = 0;; ++round) {
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on a chain of + here.
    std::string name = "radiosity: ";
    if (round == 0) {
      name += "the mesh's";
    } else {
      name += "refinement ";
      name += std::to_string(round);
      name += "'s";
    }
    name += " rows";
    const std::string round_name = "round " + std::to_string(round);
    const bool more = round < opt.max_refinements;
    KeptRows kept_rows;
    MeshSolution fine = solve_mesh(t, opt.reciprocal_transport, result, rows_stage(name), round_name, earlier.get(),
                                   more ? &kept_rows : nullptr,
                                   refined_start(coarse_mesh, coarse.exitance, t.mesh(), parent, split));
    clock = std::chrono::steady_clock::now();
    std::size_t sensors = 0;
    for (const SensorGrid* g : grids) sensors += g->sensors.size();
    // The coarser mesh as the sensors need it: only its split elements give terms, so each
    // surface lists those alone (a surface none of whose elements was split, none).
    const RadiosityMesh split_part = listing_only(coarse_mesh, [&](std::size_t e) { return split[e]; });
    sensor_cache.keep = more;
    const SensorValues values =
        sensor_values(t, split_part, coarse.exitance, fine.exitance, parent, split, carried, grids, result,
                      stage_progress(opt, "reflections at the sensors", "sensors", sensors), &sensor_cache,
                      earlier.get());
    earlier.reset();
    result.stages.push_back({round_name + ": sensors (both meshes' transport and the estimate)", lap(clock)});
    double worst = 0;
    for (std::size_t g = 0; g < grids.size(); ++g) {
      SensorReflections& out = result.grids[g];
      for (std::size_t i = 0; i < out.erc_percent.size(); ++i) {
        out.erc_percent[i] = to_percent * values.erc[g][i];
        out.irc_percent[i] = to_percent * values.irc[g][i];
        out.error_percent[i] = to_percent * values.estimate[g][i];
        worst = std::max(worst, out.error_percent[i]);
      }
    }
    result.error_by_round.push_back(worst);
    result.max_error_percent = worst;
    result.elements = t.mesh().elements.size();
    result.unknowns = t.unknowns();
    result.max_level = t.mesh().max_level;
    result.refinements = round;
    result.sweeps = fine.sweeps;
    result.solver_change = fine.solver_change;
    result.flux_first_bounce = fine.flux_first_bounce;
    result.flux_absorbed = fine.flux_absorbed;
    result.flux_escaping = fine.flux_escaping;
    result.reciprocity = fine.reciprocity;
    const double first = fine.flux_first_bounce;
    result.balance_mismatch = first > 0 ? (first - fine.flux_absorbed - fine.flux_escaping) / first : 0;
    if (worst <= opt.tolerance_percent || !more || result.elements == 0) break;
    std::vector<bool> next = local_refinement(values, opt.tolerance_percent / to_percent, parent,
                                              coarse_mesh.elements.size(), carried);
    if (std::find(next.begin(), next.end(), true) == next.end()) break;  // nothing a sensor could flag
    if (opt.memory_bytes > 0) {
      const double elements = double(t.mesh().elements.size());
      const double next_elements = elements + 3.0 * double(std::count(next.begin(), next.end(), true));
      const double needed = rows_bytes_estimate(double(fine.entries), elements, next_elements, true);
      if (needed > double(opt.memory_bytes)) {
        result.stopped = "refinement stopped after round " + std::to_string(round) + ": round " +
                         std::to_string(round + 1) + " (" + std::to_string(std::size_t(next_elements)) +
                         " elements) would need about " + gigabytes(needed) + " for its transport rows, more than the " +
                         gigabytes(double(opt.memory_bytes)) + " allowed; the tolerance is not met";
        break;
      }
    }
    earlier = std::make_unique<EarlierRows>();
    earlier->kept = std::move(kept_rows);
    coarse = std::move(fine);
    coarse_mesh = t.mesh();
    split = next;
    parent = t.refine(next);
    earlier->refined(std::move(next), parent, t.mesh());
  }
  return result;
}

ReflectionOperator reflection_operator(const Scene& scene, const std::vector<double>& reflectance,
                                       const VisibilityEngine& engine, const std::vector<const SensorGrid*>& grids,
                                       const ReflectionOptions& options, bool coarse, std::size_t max_nodes,
                                       const std::vector<const SensorGrid*>* response_grids) {
  double rho_max = 0;
  const ReflectionOptions opt = checked_options(scene, reflectance, grids, options, rho_max);
  auto clock = std::chrono::steady_clock::now();
  ReflectionOperator op;
  op.element_size = opt.element_size * (coarse ? 2 : 1);
  Transport t(scene, reflectance, engine, grids, opt, 2.0, false);
  if (!coarse) t.split_all();
  const RadiosityMesh& mesh = t.mesh();
  op.elements = mesh.elements.size();
  op.sides_solved = t.live_side_count();
  op.sides_left_out = 2 * t.surface_count() - op.sides_solved;
  const std::size_t nu = t.unknowns();

  // The live unknowns, numbered in mesh order; their views and rows of K, in parallel over sides.
  std::vector<std::int64_t> index(nu, -1);
  std::size_t n = 0;
  for (std::size_t u = 0; u < nu; ++u)
    if (rho_max > 0 && t.live(mesh.elements[u / 6].surface, int(u / 3 % 2))) index[u] = std::int64_t(n++);
  // The live nodes of the coarsest mesh (coarsest_transport; split once for the reported mesh).
  const auto coarsest_nodes = [&] {
    Transport floor = coarsest_transport(scene, reflectance, engine, grids, opt, t.scale());
    if (!coarse) floor.split_all();
    std::size_t fewest = 0;
    for (std::size_t u = 0; u < floor.unknowns(); ++u)
      fewest += floor.live(floor.mesh().elements[u / 6].surface, int(u / 3 % 2));
    return fewest;
  };
  const std::string no_size_helps =
      " at any --element-size (each surface's own triangles): the model has too many reflecting surfaces for the "
      "dense operator; use --components sc, or give the rooms (or fewer surfaces) a run each";
  if (n > max_nodes) {
    const std::size_t fewest = coarsest_nodes();
    std::string message = "the reflected components' operator would have " + std::to_string(n) + " nodes (at most " +
                          std::to_string(max_nodes) + ")";
    if (fewest > max_nodes)
      message += ", and " + std::to_string(fewest) + no_size_helps;
    else
      message += ": raise --element-size (the coarsest mesh has " + std::to_string(fewest) + ")";
    throw Error(message);
  }
  // The dense matrix of the LU (8 n² bytes) must fit the memory allowed beside the rows of K
  // (ReflectionOptions::memory_bytes): checked before the rows are found, and with them after.
  const auto refuse_memory = [&](double bytes) {
    if (opt.memory_bytes == 0 || bytes <= double(opt.memory_bytes)) return;
    std::string message = "the reflected components' operator of " + std::to_string(n) + " nodes would need about ";
    message += gigabytes(bytes) + " for its dense LU and rows, more than the " + gigabytes(double(opt.memory_bytes));
    const std::size_t fewest = coarsest_nodes();
    if (8.0 * double(fewest) * double(fewest) > double(opt.memory_bytes))
      message += " allowed; its LU alone needs " + gigabytes(8.0 * double(fewest) * double(fewest)) + " with " +
                 std::to_string(fewest) + " nodes" + no_size_helps;
    else
      message += " allowed: raise --element-size (the coarsest mesh has " + std::to_string(fewest) + " nodes)";
    throw Error(message);
  };
  const double lu_bytes = 8.0 * double(n) * double(n);
  refuse_memory(lu_bytes);
  op.nodes.resize(n);
  for (std::size_t u = 0; u < nu; u += 3)
    if (index[u] >= 0) {
      op.sides.push_back(mesh.elements[u / 6]);
      op.side_polygon.push_back(mesh.surfaces[mesh.elements[u / 6].surface].occluder);
    }
  op.scale = t.scale();
  std::vector<TransportRow> rows(nu);
  const auto row_locals = for_each_sensor<Local>(
      2 * mesh.elements.size(), 8, stage_progress(opt, "reflections: the mesh's rows", "element sides", 2 * mesh.elements.size()),
      [&](std::size_t i, Local& local) {
        VisibilityCounters& counters = local.counters;
        const std::size_t e = i / 2;
        const int side = int(i % 2);
        const RadiosityElement& el = mesh.elements[e];
        if (index[unknown(e, side, 0)] < 0) return;
        const Vec3 normal = side == 0 ? el.normal : -1.0 * el.normal;
        const std::size_t own = mesh.surfaces[el.surface].occluder;
        for (int k = 0; k < 3; ++k) {
          const std::size_t u = unknown(e, side, k);
          ReflectionNode& node = op.nodes[std::size_t(index[u])];
          node.position = el.nodes[k];
          node.normal = normal;
          node.views = t.views(el.nodes[k], normal, own, true, counters);
          local.scratch.clear();  // as in receiver_row
          t.transport(mesh, el.nodes[k], normal, el.surface, counters,
                      [&](std::size_t src, int src_side, const std::array<double, 3>& c, bool, double) {
                        add_coefficients(local.scratch, src, src_side, c);
                      });
          rows[u].assign(local.scratch.begin(), local.scratch.end());
        }
      });
  for (const auto& l : row_locals) op.counters += l.counters;
  op.stages.push_back({"rows (every node's views and transport)", lap(clock)});
  if (opt.reciprocal_transport) {
    std::vector<double> weight(nu, 0.0);
    for (std::size_t u = 0; u < nu; ++u)
      if (index[u] >= 0) weight[u] = mesh.elements[u / 6].area / 3;
    op.reciprocity = make_reciprocal(rows, weight);
    op.stages.push_back({"reciprocity", lap(clock)});
  }

  std::size_t entries = 0;
  for (const TransportRow& row : rows) entries += row.size();
  refuse_memory(lu_bytes + kRowBytesPerEntry * double(entries));
  // (I − ρK)ᵀ, factorised in place.
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(Eigen::Index(n), Eigen::Index(n));
  std::vector<double> rho(n, 0.0);
  for (std::size_t u = 0; u < nu; ++u) {
    if (index[u] < 0) continue;
    const std::size_t i = std::size_t(index[u]);
    rho[i] = mesh.surfaces[mesh.elements[u / 6].surface].reflectance;
    for (const auto& [j, c] : rows[u]) a(index[j], Eigen::Index(i)) -= rho[i] * c;
  }
  rows.clear();
  // OpenBLAS's threads as many as the run's (--threads).
  const DenseLU lu(std::move(a), tbb::this_task_arena::max_concurrency());
  op.stages.push_back({"dense LU of " + std::to_string(n) + " nodes", lap(clock)});

  if (response_grids != nullptr && response_grids->size() != grids.size())
    throw Error("reflection_operator: the response grids are not as many as the grids");
  const std::vector<const SensorGrid*>& responses = response_grids != nullptr ? *response_grids : grids;
  double sensor_time = 0, solve_time = 0;
  std::size_t before = 0, sensors = 0;
  for (const SensorGrid* g : responses) sensors += g->sensors.size();
  const ProgressCallback progress = stage_progress(opt, "reflections at the sensors", "sensors", sensors);
  for (const SensorGrid* grid : responses) {
    const std::size_t m = grid->sensors.size();
    Eigen::MatrixXd st = Eigen::MatrixXd::Zero(Eigen::Index(n), Eigen::Index(m));
    std::vector<double> ground(m * scene.apertures.size(), 0.0), ground_direct(m, 0.0);
    std::vector<char> outdoors(m, 0);
    ProgressCallback grid_progress;
    if (progress) grid_progress = [&progress, before](std::size_t done) { progress(before + done); };
    before += m;
    const auto locals = for_each_sensor<VisibilityCounters>(m, 4, grid_progress, [&](std::size_t s, VisibilityCounters& counters) {
      const Sensor& sensor = grid->sensors[s];
      for (const LightView& v :
           t.views(sensor.position, sensor.normal, VisibilityOptions::kNoOccluder, grid->sees_sky_directly, counters)) {
        if (v.aperture < 0) {
          ground_direct[s] += v.sign * v.ground;
          outdoors[s] = 1;
        } else {
          ground[s * scene.apertures.size() + std::size_t(v.aperture)] += v.sign * v.ground;
        }
      }
      if (n == 0) return;
      t.transport(mesh, sensor.position, sensor.normal, std::size_t(-1), counters,
                  [&](std::size_t e, int side, const std::array<double, 3>& c, bool, double) {
                    for (int k = 0; k < 3; ++k) st(index[unknown(e, side, k)], Eigen::Index(s)) += c[k];
                  });
    });
    for (const auto& l : locals) op.counters += l;
    sensor_time += lap(clock);
    std::vector<double> w(m * n, 0.0);
    if (n > 0) {
      const Eigen::MatrixXd z = lu.solve(std::move(st), grid->first);
      for (std::size_t s = 0; s < m; ++s)
        for (std::size_t k = 0; k < n; ++k) w[s * n + k] = rho[k] * z(Eigen::Index(k), Eigen::Index(s));
    }
    solve_time += lap(clock);
    op.response.push_back(std::move(w));
    op.sensor_ground.push_back(std::move(ground));
    op.sensor_ground_direct.push_back(std::move(ground_direct));
    op.sensor_outdoors.push_back(std::move(outdoors));
    op.response_first.push_back(grid->first);
  }
  op.stages.push_back({"sensors' views and transport", sensor_time});
  op.stages.push_back({"solves for the sensors' rows of W", solve_time});
  return op;
}

}  // namespace daylit
