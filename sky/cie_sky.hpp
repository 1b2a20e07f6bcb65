#pragma once
// The fifteen CIE standard general skies (CIE S 011/E:2003 = ISO 15469:2004), relative to the zenith
// luminance, integrated over exact visible regions: closed-form moments of a fitted luminance
// (fast, with a stated fit error) or adaptive quadrature of the standard's formula (the reference).
//
// Frame: x east, y north, z up; the sun is a unit vector s (its zenith angle Z_s = acos s_z).

#include <array>
#include <functional>
#include <vector>

#include "geometry/spherical_region.hpp"

namespace daylit {

// L(u)/L_z = φ(Z) f(χ) / (φ(0) f(Z_s)) with gradation φ(Z) = 1 + a exp(b / cos Z) (φ = 1 at the
// horizon) and indicatrix f(χ) = 1 + c (exp(d χ) − exp(d π/2)) + e cos²χ, Z the zenith angle of u
// and χ its angle from the sun (ISO 15469:2004, eqs. 1–4; parameters of its Table 1).
struct CieSky {
  int type;  // 1..15
  double a, b, c, d, e;
  Vec3 sun;  // unit, towards the sun

  // Throws daylit::Error for a type outside 1..15 or a sun below the horizon.
  CieSky(int type, const Vec3& sun);
  // L/L_z for a unit direction above the horizon (0 below it).
  double relative_luminance(const Vec3& u) const;
  // The largest L/L_z over the sky: the larger of the sun's direction (the circumsolar peak) and
  // 40,000 directions spread over the hemisphere (a bound on what a left-out obstruction hides).
  double max_relative_luminance() const;
};

// The sun's unit vector from its zenith angle and azimuth (degrees, clockwise from north).
Vec3 sun_direction(double zenith_deg, double azimuth_deg);

// L/L_z ≈ Σ_i p_i z^i + Σ_i q_i z^i t + Σ_j r_j t^j + Σ_j w_j t^j z + Σ_k h_k t^{n_k}, with z = u_z,
// t = s·u and Phong lobes of exponents n_k = 16 … 1024 about the sun for the circumsolar peak: a
// basis whose moments against (n·u) are all closed forms (double-axis and (k,1,1) moments,
// moments.hpp). Least squares over the sky hemisphere (uniform in solid angle), in long double.
struct CieSkyFit {
  std::vector<double> zenith_powers;           // p_i, i = 0..P
  std::vector<double> zenith_powers_times_sun;  // q_i, i = 0..P
  std::vector<double> sun_powers;              // r_j for t^j, j = 0..Q (r_0 = r_1 = 0: in p, q)
  std::vector<double> sun_powers_times_zenith;  // w_j for t^j z, j = 0..Q (w_0 = w_1 = 0)
  std::vector<int> lobe_exponents;
  std::vector<double> lobe_weights;
  double max_error = 0;  // max |fit − L/L_z| over the hemisphere (checked on 40,000 directions)
  double rms_error = 0;
};
CieSkyFit fit_cie_sky(const CieSky& sky);

// E/L_z on a receiver with unit normal n from the sky seen in `region` (above the horizon and in
// front of the receiver, as the visibility routine returns it): closed forms of the fit.
double cie_sky_irradiance(const CieSkyFit& fit, const Vec3& sun, const SphericalRegion& region, const Vec3& n);

// The same by adaptive quadrature of the standard's formula (spherical_quadrature.hpp), to the
// relative tolerance given; fan triangles are split at the sun's direction when they contain it
// (the indicatrix has a kink there).
struct CieQuadrature {
  double value, error_estimate;
  long evaluations;
};
// `transmittance`, when given, weighs each direction (glazing's T at the cosine of incidence).
CieQuadrature cie_sky_irradiance_quadrature(const CieSky& sky, const SphericalRegion& region, const Vec3& n,
                                            double tolerance,
                                            const std::function<double(const Vec3&)>& transmittance = {});

// E/L_z over the part of the spherical cap {u : L·u ≥ cos σ} (L = cap_axis, any non-zero vector;
// σ = half_angle ∈ (0, π]) above the horizon and in front of the receiver (normal n, unit):
// nested adaptive Gauss–Kronrod quadrature (GSL's QAGP) in polar coordinates about L, the inner
// integral over θ ∈ [0, σ] cut exactly to where z ≥ 0 and n·u ≥ 0 (each a single interval, found
// in closed form), with breakpoints at the sun's nearest approach in both variables. The reference
// for cap regions (Snyder's sources, the sun's disk), whose fit moments have no closed form here.
// Throws daylit::Error when GSL cannot reach the tolerance.
CieQuadrature cie_sky_irradiance_over_cap(const CieSky& sky, const Vec3& cap_axis, double half_angle, const Vec3& n,
                                          double tolerance);

// The part of a region above the horizon and in front of a receiver with normal n.
SphericalRegion above_horizon_and_in_front(const SphericalRegion& region, const Vec3& n);

// The whole sky hemisphere as a region: four octant triangles from the zenith, positively oriented.
SphericalRegion sky_hemisphere();

}  // namespace daylit
