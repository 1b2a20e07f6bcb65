#pragma once
// Angle-dependent transmittance of Radiance's `glass` material, and its fit by a polynomial in
// the cosine of incidence, so that the sky seen through glazing stays a sum of closed-form moments
// about the pane's normal (DESIGN.md §3: "glazing whose transmittance depends on the angle of
// incidence ... become higher moments of the same kind").

#include <array>
#include <functional>
#include <optional>
#include <vector>

namespace daylit {

struct GlassOptics {
  std::array<double, 3> transmissivity;  // Radiance's per-channel transmissivities (the material's first 3 reals)
  double refractive_index = 1.52;        // its optional 4th real
};

// Luminance-weighted transmittance (weights 0.265, 0.670, 0.065) at cosine of incidence μ ∈ [0, 1]:
// Radiance's m_glass (src/rt/glass.c): with cos θ_t = √(1 − (1 − μ²)/n²), per-pass d = t^{1/cos θ_t},
// Fresnel r_s = ((μ − n cos θ_t)/(μ + n cos θ_t))², r_p = ((1/μ − n/cos θ_t)/(1/μ + n/cos θ_t))²,
// T = ½ Σ_{r ∈ {r_s, r_p}} (1 − r)² d / (1 − r² d²), multiple reflections inside the pane included.
double glass_transmittance(const GlassOptics& glass, double cos_incidence);

// Luminance-weighted reflectance at cosine of incidence μ, the same on both sides of the pane:
// m_glass's reflected ray, R = ½ Σ_{r ∈ {r_s, r_p}} r (1 + (1 − 2r) d²)/(1 − r² d²) (the first
// surface's r plus what returns through it after one or more passes: r + (1 − r)² r d²/(1 − r² d²)).
// Without absorption (t = 1, so d = 1) R + T = 1 exactly: what the pane does not transmit it reflects.
double glass_reflectance(const GlassOptics& glass, double cos_incidence);

// The pane's reflectance for diffuse light (a uniform radiance from one side), 2 ∫₀¹ R(μ) μ dμ:
// what a radiosity solution, which carries Lambertian exitance only, takes as the glass's
// reflectance (its specular direction is not kept, as with plastic's specular part; the energy is
// exact for diffuse incidence). R(μ) is smooth on [0, 1] (the Fresnel terms are rational in μ and
// cos θ_t, d = t^{1/cos θ_t} with cos θ_t ≥ √(1 − 1/n²)), so 64-point Gauss–Legendre (GSL) gives
// it to roundoff. Clear glass (t = 0.96, n = 1.52): R(1) = 0.0786, diffuse 0.1478.
double glass_diffuse_reflectance(const GlassOptics& glass);

// The transmissivity t (the same in every channel) whose glass of refractive index n transmits
// `transmittance` at normal incidence: glass_transmittance({t, t, t}, n, 1) = transmittance, found
// by bisection on t ∈ [0, 1], where T rises monotonically (to the last bit: 64 halvings, the result
// within an ulp or two of the root). Radiance's closed form for n = 1.52, t = (√(0.8402528435 +
// 0.0072522239 T²) − 0.9166530661)/(0.0036261119 T), which Honeybee's glass modifiers use
// (generic_exterior_window_vis_0.64 = 0.6975761815384331), is an approximation of the same model:
// it differs by 1.2e-8 at T = 0.64, 2.3e-9 at 0.88 and 1.3e-7 at 0.1. Returns nullopt when even
// t = 1 transmits less (0.9183 for n = 1.52: the surfaces reflect the rest).
std::optional<double> glass_transmissivity(double transmittance, double refractive_index = 1.52);

// T(μ) ≈ Σ_k coefficients[k] μ^k on [0, 1], the lowest degree (at most 12) whose maximum error,
// measured on 20,001 points, is below `tolerance` (absolute transmittance), else the best of
// degree ≤ 12. Least squares on Chebyshev points in the Chebyshev basis (well conditioned),
// converted to monomials in long double.
//
// Why degree 12 and errors near 1e-3 for clear glass: T has a complex singularity close to μ = 0
// (where r² d² = 1 for r slightly above 1), so polynomial fits converge slowly: for t = 0.96 the
// maximum error is 1.6e-3 at degree 14 and 3.9e-4 at degree 22, but the monomial coefficients
// grow to 1e11 there, and their cancellation in Σ c_k M_k would cost more digits than the fit
// gains; at degree 12 they stay below 1e6 (Lawson's minimax reweighting gained only 20 %).
struct TransmittancePolynomial {
  std::vector<double> coefficients;
  double max_error = 0;  // max over μ ∈ [0, 1] of |Σ c_k μ^k − T(μ)|
};
// Σ_k c_k μ^k by Horner's rule.
double evaluate_polynomial(const std::vector<double>& c, double mu) noexcept;

// Largest |d/dμ Σ c_k μ^k| on [0, 1], on 1,001 points: how much T changes across the sun's disk.
double max_slope(const std::vector<double>& c);

TransmittancePolynomial fit_glass_transmittance(const GlassOptics& glass, double tolerance = 2e-5);
// The same fit of any transmittance T(μ) on [0, 1] (the product of two panes' along one view).
TransmittancePolynomial fit_transmittance(const std::function<double(double)>& transmittance, double tolerance = 2e-5);

}  // namespace daylit
