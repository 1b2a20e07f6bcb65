#pragma once
// Daylight coefficients without patches (DESIGN.md §5; issue 14, deliverable 3).
//
// Per sensor, once: the moments B_j = Σ_apertures τ ∫_A φ_j(u) T(u) (n·u) dσ of what the sensor
// sees of the sky through each aperture (A the exact visible region), against a fixed basis φ_j
// of polynomials in the direction u. Per hour: the Perez sky's smooth part
//     G(u_z) (1 + e (s·u)²),   G(t) = 1 + a e^{b/t}   (Perez, Seals and Michalsky 1993, eq. 1)
// written exactly in that basis once G is replaced by its Chebyshev interpolant p of degree D on
// t = u_z ∈ [0, 1]: with T_k(2u_z − 1) the Chebyshev polynomials on [0, 1],
//     p(u_z)(1 + e (s·u)²) = Σ_k g_k T_k(2u_z − 1) [1 + e Σ_{i≤j} (2 − δ_ij) s_i s_j u_i u_j],
// so the basis is the seven families T_k(2u_z − 1)·{1, u_x², u_y², u_z², u_x u_y, u_x u_z, u_y u_z},
// k = 0..D, and each hour is a dot product. |G − p| ≤ ε_G on [0, 1] and |1 + e (s·u)²| ≤ 1 + |e|
// bound the hour's error by ε_G (1 + |e|) Σ τ ∫_A (n·u) T dσ (the "lambert" weight kept per sensor).
// The circumsolar term c·G(u_z)·e^{dγ} is not a low-degree polynomial (DESIGN.md §5): it is
// integrated per hour over the stored regions (annual.cpp), and so is the sun's disk (cap_clip).
//
// The moments are computed by a fixed product Gauss rule on each fan triangle of each loop (the
// central projection of the planar triangle, collapsed to the square: Duffy's map), split to sides
// of at most kMomentMaxSide (fan_product_rule.hpp), at two orders
// (kOrderLow, kOrderHigh points per direction); their largest difference relative to the lambert
// weight is kept as the moments' error estimate. The integrands are polynomials of degree ≤ D + 3
// in u times T(μ) composed with an analytic map, so the rule converges spectrally; it is not a
// closed form, and the estimate says how far it is from one.
//
// Window groups (for the LM-83 blinds rule): apertures whose polygons share a material name form
// one group; the coefficients are kept per group so that blinds scale a group alone.

#include <string>
#include <memory>
#include <optional>
#include <vector>

#include "geometry/scene.hpp"
#include "geometry/sensor_grid.hpp"
#include "geometry/visibility.hpp"
#include "simulation/pane_transmittance.hpp"
#include "simulation/sky_component.hpp"

namespace daylit {

inline constexpr int kAnnualBasisFamilies = 7;
inline constexpr int kOrderLow = 20, kOrderHigh = 28;
// 0.7 rad (40°): the two orders agree to 1e-14 of the Lambert weight on the room sample's
// sensor nearest its window (1.0 rad: 7e-7; unsplit: 0.26), at about 10 ms per such sensor.
inline constexpr double kMomentMaxSide = 0.7;

// Basis index of family f (0..6, the order above) and Chebyshev degree k (0..D).
inline int annual_basis_index(int family, int k, int degree) noexcept { return family * (degree + 1) + k; }
inline int annual_basis_size(int degree) noexcept { return kAnnualBasisFamilies * (degree + 1); }

// The window groups of a scene: group_of_aperture[a] and the groups' names (their materials).
struct WindowGroups {
  std::vector<int> group_of_aperture;
  std::vector<std::string> names;
};
WindowGroups window_groups(const Scene& scene);

// A region of the sky seen through an aperture: the last pane on the way, whose window group it
// belongs to, and where panes lie in front of it, their combined transmittance with the
// aperture's (pane_transmittance.hpp).
struct SeenRegion {
  int aperture = -1;  // Scene::apertures
  SphericalRegion region;
  std::shared_ptr<const Aperture> through{};  // null: the aperture's own transmittance
  std::vector<std::uint32_t> panes{};         // the panes in front (for the sun: transmittance_along)
  double sign = 1;                            // −1: a count taken back (PaneView), subtracted
  const Aperture& transmitting(const Scene& scene) const { return through ? *through : scene.apertures[std::size_t(aperture)]; }
};

// The transmittance factor of an aperture for direction u: τ, or glass's T(|a·u|), a the pane's
// unit normal, found once (a many-sided pane's Newell normal is not cheap per direction).
class ApertureTransmittance {
 public:
  explicit ApertureTransmittance(const Aperture& aperture);
  double operator()(const Vec3& u) const noexcept;
  const Vec3& axis() const noexcept { return axis_; }
  const std::vector<double>* angular() const noexcept { return angular_; }  // null: constant
  double constant() const noexcept { return constant_; }

 private:
  double constant_ = 1;
  Vec3 axis_{};
  const std::vector<double>* angular_ = nullptr;
};

// The transmittance of a seen region along a direction u: the aperture's τ or T(|a·u|), or, seen
// through panes, every pane's T at its own cosine of incidence (TransmittanceAlong). Exact where
// `through`'s combined polynomial is not: that takes a pane not parallel to the aperture as
// constant over the region (pane_transmittance.hpp); the moments, the circumsolar term and the
// sun of an annual run take this instead, so only the sky in patches keeps that approximation.
class SeenTransmittance {
 public:
  SeenTransmittance(const Scene& scene, const SeenRegion& seen);
  double operator()(const Vec3& u) const noexcept;
  // values[i] *= T(u_i) for n directions given as coordinate arrays (a batch of the cubature).
  void multiply(const double* x, const double* y, const double* z, std::size_t n, double* values) const noexcept;
  // The same value along every direction (an open aperture): value() then.
  bool constant() const noexcept { return aperture_ && aperture_->angular() == nullptr; }
  double value() const noexcept { return aperture_ ? aperture_->constant() : 1.0; }

 private:
  std::optional<ApertureTransmittance> aperture_;  // the aperture's own (seen directly)
  std::optional<TransmittanceAlong> along_;        // through panes
};

// What one sensor sees, once.
struct SensorCoefficients {
  // The sky seen directly through the apertures: [group][basis] (group-major).
  std::vector<double> sky_direct;
  // (The reflected part is not a per-sensor moment: it comes through the reflection operator's
  // nodes, annual_reflections.hpp.)
  // Σ τ ∫_A (n·u) T dσ per group: the weight of the hourly fit bound.
  std::vector<double> lambert;
  // The range of u_z over the regions (exact: at vertices or at an arc's top or bottom).
  double min_uz = 1, max_uz = 0;
  // Largest |B_j(high) − B_j(low)| over the basis, relative to the largest lambert weight (0 if none).
  double moment_error = 0;
  // The largest relative bound of a pane taken as constant over a region (pane_transmittance.hpp):
  // what the sky in patches (add_patch_coefficients) carries; the exact path takes every pane's T
  // along each direction (SeenTransmittance) and has no such term.
  double pane_spread = 0;
  // The visible regions, kept for the circumsolar term and the sun.
  std::vector<SeenRegion> regions;
};

// The coefficients of every sensor of a grid (in parallel over sensors, like sky_component).
std::vector<SensorCoefficients> annual_coefficients(const VisibilityEngine& engine, const Scene& scene,
                                                    const SensorGrid& grid, const WindowGroups& groups, int degree,
                                                    VisibilityCounters& counters, const ProgressCallback& progress = {});

// One sensor's coefficients (no threading).
SensorCoefficients sensor_coefficients(const VisibilityEngine& engine, const Scene& scene, const Sensor& sensor,
                                       const WindowGroups& groups, int degree, VisibilityCounters& counters);

// The smooth part of one hour's sky in the basis: coefficients c_j with Σ c_j φ_j(u) = p(u_z)(1 + e(s·u)²),
// p the degree-D Chebyshev interpolant of G(t) = 1 + a·exp(b / max(t, t_min)) on [0, 1] (t_min = 0 for
// the published model, 0.01 under Radiance's clamps), and max_error = max |G − p| over 4001 points of
// [0, 1] evenly spaced and the clamp's kink t_min (a sampled, not a proven, maximum).
struct SmoothSkyFit {
  std::vector<double> coefficients;
  double coefficients_abs_sum = 0;  // Σ_j |c_j|: what the moments' error estimate is multiplied by
  double gradation_max_error = 0;  // ε_G over [0, 1]
  double bound_factor = 0;         // ε_G (1 + |e|): times the lambert weight, a bound on the error of lv
  // The same maximum on each of kFitErrorBins equal parts of [0, 1] in u_z, times (1 + |e|): a
  // sensor that sees only u_z ∈ [lo, hi] takes the bins that overlap it (bound_over), which is
  // much tighter than ε_G for windows that do not reach the horizon, where e^{b/t} is hardest to fit.
  std::vector<double> bound_by_bin;
  double bound_over(double lo, double hi) const noexcept;
};
inline constexpr int kFitErrorBins = 64;
SmoothSkyFit fit_smooth_sky(double a, double b, double e, double min_cos_theta, const Vec3& sun, int degree);

// Σ_j c_j φ_j(u): the fitted smooth part at a direction (for tests).
double evaluate_smooth_fit(const SmoothSkyFit& fit, const Vec3& u, int degree);

}  // namespace daylit
