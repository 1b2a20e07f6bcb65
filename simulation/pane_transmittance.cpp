#include "simulation/pane_transmittance.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#include "materials/glass_transmittance.hpp"

namespace daylit {

namespace {

Vec3 pane_axis(const Aperture& a) { return normalized(newell_normal(a.polygon.vertices)); }

// The refit of Π T_a(μ) over the panes parallel to one another (materials' fit_transmittance),
// the same for every region seen through the same panes: kept, so that a sensor's every view does
// not repeat the least squares (a pure function of the polynomials; the cache is shared by the
// threads). The constant factor (open apertures' τ and the means of panes at other angles, which
// depend on the region) scales the fit and its error afterwards: were it part of the key, as it
// was until 2026-12-06, every view behind a pane at another angle would refit (on Honeybee's
// tree-crown sample a third of the run). A constant ≤ 1 leaves the scaled error within the
// tolerance the fit met.
TransmittancePolynomial product_fit(double constant, const std::vector<const Aperture*>& parallel) {
  std::vector<std::vector<double>> key;
  for (const Aperture* a : parallel) key.push_back(a->angular_transmittance);
  std::sort(key.begin(), key.end());
  static std::mutex mutex;
  static std::map<std::vector<std::vector<double>>, TransmittancePolynomial> cache;
  TransmittancePolynomial fit;
  bool found = false;
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (const auto it = cache.find(key); it != cache.end()) fit = it->second, found = true;
  }
  if (!found) {
    fit = fit_transmittance([&](double mu) {
      double t = 1;
      for (const Aperture* a : parallel) t *= evaluate_polynomial(a->angular_transmittance, mu);
      return t;
    });
    const std::lock_guard<std::mutex> lock(mutex);
    cache.emplace(std::move(key), fit);
  }
  for (double& c : fit.coefficients) c *= constant;
  fit.max_error *= std::abs(constant);
  return fit;
}

}  // namespace

std::pair<double, double> cosine_range(const SphericalRegion& region, const Vec3& w) {
  double lo = 1, hi = -1;
  for (const DirectionLoop& loop : region.loops) {
    const std::size_t m = loop.size();
    bool plus_inside = true, minus_inside = true;
    for (std::size_t i = 0; i < m; ++i) {
      const Vec3 a = normalized(loop[i]), b = normalized(loop[(i + 1) % m]);
      const double at = dot(w, a);
      lo = std::min(lo, at);
      hi = std::max(hi, at);
      const Vec3 normal = cross(a, b);  // the arc's plane; inside the loop: u·normal ≥ 0
      const double side = dot(w, normal);
      plus_inside &= side >= 0;
      minus_inside &= side <= 0;
      const double length = norm(normal);
      if (length == 0) continue;
      // w's component in the arc's plane, c = w − (w·n̂)n̂, lies on the arc when it is between a
      // and b: on the inner sides of the planes through n̂ and a, and n̂ and b.
      const Vec3 nh = (1 / length) * normal;
      const Vec3 c = w - dot(w, nh) * nh;
      if (norm(c) == 0) continue;
      const Vec3 cu = normalized(c);
      for (const Vec3& e : {cu, -1.0 * cu})
        if (dot(cross(a, e), nh) >= 0 && dot(cross(e, b), nh) >= 0) {
          lo = std::min(lo, dot(w, e));
          hi = std::max(hi, dot(w, e));
        }
    }
    if (plus_inside) hi = 1;
    if (minus_inside) lo = -1;
  }
  return {lo, hi};
}

std::vector<PaneTerm> pane_terms(const Scene& scene, std::size_t aperture, const PaneView& view) {
  std::vector<PaneTerm> terms;
  terms.push_back({panes_through(scene, aperture, view.region, view.panes), 1.0, aperture, view.panes});
  std::vector<std::uint32_t> others;
  for (std::uint32_t b : view.panes)
    if (b != view.last) others.push_back(b);
  terms.push_back({panes_through(scene, view.last, view.region, others), -1.0, view.last, others});
  return terms;
}

PanesThrough panes_through(const Scene& scene, std::size_t aperture, const SphericalRegion& region,
                           const std::vector<std::uint32_t>& panes) {
  // The axis of the exact polynomial: the aperture's, or where the aperture's transmittance is
  // constant, the first angle-dependent pane's.
  std::vector<const Aperture*> factors{&scene.apertures.at(aperture)};
  for (std::uint32_t b : panes) factors.push_back(&scene.apertures.at(b));
  const auto angular = std::find_if(factors.begin(), factors.end(), [](const Aperture* a) { return !a->angular_transmittance.empty(); });
  const Aperture& own = angular == factors.end() ? *factors[0] : **angular;
  PanesThrough out;
  out.combined.polygon = own.polygon;
  double constant = 1.0;
  const Vec3 axis = pane_axis(own);
  std::vector<const Aperture*> parallel;  // angle-dependent factors about that axis
  for (const Aperture* factor : factors) {
    const Aperture& pane = *factor;
    if (pane.angular_transmittance.empty()) {
      constant *= pane.transmittance;
      continue;
    }
    const Vec3 w = pane_axis(pane);
    if (norm(cross(w, axis)) <= 1e-9) {
      parallel.push_back(&pane);
      continue;
    }
    // Seen through the pane, w·u has one sign over the region; the cosine of incidence is |w·u|.
    auto [lo, hi] = cosine_range(region, w);
    if (hi <= 0) std::swap(lo, hi), lo = -lo, hi = -hi;
    lo = std::clamp(lo, 0.0, 1.0);
    hi = std::clamp(hi, 0.0, 1.0);
    double t_lo = 2, t_hi = -1;
    constexpr int kSamples = 16;  // the fit need not be monotone between the extremes
    for (int i = 0; i <= kSamples; ++i) {
      const double t = evaluate_polynomial(pane.angular_transmittance, lo + (hi - lo) * i / kSamples);
      t_lo = std::min(t_lo, t);
      t_hi = std::max(t_hi, t);
    }
    const double mean = 0.5 * (t_lo + t_hi);
    constant *= mean;
    if (mean > 0) out.spread += 0.5 * (t_hi - t_lo) / mean;
  }
  out.combined.transmittance = constant;
  if (parallel.size() == 1) {
    out.combined.angular_transmittance = parallel[0]->angular_transmittance;
    for (double& c : out.combined.angular_transmittance) c *= constant;
    out.combined.angular_fit_error = constant * parallel[0]->angular_fit_error;
    out.combined.transmittance = constant * evaluate_polynomial(parallel[0]->angular_transmittance, 1.0);
  } else if (parallel.size() > 1) {
    const TransmittancePolynomial fit = product_fit(constant, parallel);
    double error = fit.max_error;
    for (const Aperture* a : parallel) error += constant * a->angular_fit_error;
    out.combined.angular_transmittance = fit.coefficients;
    out.combined.angular_fit_error = error;
    out.combined.transmittance = evaluate_polynomial(fit.coefficients, 1.0);
  }
  return out;
}

TransmittanceAlong::TransmittanceAlong(const Scene& scene, std::size_t aperture, const std::vector<std::uint32_t>& panes) {
  const auto add = [&](const Aperture& a) {
    if (a.angular_transmittance.empty()) constant_ *= a.transmittance;
    else factors_.push_back({pane_axis(a), &a.angular_transmittance});
  };
  add(scene.apertures.at(aperture));
  for (std::uint32_t b : panes) add(scene.apertures.at(b));
}

double TransmittanceAlong::operator()(const Vec3& u) const noexcept {
  double t = constant_;
  for (const Factor& f : factors_) t *= evaluate_polynomial(*f.angular, std::abs(dot(f.axis, u)));
  return t;
}

double transmittance_along(const Scene& scene, std::size_t aperture, const std::vector<std::uint32_t>& panes, const Vec3& u) {
  return TransmittanceAlong(scene, aperture, panes)(u);
}

}  // namespace daylit
