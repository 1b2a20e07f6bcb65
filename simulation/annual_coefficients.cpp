#include "simulation/annual_coefficients.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>

#include "geometry/error.hpp"
#include "illumination/fan_product_rule.hpp"
#include "illumination/gauss_legendre.hpp"
#include "materials/glass_transmittance.hpp"
#include "simulation/pane_transmittance.hpp"
#include "simulation/sensor_loop.hpp"

namespace daylit {

namespace {

using UnitRule = quadrature::UnitGaussRule;
const auto unit_rule = quadrature::gauss_legendre_unit;

// φ_j(u) for every j, into `out` (size annual_basis_size(degree)).
void evaluate_basis(const Vec3& u, int degree, double* out) {
  const double t = 2 * u.z - 1;
  const double family[kAnnualBasisFamilies] = {1, u.x * u.x, u.y * u.y, u.z * u.z, u.x * u.y, u.x * u.z, u.y * u.z};
  double t0 = 1, t1 = t;
  for (int k = 0; k <= degree; ++k) {
    const double tk = k == 0 ? 1 : k == 1 ? t : 2 * t * t1 - t0;
    if (k >= 2) {
      t0 = t1;
      t1 = tk;
    }
    for (int f = 0; f < kAnnualBasisFamilies; ++f) out[annual_basis_index(f, k, degree)] = family[f] * tk;
  }
}

// Σ over the region of φ_j(u) T(u) (n·u) dσ and of T(u)(n·u) dσ, by the n×n collapsed product rule
// on the region's fan triangles split to sides of at most kMomentMaxSide (fan_product_rule.hpp).
void integrate_basis(const SphericalRegion& region, const Vec3& n, const SeenTransmittance& transmittance, int degree,
                     const UnitRule& rule, double* moments, double& lambert) {
  std::vector<double> phi(std::size_t(annual_basis_size(degree)));
  const int size = annual_basis_size(degree);
  for_each_fan_node(region, rule, kMomentMaxSide, [&](const Vec3& u, double area) {
    const double weight = area * dot(n, u) * transmittance(u);
    lambert += weight;
    evaluate_basis(u, degree, phi.data());
    for (int j = 0; j < size; ++j) moments[j] += weight * phi[std::size_t(j)];
  });
}

// Extend [lo, hi] by the range of z·u over the region's arcs: z·u(t) = A cos t + B sin t on
// u(t) = a cos t + q sin t (q ⊥ a in the arc's plane), extreme at its ends or where tan t = B/A.
void extend_uz_range(const SphericalRegion& region, double& lo, double& hi) {
  for (const DirectionLoop& loop : region.loops) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec3 a = normalized(loop[i]), b = normalized(loop[(i + 1) % loop.size()]);
      lo = std::min(lo, a.z);
      hi = std::max(hi, a.z);
      const Vec3 m = cross(a, b);
      if (norm(m) == 0) continue;
      const Vec3 q = normalized(cross(m, a));
      const double theta = std::atan2(norm(m), dot(a, b));
      const double t = std::atan2(q.z, a.z);  // the top of the great circle; t + π its bottom
      for (double tt : {t, t + std::numbers::pi, t - std::numbers::pi}) {
        if (tt > 0 && tt < theta) {
          const double z = a.z * std::cos(tt) + q.z * std::sin(tt);
          lo = std::min(lo, z);
          hi = std::max(hi, z);
        }
      }
    }
  }
}

}  // namespace

ApertureTransmittance::ApertureTransmittance(const Aperture& aperture) : constant_(aperture.transmittance) {
  if (aperture.angular_transmittance.empty()) return;
  axis_ = normalized(newell_normal(aperture.polygon.vertices));
  angular_ = &aperture.angular_transmittance;
}

double ApertureTransmittance::operator()(const Vec3& u) const noexcept {
  return angular_ != nullptr ? evaluate_polynomial(*angular_, std::abs(dot(axis_, u))) : constant_;
}

SeenTransmittance::SeenTransmittance(const Scene& scene, const SeenRegion& seen) {
  if (seen.through)
    along_.emplace(scene, std::size_t(seen.aperture), seen.panes);
  else
    aperture_.emplace(scene.apertures[std::size_t(seen.aperture)]);
}

double SeenTransmittance::operator()(const Vec3& u) const noexcept { return along_ ? (*along_)(u) : (*aperture_)(u); }

void SeenTransmittance::multiply(const double* x, const double* y, const double* z, std::size_t n,
                                 double* values) const noexcept {
  if (along_) {
    for (std::size_t i = 0; i < n; ++i) values[i] *= (*along_)(Vec3{x[i], y[i], z[i]});
    return;
  }
  const std::vector<double>* angular = aperture_->angular();
  if (angular == nullptr) {
    for (std::size_t i = 0; i < n; ++i) values[i] *= aperture_->constant();
    return;
  }
  // Horner's rule (evaluate_polynomial's arithmetic, in the same order), a block of directions
  // at a time with the loop over directions innermost: each direction's chain of multiply-adds
  // is sequential, the block's chains are independent and run side by side.
  const std::vector<double>& c = *angular;
  const Vec3& axis = aperture_->axis();
  if (c.empty()) {
    for (std::size_t i = 0; i < n; ++i) values[i] *= 0.0;  // the zero polynomial
    return;
  }
  constexpr std::size_t kBlock = 64;
  std::array<double, kBlock> mu, t;
  for (std::size_t start = 0; start < n; start += kBlock) {
    const std::size_t m = std::min(kBlock, n - start);
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t j = start + i;
      mu[i] = std::abs(axis.x * x[j] + axis.y * y[j] + axis.z * z[j]);
      t[i] = c.back();
    }
    for (std::size_t k = c.size() - 1; k-- > 0;)
      for (std::size_t i = 0; i < m; ++i) t[i] = t[i] * mu[i] + c[k];
    for (std::size_t i = 0; i < m; ++i) values[start + i] *= t[i];
  }
}

WindowGroups window_groups(const Scene& scene) {
  WindowGroups g;
  std::map<std::string, int> index;
  for (const Aperture& a : scene.apertures) {
    const auto [it, added] = index.emplace(a.polygon.material, int(g.names.size()));
    if (added) g.names.push_back(a.polygon.material);
    g.group_of_aperture.push_back(it->second);
  }
  return g;
}

SensorCoefficients sensor_coefficients(const VisibilityEngine& engine, const Scene& scene, const Sensor& sensor,
                                       const WindowGroups& groups, int degree, VisibilityCounters& counters) {
  static const UnitRule low = unit_rule(kOrderLow), high = unit_rule(kOrderHigh);
  const std::size_t size = std::size_t(annual_basis_size(degree)), group_count = groups.names.size();
  SensorCoefficients c;
  c.sky_direct.assign(group_count * size, 0.0);
  c.lambert.assign(group_count, 0.0);
  std::vector<double> coarse(group_count * size, 0.0), coarse_lambert(group_count, 0.0);
  for (std::size_t a = 0; a < engine.aperture_count(); ++a) {
    ApertureView view = engine.aperture_view(sensor.position, sensor.normal, a, counters);
    // A region seen through `own` (its window group) with `through`'s transmittance, `sign`
    // −1 for a count taken back (PaneView).
    const auto add = [&](std::size_t own, SphericalRegion region, std::shared_ptr<const Aperture> through,
                         std::vector<std::uint32_t> panes, double sign) {
      SeenRegion& seen = c.regions.emplace_back(SeenRegion{int(own), std::move(region), std::move(through), std::move(panes), sign});
      const SeenTransmittance transmittance(scene, seen);
      const std::size_t gg = std::size_t(groups.group_of_aperture[own]);
      std::vector<double> moments(size, 0.0), moments_low(size, 0.0);
      double l = 0, l_low = 0;
      integrate_basis(seen.region, sensor.normal, transmittance, degree, high, moments.data(), l);
      integrate_basis(seen.region, sensor.normal, transmittance, degree, low, moments_low.data(), l_low);
      for (std::size_t j = 0; j < size; ++j) {
        c.sky_direct[gg * size + j] += sign * moments[j];
        coarse[gg * size + j] += sign * moments_low[j];
      }
      c.lambert[gg] += sign * l;
      coarse_lambert[gg] += sign * l_low;
      extend_uz_range(seen.region, c.min_uz, c.max_uz);
    };
    if (!view.region.empty()) add(a, std::move(view.region), nullptr, {}, 1.0);
    // Through panes in front as well, with their transmittances, each term in its own pane's
    // window group (the count taken back is in the group that made it).
    for (PaneView& behind : view.behind)
      for (PaneTerm& term : pane_terms(scene, a, behind)) {
        c.pane_spread = std::max(c.pane_spread, term.transmittance.spread);
        add(term.aperture, behind.region, std::make_shared<const Aperture>(std::move(term.transmittance.combined)),
            std::move(term.panes), term.sign);
      }
  }
  const double scale = c.lambert.empty() ? 0 : *std::max_element(c.lambert.begin(), c.lambert.end());
  double worst = 0;
  for (std::size_t j = 0; j < c.sky_direct.size(); ++j) worst = std::max(worst, std::abs(c.sky_direct[j] - coarse[j]));
  c.moment_error = scale > 0 ? worst / scale : 0;
  return c;
}

std::vector<SensorCoefficients> annual_coefficients(const VisibilityEngine& engine, const Scene& scene,
                                                    const SensorGrid& grid, const WindowGroups& groups, int degree,
                                                    VisibilityCounters& counters, const ProgressCallback& progress) {
  std::vector<SensorCoefficients> out(grid.sensors.size());
  const auto locals = for_each_sensor<VisibilityCounters>(grid.sensors.size(), 16, progress,
                                                          [&](std::size_t i, VisibilityCounters& local) {
                                                            out[i] = sensor_coefficients(engine, scene, grid.sensors[i],
                                                                                         groups, degree, local);
                                                          });
  for (const auto& l : locals) counters += l;
  return out;
}

SmoothSkyFit fit_smooth_sky(double a, double b, double e, double min_cos_theta, const Vec3& sun, int degree) {
  if (degree < 0 || degree > 64) throw Error("the basis degree must lie in 0..64");
  const auto gradation = [&](double t) {
    const double c = std::max(t, min_cos_theta);
    return c > 0 ? 1 + a * std::exp(b / c) : (b < 0 ? 1.0 : 1 + a);  // the limit t → 0⁺ for b ≤ 0
  };
  // Chebyshev interpolation at the D + 1 Chebyshev points of the first kind on [0, 1]
  // (Trefethen, Approximation Theory and Approximation Practice, ch. 4): near-minimax, and its
  // coefficients come from a discrete cosine sum.
  const int n = degree + 1;
  std::vector<double> values(static_cast<std::size_t>(n)), g(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    const double theta = std::numbers::pi * (i + 0.5) / n;
    values[std::size_t(i)] = gradation((std::cos(theta) + 1) / 2);
  }
  for (int k = 0; k < n; ++k) {
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += values[std::size_t(i)] * std::cos(k * std::numbers::pi * (i + 0.5) / n);
    g[std::size_t(k)] = (k == 0 ? 1.0 : 2.0) * sum / n;
  }
  SmoothSkyFit fit;
  fit.coefficients.assign(std::size_t(annual_basis_size(degree)), 0.0);
  const Vec3 s = normalized(sun);
  const double family[kAnnualBasisFamilies] = {1, e * s.x * s.x, e * s.y * s.y, e * s.z * s.z,
                                               2 * e * s.x * s.y, 2 * e * s.x * s.z, 2 * e * s.y * s.z};
  for (int k = 0; k <= degree; ++k)
    for (int f = 0; f < kAnnualBasisFamilies; ++f)
      fit.coefficients[std::size_t(annual_basis_index(f, k, degree))] = family[f] * g[std::size_t(k)];
  for (double cj : fit.coefficients) fit.coefficients_abs_sum += std::abs(cj);
  // The sampled maximum error of p: an even grid, and the clamp's kink where there is one. p by
  // the three-term recurrence T_{k+1} = 2x T_k − T_{k−1}, a block of samples at a time with the
  // loop over samples innermost (their recurrences are independent and run side by side).
  fit.bound_by_bin.assign(kFitErrorBins, 0.0);
  const auto record = [&](double t, double error) {
    const int bin = std::min(kFitErrorBins - 1, int(t * kFitErrorBins));
    fit.bound_by_bin[std::size_t(bin)] = std::max(fit.bound_by_bin[std::size_t(bin)], error);
    // A bin's edge belongs to both bins that meet there.
    if (bin > 0 && t * kFitErrorBins == bin)
      fit.bound_by_bin[std::size_t(bin - 1)] = std::max(fit.bound_by_bin[std::size_t(bin - 1)], error);
    fit.gradation_max_error = std::max(fit.gradation_max_error, error);
  };
  std::vector<double> samples;
  for (int i = 0; i <= 64 * kFitErrorBins; ++i) samples.push_back(double(i) / (64 * kFitErrorBins));
  if (min_cos_theta > 0) samples.push_back(min_cos_theta);
  constexpr std::size_t kBlock = 64;
  std::array<double, kBlock> x, t0, t1, sum;
  for (std::size_t start = 0; start < samples.size(); start += kBlock) {
    const std::size_t m = std::min(kBlock, samples.size() - start);
    for (std::size_t i = 0; i < m; ++i) {
      x[i] = 2 * samples[start + i] - 1;
      t0[i] = 1;
      t1[i] = x[i];
      sum[i] = g[0] + (n > 1 ? g[1] * x[i] : 0);
    }
    for (int k = 2; k < n; ++k)
      for (std::size_t i = 0; i < m; ++i) {
        const double t2 = 2 * x[i] * t1[i] - t0[i];
        sum[i] += g[std::size_t(k)] * t2;
        t0[i] = t1[i];
        t1[i] = t2;
      }
    for (std::size_t i = 0; i < m; ++i) {
      const double t = samples[start + i];
      record(t, std::abs(sum[i] - gradation(t)));
    }
  }
  for (double& b : fit.bound_by_bin) b *= 1 + std::abs(e);
  fit.bound_factor = fit.gradation_max_error * (1 + std::abs(e));
  return fit;
}

double SmoothSkyFit::bound_over(double lo, double hi) const noexcept {
  if (bound_by_bin.empty() || hi < lo) return bound_factor;
  const int first = std::clamp(int(lo * kFitErrorBins), 0, kFitErrorBins - 1);
  const int last = std::clamp(int(hi * kFitErrorBins), 0, kFitErrorBins - 1);
  double worst = 0;
  for (int b = first; b <= last; ++b) worst = std::max(worst, bound_by_bin[std::size_t(b)]);
  return worst;
}

double evaluate_smooth_fit(const SmoothSkyFit& fit, const Vec3& u, int degree) {
  std::vector<double> phi(std::size_t(annual_basis_size(degree)));
  evaluate_basis(u, degree, phi.data());
  double sum = 0;
  for (std::size_t j = 0; j < phi.size(); ++j) sum += fit.coefficients[j] * phi[j];
  return sum;
}

}  // namespace daylit
