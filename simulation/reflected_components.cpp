#include "simulation/reflected_components.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "illumination/moments.hpp"
#include "simulation/element_transport.hpp"
#include "simulation/radiosity_solver.hpp"
#include "simulation/sensor_loop.hpp"

namespace daylit {

namespace {

constexpr double kPi = std::numbers::pi;

// ---- Apertures grouped by transmittance ------------------------------------------------------
// Light seen through an aperture is weighted by its transmittance; apertures that transmit alike
// share one "through" engine, so the engines grow with the kinds of glazing, not the windows.
struct ApertureGroup {
  std::vector<std::size_t> apertures;
  double transmittance = 1;
  std::vector<double> angular;  // T(μ) = Σ c_k μ^k, empty: constant
  Vec3 pane_normal{};           // of the first aperture (glass: μ about it)
  // T at the cosine μ (|μ|: both directions through the pane).
  double at(double mu) const {
    if (angular.empty()) return transmittance;
    mu = std::min(1.0, std::abs(mu));
    double t = 0;
    for (std::size_t k = angular.size(); k-- > 0;) t = t * mu + angular[k];
    return std::max(0.0, t);
  }
};

std::vector<ApertureGroup> group_apertures(const Scene& scene) {
  std::vector<ApertureGroup> groups;
  for (std::size_t a = 0; a < scene.apertures.size(); ++a) {
    const Aperture& ap = scene.apertures[a];
    auto it = std::find_if(groups.begin(), groups.end(), [&](const ApertureGroup& g) {
      return g.transmittance == ap.transmittance && g.angular == ap.angular_transmittance;
    });
    if (it == groups.end()) {
      groups.push_back({{}, ap.transmittance, ap.angular_transmittance, normalized(newell_normal(ap.polygon.vertices))});
      it = groups.end() - 1;
    }
    it->apertures.push_back(a);
  }
  return groups;
}

struct Box {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi = -1.0 * lo;
  void add(const Vec3& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  bool empty() const { return !(lo.x <= hi.x); }
  bool meets(const Box& o, double margin) const {
    return lo.x - margin <= o.hi.x && o.lo.x - margin <= hi.x && lo.y - margin <= o.hi.y &&
           o.lo.y - margin <= hi.y && lo.z - margin <= o.hi.z && o.lo.z - margin <= hi.z;
  }
  double distance(const Vec3& p) const {
    const double dx = std::max({lo.x - p.x, 0.0, p.x - hi.x});
    const double dy = std::max({lo.y - p.y, 0.0, p.y - hi.y});
    const double dz = std::max({lo.z - p.z, 0.0, p.z - hi.z});
    return std::hypot(dx, dy, dz);
  }
};

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

// ---- The transport model ----------------------------------------------------------------------
class Transport {
 public:
  Transport(const Scene& scene, const std::vector<double>& reflectance, const VisibilityEngine& engine,
            const std::vector<const SensorGrid*>& grids, const ReflectionOptions& options)
      : scene_(scene), reflectance_(reflectance), engine_(engine), options_(options), groups_(group_apertures(scene)) {
    e_out_ = unobstructed_horizontal_irradiance(options.sky);
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
    scale_ = all.empty() ? 1 : std::max({all.hi.x - all.lo.x, all.hi.y - all.lo.y, all.hi.z - all.lo.z, 1e-300});
    mesh_ = mesh_surfaces(scene.occluders, reflectance, [&](const RadiosityElement& e) { return max_edge(e); });
    build_luminaire_engines();
    build_sky_box(all);
  }

  const RadiosityMesh& mesh() const { return mesh_; }
  RadiosityMesh& mesh() { return mesh_; }
  double e_out() const { return e_out_; }
  std::size_t unknowns() const { return 6 * mesh_.elements.size(); }
  std::size_t surface_count() const { return mesh_.surfaces.size(); }

  double max_edge(const RadiosityElement& e) const {
    const Vec3 c = e.point(1.0 / 3, 1.0 / 3, 1.0 / 3);
    double d = sensor_box_.empty() ? std::numeric_limits<double>::infinity() : sensor_box_.distance(c);
    for (const Box& b : aperture_boxes_) d = std::min(d, b.distance(c));
    if (!std::isfinite(d)) d = 0;
    return std::max(options_.element_size, options_.grading * d);
  }

  // First bounce at (x, n) through the apertures: the sky above the horizon and the far ground
  // below it, times the transmittance. Glass: the sky and the ground (a uniform luminance) through
  // the glazing moments of T(μ), exact.
  struct ThroughApertures {
    double sky = 0, ground = 0;
  };
  // `own`: the occluder the receiver lies on (kNoOccluder for a sensor), which must not hide
  // what the receiver sees.
  ThroughApertures through_apertures(const Vec3& x, const Vec3& n, std::size_t own, bool with_sky,
                                     VisibilityCounters& c) const {
    ThroughApertures out;
    if (!with_sky && ground_luminance_ == 0) return out;
    VisibilityOptions full, half;
    full.clip_to_horizon = false;
    full.excluded_occluder = half.excluded_occluder = own;
    for (std::size_t a = 0; a < engine_.aperture_count(); ++a) {
      const Aperture& ap = scene_.apertures[a];
      // As in direct(): nothing of the aperture visible at all, nothing above the horizon.
      const SphericalRegion all = engine_.visible_region(x, n, a, c, full);
      if (all.empty()) continue;
      const SphericalRegion above = above_horizon(engine_, x, n, a, c, half);
      if (ap.angular_transmittance.empty()) {
        if (with_sky && !above.empty()) out.sky += ap.transmittance * sky_irradiance(above, n, options_.sky);
        if (ground_luminance_ > 0)
          out.ground += ap.transmittance * ground_luminance_ *
                        (lambert(all, n) - (above.empty() ? 0.0 : lambert(above, n)));
      } else {
        const Vec3 pane = normalized(newell_normal(ap.polygon.vertices));
        if (with_sky && !above.empty())
          out.sky += sky_irradiance_through_glazing(above, n, options_.sky, pane, ap.angular_transmittance);
        if (ground_luminance_ > 0) {
          const auto glazed = [&](const SphericalRegion& r) {
            return r.empty() ? 0.0
                             : sky_irradiance_through_glazing(r, n, SkyModel::uniform, pane, ap.angular_transmittance);
          };
          out.ground += ground_luminance_ * (glazed(all) - glazed(above));
        }
      }
    }
    return out;
  }

  // The sky and far ground seen directly (not through an aperture): the six inward faces of the
  // box around the model as apertures, every opaque and aperture polygon as an occluder.
  double direct(const Vec3& x, const Vec3& n, std::size_t own, VisibilityCounters& c, bool& empty) const {
    double e = 0;
    empty = true;
    VisibilityOptions full, half;
    full.clip_to_horizon = false;
    full.excluded_occluder = half.excluded_occluder = own;  // the box's occluders start with the scene's
    for (std::size_t f = 0; f < sky_box_->aperture_count(); ++f) {
      // The region above the horizon is part of the whole one: where that is empty (every
      // receiver inside a closed room), the second query is left out, exactly.
      const SphericalRegion all = sky_box_->visible_region(x, n, f, c, full);
      if (all.empty()) continue;
      empty = false;
      const SphericalRegion above = above_horizon(*sky_box_, x, n, f, c, half);
      if (!above.empty()) e += sky_irradiance(above, n, options_.sky);
      if (ground_luminance_ > 0) e += ground_luminance_ * (lambert(all, n) - (above.empty() ? 0.0 : lambert(above, n)));
    }
    return e;
  }

  // Every element's coefficients at (x, n): sink(element, side, c, through, spread), c such that
  // the irradiance is Σ_k c_k M_k (through: already weighted by the transmittance, as the
  // difference of the two occluder sets), spread: the relative spread of T(μ) over the element's
  // directions (glass), for the error estimate.
  template <class Sink>
  void transport(const Vec3& x, const Vec3& n, std::size_t own_surface, VisibilityCounters& counters, Sink&& sink) const {
    // The surface is a luminaire: nothing beyond its plane hides it, and it does not hide itself
    // (the receiver's own polygon lies in the receiver's tangent plane and casts no shadow).
    VisibilityOptions opt;
    opt.clip_to_horizon = false;
    opt.occluders_beyond = false;
    for (std::size_t s = 0; s < mesh_.surfaces.size(); ++s) {
      if (s == own_surface) continue;
      const RadiositySurface& surf = mesh_.surfaces[s];
      const double facing = dot(surf.normal, x - surf.point);
      if (facing == 0) continue;
      const int side = facing > 0 ? 0 : 1;
      const Polygon& poly = scene_.occluders[surf.occluder];
      bool in_front = false;
      for (const Vec3& v : poly.vertices) in_front |= dot(n, v - x) > 0;
      if (!in_front) continue;
      opt.excluded_occluder = surf.occluder;
      const std::uint64_t clipped = counters.pairs_clipped;
      const SphericalRegion inside = inside_->visible_region(x, n, s, counters, opt);
      const bool inside_free = counters.pairs_clipped == clipped;
      std::vector<SphericalRegion> inside_parts;
      inside_parts.reserve(surf.elements.size());
      for (std::size_t e : surf.elements) {
        inside_parts.push_back(inside.empty() ? SphericalRegion{}
                                              : element_region(inside, inside_free, mesh_.elements[e], x, n));
        const auto c = element_irradiance_coefficients(inside_parts.back(), mesh_.elements[e], x, n);
        sink(e, side, c, false, 0.0);
      }
      // Through each group of apertures: only where one of its apertures may stand between x
      // and the surface (boxes, conservatively: a group that cannot is left out exactly).
      Box reach = surf_boxes_[s];
      reach.add(x);
      for (std::size_t g = 0; g < groups_.size(); ++g) {
        bool may_cross = false;
        for (std::size_t a : groups_[g].apertures) may_cross |= reach.meets(aperture_boxes_[a], 1e-9 * scale_);
        if (!may_cross) continue;
        const std::uint64_t clipped_t = counters.pairs_clipped;
        const SphericalRegion through = through_[g].visible_region(x, n, s, counters, opt);
        if (through.empty()) continue;
        const bool through_free = counters.pairs_clipped == clipped_t;
        const ApertureGroup& group = groups_[g];
        for (std::size_t i = 0; i < surf.elements.size(); ++i) {
          const RadiosityElement& el = mesh_.elements[surf.elements[i]];
          const SphericalRegion part = element_region(through, through_free, el, x, n);
          if (part.empty()) continue;
          auto c = element_irradiance_coefficients(part, el, x, n);
          const auto c_in = element_irradiance_coefficients(inside_parts[i], el, x, n);
          double t = group.transmittance, spread = 0;
          if (!group.angular.empty()) {
            // T(μ) taken at the centroid's direction; its spread over the vertices' directions
            // bounds (for T monotone in μ over the element, as Fresnel's is) the error of that.
            const Vec3 cen = normalized(el.point(1.0 / 3, 1.0 / 3, 1.0 / 3) - x);
            t = group.at(dot(cen, group.pane_normal));
            double lo = t, hi = t;
            for (const Vec3& v : el.vertices) {
              const double tv = group.at(dot(normalized(v - x), group.pane_normal));
              lo = std::min(lo, tv);
              hi = std::max(hi, tv);
            }
            spread = t > 0 ? (hi - lo) / t : 0;
          }
          for (int k = 0; k < 3; ++k) c[k] = t * (c[k] - c_in[k]);
          sink(surf.elements[i], side, c, true, spread);
        }
      }
    }
  }

  void remesh_boxes() {
    surf_boxes_.clear();
    for (const auto& s : mesh_.surfaces) surf_boxes_.push_back(box_of(scene_.occluders[s.occluder].vertices));
  }

 private:
  // The surfaces as luminaires (aperture s: surface s), seen past the opaque polygons, which keep
  // their indices in Scene::occluders so that the luminaire's own can be excluded by index:
  // `inside_` also past every aperture (what is seen inside), `through_[g]` past the apertures
  // of the other groups only, so that through_[g] − inside_ is what is seen through group g.
  // The cut to the receiver's side of the luminaire's plane is the engine's, exact
  // (VisibilityOptions::occluders_beyond), so one engine serves every surface and both sides.
  void build_luminaire_engines() {
    Scene base;
    for (const RadiositySurface& s : mesh_.surfaces) base.apertures.push_back({scene_.occluders[s.occluder], 1.0});
    base.occluders = scene_.occluders;
    Scene inside = base;
    for (const Aperture& a : scene_.apertures) inside.occluders.push_back(a.polygon);
    inside_ = std::make_unique<VisibilityEngine>(inside, options_.mode);
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      Scene t = base;
      for (std::size_t h = 0; h < groups_.size(); ++h)
        if (h != g)
          for (std::size_t a : groups_[h].apertures) t.occluders.push_back(scene_.apertures[a].polygon);
      through_.emplace_back(t, options_.mode);
    }
    remesh_boxes();
  }

  void build_sky_box(const Box& all) {
    const double m = 2 * scale_ + 1;
    const Vec3 lo = all.lo - Vec3{m, m, m}, hi = all.hi + Vec3{m, m, m};
    Scene box;
    for (const Polygon& p : scene_.occluders) box.occluders.push_back(p);
    for (const Aperture& a : scene_.apertures) box.occluders.push_back(a.polygon);
    const auto face = [&](std::vector<Vec3> v) {
      Polygon p;
      p.vertices = std::move(v);
      p.name = "sky box";
      box.apertures.push_back({p, 1.0});
    };
    face({{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z}});
    face({{lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z}});
    face({{lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, lo.y, lo.z}});
    face({{lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}});
    face({{lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {lo.x, lo.y, hi.z}});
    face({{hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}});
    sky_box_ = std::make_unique<VisibilityEngine>(box, options_.mode);
  }

  const Scene& scene_;
  const std::vector<double>& reflectance_;
  const VisibilityEngine& engine_;
  ReflectionOptions options_;
  std::vector<ApertureGroup> groups_;
  double e_out_ = 1, ground_luminance_ = 0, scale_ = 1;
  std::vector<Box> aperture_boxes_, surf_boxes_;
  Box sensor_box_;
  RadiosityMesh mesh_;
  std::unique_ptr<VisibilityEngine> inside_;
  std::vector<VisibilityEngine> through_;  // per aperture group
  std::unique_ptr<VisibilityEngine> sky_box_;
};

std::size_t unknown(std::size_t element, int side, int k) { return 6 * element + 3 * std::size_t(side) + std::size_t(k); }

// What a receiver on an element side needs: its first bounce and its row of K.
struct ReceiverRow {
  double first_bounce = 0;
  TransportRow row;
  bool direct_empty = true;
};

ReceiverRow receiver_row(const Transport& t, const Vec3& x, const Vec3& n, std::size_t own_surface,
                         VisibilityCounters& counters) {
  ReceiverRow r;
  const std::size_t own = t.mesh().surfaces[own_surface].occluder;
  const auto a = t.through_apertures(x, n, own, true, counters);
  r.first_bounce = a.sky + a.ground + t.direct(x, n, own, counters, r.direct_empty);
  t.transport(x, n, own_surface, counters, [&](std::size_t e, int side, const std::array<double, 3>& c, bool, double) {
    for (int k = 0; k < 3; ++k)
      if (c[k] != 0) r.row.emplace_back(std::uint32_t(unknown(e, side, k)), c[k]);
  });
  return r;
}

struct Local {
  VisibilityCounters counters;
  std::size_t direct_empty = 0, direct = 0;
  std::vector<double> importance;
};

// Rows of K and first bounce at every node, in parallel over element sides.
std::vector<ReceiverRow> node_rows(const Transport& t, ReflectionResult& result) {
  const RadiosityMesh& mesh = t.mesh();
  const std::size_t ne = mesh.elements.size();
  std::vector<ReceiverRow> rows(t.unknowns());
  const auto locals = for_each_sensor<Local>(2 * ne, 8, {}, [&](std::size_t i, Local& local) {
    const std::size_t e = i / 2;
    const int side = int(i % 2);
    const RadiosityElement& el = mesh.elements[e];
    const Vec3 n = side == 0 ? el.normal : -1.0 * el.normal;
    for (int k = 0; k < 3; ++k) {
      ReceiverRow r = receiver_row(t, el.nodes[k], n, el.surface, local.counters);
      local.direct_empty += r.direct_empty;
      ++local.direct;
      rows[unknown(e, side, k)] = std::move(r);
    }
  });
  result.receivers_direct_empty = result.receivers_direct = 0;
  for (const auto& l : locals) {
    result.counters += l.counters;
    result.receivers_direct_empty += l.direct_empty;
    result.receivers_direct += l.direct;
  }
  return rows;
}

double check_inputs(const Scene& scene, const std::vector<double>& reflectance, const ReflectionOptions& options) {
  if (!(options.ground_reflectance >= 0 && options.ground_reflectance < 1))
    throw Error("ground reflectance " + std::to_string(options.ground_reflectance) + " is outside [0, 1)");
  if (reflectance.size() != scene.occluders.size()) throw Error("one reflectance per occluder is needed");
  double rho_max = 0;
  for (std::size_t i = 0; i < reflectance.size(); ++i) {
    if (!(reflectance[i] >= 0 && reflectance[i] < 1))
      throw input_error(scene.occluders[i].where, "reflectance " + std::to_string(reflectance[i]) + " of '" +
                                                      scene.occluders[i].name + "' is outside [0, 1)");
    rho_max = std::max(rho_max, reflectance[i]);
  }
  return rho_max;
}

}  // namespace

RadiositySystem radiosity_system(const Scene& scene, const std::vector<double>& reflectance,
                                 const VisibilityEngine& engine, const std::vector<const SensorGrid*>& grids,
                                 const ReflectionOptions& options) {
  check_inputs(scene, reflectance, options);
  const Transport t(scene, reflectance, engine, grids, options);
  ReflectionResult scratch;
  std::vector<ReceiverRow> rows = node_rows(t, scratch);
  RadiositySystem sys;
  sys.mesh = t.mesh();
  for (std::size_t u = 0; u < rows.size(); ++u) {
    sys.first_bounce.push_back(rows[u].first_bounce);
    sys.reflectance.push_back(sys.mesh.surfaces[sys.mesh.elements[u / 6].surface].reflectance);
    sys.rows.push_back(std::move(rows[u].row));
  }
  return sys;
}

ReflectionResult reflected_components(const Scene& scene, const std::vector<double>& reflectance,
                                      const VisibilityEngine& engine, const std::vector<const SensorGrid*>& grids,
                                      const ReflectionOptions& options, const ProgressCallback& progress) {
  const double rho_max = check_inputs(scene, reflectance, options);
  ReflectionResult result;
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

  Transport t(scene, reflectance, engine, grids, options);
  const double to_percent = 100 / t.e_out();

  for (int round = 0;; ++round) {
    RadiosityMesh& mesh = t.mesh();
    const std::size_t ne = mesh.elements.size(), nu = t.unknowns();
    std::vector<ReceiverRow> rows = node_rows(t, result);
    std::vector<double> rho(nu), source(nu);
    std::vector<TransportRow> k_rows(nu);
    for (std::size_t u = 0; u < nu; ++u) {
      const double r = mesh.surfaces[mesh.elements[u / 6].surface].reflectance;
      rho[u] = r;
      source[u] = r * rows[u].first_bounce;
      k_rows[u] = std::move(rows[u].row);
    }
    const RadiositySolution sol = solve_radiosity(k_rows, rho, source);
    const std::vector<double>& m = sol.exitance;
    result.sweeps = sol.sweeps;
    result.solver_change = sol.last_change;

    // ---- Energy balance (see the header): first bounce, absorbed, escaping, by the nodes' rule.
    double first = 0, absorbed = 0, escaping = 0;
    for (std::size_t u = 0; u < nu; ++u) {
      const double w = mesh.elements[u / 6].area / 3;
      const double e_total = rows[u].first_bounce + [&] {
        double s = 0;
        for (const auto& [j, c] : k_rows[u]) s += c * m[j];
        return s;
      }();
      double f = 0;
      for (const auto& [j, c] : k_rows[u]) f += c;
      first += w * rows[u].first_bounce;
      absorbed += w * (1 - rho[u]) * e_total;
      escaping += w * m[u] * (1 - f);
    }
    result.flux_first_bounce = first;
    result.flux_absorbed = absorbed;
    result.flux_escaping = escaping;
    result.balance_mismatch = first > 0 ? (first - absorbed - escaping) / first : 0;

    // ---- Residual at check points other than the nodes, per element side.
    static constexpr double kCheck[4][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.8, 0.1, 0.1}, {0.1, 0.8, 0.1}, {0.1, 0.1, 0.8}};
    std::vector<double> residual(2 * ne, 0.0), residual_peak(2 * ne, 0.0);
    const auto rlocals = for_each_sensor<Local>(2 * ne, 8, {}, [&](std::size_t i, Local& local) {
      const std::size_t e = i / 2;
      const int side = int(i % 2);
      const RadiosityElement& el = mesh.elements[e];
      const Vec3 n = side == 0 ? el.normal : -1.0 * el.normal;
      const double r = mesh.surfaces[el.surface].reflectance;
      // A sensor's irradiance integrates the exitance's error over each element, so what it
      // needs is the element's mean |r|, not its maximum: the mean over the check points.
      double sum = 0, worst = 0;
      for (const auto& b : kCheck) {
        const Vec3 y = el.point(b[0], b[1], b[2]);
        const ReceiverRow row = receiver_row(t, y, n, el.surface, local.counters);
        double e_total = row.first_bounce;
        for (const auto& [j, c] : row.row) e_total += c * m[j];
        double m_h = 0;
        for (int k = 0; k < 3; ++k) m_h += el.basis(k, y) * m[unknown(e, side, k)];
        sum += std::abs(m_h - r * e_total);
        worst = std::max(worst, std::abs(m_h - r * e_total));
      }
      residual[i] = sum / 4;
      residual_peak[i] = worst;
    });
    for (const auto& l : rlocals) result.counters += l.counters;
    result.residual_max = 0;
    std::vector<double> r_source(nu);
    for (std::size_t u = 0; u < nu; ++u) {
      r_source[u] = residual[u / 3];
      result.residual_max = std::max(result.residual_max, residual_peak[u / 3]);
    }
    // ē = |r̄| + ρ|K| ē: the residual carried through every further bounce.
    const std::vector<double> e_bar = solve_radiosity(k_rows, rho, r_source, true).exitance;

    // ---- Sensors: ERC (far ground and elements seen through apertures), IRC (elements seen
    // inside), and the error estimate with each element's share of it.
    double worst_sensor = 0;
    std::vector<double> importance(ne, 0.0);
    for (std::size_t g = 0; g < grids.size(); ++g) {
      const SensorGrid& grid = *grids[g];
      SensorReflections& out = result.grids[g];
      const auto slocals = for_each_sensor<Local>(grid.sensors.size(), 4, progress, [&](std::size_t i, Local& local) {
        if (local.importance.empty()) local.importance.assign(ne, 0.0);
        const Sensor& s = grid.sensors[i];
        const auto a = t.through_apertures(s.position, s.normal, VisibilityOptions::kNoOccluder, false, local.counters);
        double erc = a.ground, irc = 0, err = 0;
        t.transport(s.position, s.normal, std::size_t(-1), local.counters,
                    [&](std::size_t e, int side, const std::array<double, 3>& c, bool through, double spread) {
                      double value = 0, bound = 0;
                      for (int k = 0; k < 3; ++k) {
                        value += c[k] * m[unknown(e, side, k)];
                        bound += std::abs(c[k]) * e_bar[unknown(e, side, k)];
                      }
                      (through ? erc : irc) += value;
                      const double share = bound + spread * std::abs(value);
                      err += share;
                      local.importance[e] = std::max(local.importance[e], share);
                    });
        out.erc_percent[i] = to_percent * erc;
        out.irc_percent[i] = to_percent * irc;
        out.error_percent[i] = to_percent * err;
      });
      for (const auto& l : slocals) {
        result.counters += l.counters;
        for (std::size_t e = 0; e < l.importance.size(); ++e) importance[e] = std::max(importance[e], l.importance[e]);
      }
      for (double e : out.error_percent) worst_sensor = std::max(worst_sensor, e);
    }
    result.error_by_round.push_back(worst_sensor);
    result.max_error_percent = worst_sensor;
    result.elements = ne;
    result.unknowns = nu;
    result.max_level = mesh.max_level;
    result.refinements = round;
    if (worst_sensor <= options.tolerance_percent || round >= options.max_refinements || ne == 0) break;
    // Split the elements whose share of some sensor's estimate is largest: those above half the
    // largest share, and every one whose share alone exceeds a tenth of the tolerance.
    const double top = *std::max_element(importance.begin(), importance.end());
    std::vector<bool> split(ne, false);
    for (std::size_t e = 0; e < ne; ++e)
      split[e] = importance[e] >= 0.5 * top || to_percent * importance[e] > 0.1 * options.tolerance_percent;
    refine_mesh(mesh, split);
    t.remesh_boxes();
  }
  return result;
}

}  // namespace daylit
