#include "sky/perez_sky.hpp"

#include "sky/weather_file.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "geometry/error.hpp"
#include "illumination/gauss_legendre.hpp"
#include "sky/adaptive_quadrature.hpp"
#include "sky/cie_sky.hpp"
#include "sky/gradation_circle_sum.hpp"
#include "sky/sky_quadrature.hpp"

namespace daylit {

namespace {

constexpr double pi = std::numbers::pi;
constexpr double kDegree = pi / 180;

// Perez, Seals and Michalsky 1993, Table 1: for each ε bin, the coefficients (x1, x2, x3, x4) of
// a, b, c, d, e in x = x1 + x2 Z + Δ (x3 + x4 Z) (eq. 6; Z the sun's zenith angle in radians).
// In bin 1, c and d follow eqs. 7 and 8 instead: c = exp[(Δ (c1 + c2 Z))^c3] − c4 and
// d = −exp[Δ (d1 + d2 Z)] + d3 + Δ d4. Transcribed from the published table; checked digit by
// digit against the table in Radiance's gendaymtx.c (NREL/Radiance, src/gen) and against the
// coefficient file coeff_perez.dat that gendaylit reads.
constexpr double kTable1[8][5][4] = {
    {{1.3525, -0.2576, -0.2690, -1.4366}, {-0.7670, 0.0007, 1.2734, -0.1233}, {2.8000, 0.6004, 1.2375, 1.0000},
     {1.8734, 0.6297, 0.9738, 0.2809}, {0.0356, -0.1246, -0.5718, 0.9938}},
    {{-1.2219, -0.7730, 1.4148, 1.1016}, {-0.2054, 0.0367, -3.9128, 0.9156}, {6.9750, 0.1774, 6.4477, -0.1239},
     {-1.5798, -0.5081, -1.7812, 0.1080}, {0.2624, 0.0672, -0.2190, -0.4285}},
    {{-1.1000, -0.2515, 0.8952, 0.0156}, {0.2782, -0.1812, -4.5000, 1.1766}, {24.7219, -13.0812, -37.7000, 34.8438},
     {-5.0000, 1.5218, 3.9229, -2.6204}, {-0.0156, 0.1597, 0.4199, -0.5562}},
    {{-0.5484, -0.6654, -0.2672, 0.7117}, {0.7234, -0.6219, -5.6812, 2.6297}, {33.3389, -18.3000, -62.2500, 52.0781},
     {-3.5000, 0.0016, 1.1477, 0.1062}, {0.4659, -0.3296, -0.0876, -0.0329}},
    {{-0.6000, -0.3566, -2.5000, 2.3250}, {0.2937, 0.0496, -5.6812, 1.8415}, {21.0000, -4.7656, -21.5906, 7.2492},
     {-3.5000, -0.1554, 1.4062, 0.3988}, {0.0032, 0.0766, -0.0656, -0.1294}},
    {{-1.0156, -0.3670, 1.0078, 1.4051}, {0.2875, -0.5328, -3.8500, 3.3750}, {14.0000, -0.9999, -7.1406, 7.5469},
     {-3.4000, -0.1078, -1.0750, 1.5702}, {-0.0672, 0.4016, 0.3017, -0.4844}},
    {{-1.0000, 0.0211, 0.5025, -0.5119}, {-0.3000, 0.1922, 0.7023, -1.6317}, {19.0000, -5.0000, 1.2438, -1.9094},
     {-4.0000, 0.0250, 0.3844, 0.2656}, {1.0468, -0.3788, -2.4517, 1.4656}},
    {{-1.0500, 0.0289, 0.4260, 0.3590}, {-0.3250, 0.1156, 0.7781, 0.0025}, {31.0625, -14.5000, -46.1148, 55.3750},
     {-7.2312, 0.4050, 13.3500, 0.6234}, {1.5000, -0.6426, 1.8564, 0.5636}},
};
// Lower bounds of the ε bins (Table 1 of both papers).
constexpr double kBinLower[8] = {1.000, 1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200};

// Perez et al. 1990, Table 4: luminous efficacy (lm/W) per ε bin, (a, b, c, d) of
// diffuse: a + b W + c cos Z + d ln Δ (eq. 7); direct: a + b W + c exp(5.73 Z − 5) + d Δ (eq. 8).
// Checked against the tables in gendaylit.c and gendaymtx.c.
constexpr double kDiffuseEfficacy[8][4] = {
    {97.24, -0.46, 12.00, -8.91},   {107.22, 1.15, 0.59, -3.95},   {104.97, 2.96, -5.53, -8.77},
    {102.39, 5.59, -13.95, -13.90}, {100.71, 5.94, -22.75, -23.74}, {106.42, 3.83, -36.15, -28.83},
    {141.88, 1.90, -53.24, -14.03}, {152.23, 0.35, -45.27, -7.98}};
constexpr double kDirectEfficacy[8][4] = {
    {57.20, -4.55, -2.98, 117.12}, {98.99, -3.46, -1.21, 12.38},  {109.83, -4.90, -1.71, -8.81},
    {110.34, -5.84, -1.99, -4.56}, {106.36, -3.97, -1.75, -6.16}, {107.19, -1.25, -1.51, -26.73},
    {105.75, 0.77, -1.26, -34.44}, {101.18, 1.58, -1.10, -8.29}};

constexpr double kMaxAltitudeRadianceDeg = 87;  // gendaylit / gendaymtx
constexpr double kMinCosRadiance = 0.01;        // perezlum.cal

int clearness_bin(double epsilon) noexcept {
  int bin = 1;
  for (int i = 1; i < 8; ++i)
    if (epsilon >= kBinLower[i]) bin = i + 1;
  return bin;
}

}  // namespace

PerezClamps parse_perez_clamps(std::string_view name) {
  if (name == "none") return PerezClamps::none;
  if (name == "radiance") return PerezClamps::radiance;
  throw Error("unknown Perez clamps '" + std::string(name) + "': use none or radiance");
}

std::string_view perez_clamps_name(PerezClamps clamps) noexcept {
  return clamps == PerezClamps::none ? "none" : "radiance";
}

double kasten_young_air_mass(double zenith_deg) noexcept {
  return 1 / (std::cos(zenith_deg * kDegree) + 0.50572 * std::pow(96.07995 - zenith_deg, -1.6364));
}

double extraterrestrial_normal_irradiance(double distance_au) noexcept {
  return kSolarConstant / (distance_au * distance_au);
}

PerezCondition perez_condition(const PerezConditionInput& in, PerezClamps clamps) {
  if (!std::isfinite(in.diffuse_horizontal_irradiance) || !(in.diffuse_horizontal_irradiance > 0))
    throw Error(fmt::format("the Perez sky needs a diffuse horizontal irradiance above 0 W/m² (got {:g})",
                            in.diffuse_horizontal_irradiance));
  if (!std::isfinite(in.direct_normal_irradiance) || in.direct_normal_irradiance < 0)
    throw Error(fmt::format("the direct normal irradiance must be ≥ 0 W/m² (got {:g})", in.direct_normal_irradiance));
  if (!(in.sun_zenith_deg >= 0 && in.sun_zenith_deg < 90))
    throw Error(fmt::format("the Perez sky needs the sun above the horizon (zenith angle {:g}°)", in.sun_zenith_deg));
  if (!std::isfinite(in.extraterrestrial_normal) || !(in.extraterrestrial_normal > 0) || !std::isfinite(in.dew_point_c))
    throw Error("the extraterrestrial irradiance and the dew point must be finite");
  PerezCondition p;
  double zenith_deg = in.sun_zenith_deg;
  if (clamps == PerezClamps::radiance && zenith_deg < 90 - kMaxAltitudeRadianceDeg) {
    p.clamps_applied.push_back(fmt::format("sun altitude {:.4f}° lowered to 87° (gendaylit, gendaymtx)", 90 - zenith_deg));
    zenith_deg = 90 - kMaxAltitudeRadianceDeg;
  }
  p.sun_zenith_used_deg = zenith_deg;
  const double Z = zenith_deg * kDegree, kz3 = 1.041 * Z * Z * Z;
  const double Ed = in.diffuse_horizontal_irradiance, I = in.direct_normal_irradiance;
  p.clearness = ((Ed + I) / Ed + kz3) / (1 + kz3);  // 1990 eq. 1
  p.air_mass = kasten_young_air_mass(zenith_deg);
  p.brightness = Ed * p.air_mass / in.extraterrestrial_normal;  // 1990 eq. 2
  p.precipitable_water_cm = std::exp(0.07 * in.dew_point_c - 0.075);
  p.bin = clearness_bin(p.clearness);
  p.clearness_used = p.clearness;
  p.brightness_used = p.brightness;
  if (clamps == PerezClamps::radiance && p.clearness > 1.065 && p.clearness < 2.8 && p.brightness < 0.2) {
    p.clamps_applied.push_back(fmt::format("Δ = {:.6g} raised to 0.2 for the luminance coefficients (1.065 < ε < 2.8; gendaylit)",
                                           p.brightness));
    p.brightness_used = 0.2;
  }
  const double D = p.brightness_used;
  const auto& x = kTable1[p.bin - 1];
  auto eq6 = [&](int k) { return x[k][0] + x[k][1] * Z + D * (x[k][2] + x[k][3] * Z); };
  p.a = eq6(0);
  p.b = eq6(1);
  p.e = eq6(4);
  if (p.bin == 1) {
    p.c = std::exp(std::pow(D * (x[2][0] + x[2][1] * Z), x[2][2])) - x[2][3];  // eq. 7
    p.d = -std::exp(D * (x[3][0] + x[3][1] * Z)) + x[3][2] + D * x[3][3];     // eq. 8
  } else {
    p.c = eq6(2);
    p.d = eq6(3);
  }
  const double W = p.precipitable_water_cm;
  const auto& kd = kDiffuseEfficacy[p.bin - 1];
  const auto& kb = kDirectEfficacy[p.bin - 1];
  p.diffuse_efficacy = kd[0] + kd[1] * W + kd[2] * std::cos(Z) + kd[3] * std::log(p.brightness);
  p.direct_efficacy = kb[0] + kb[1] * W + kb[2] * std::exp(5.73 * Z - 5) + kb[3] * p.brightness;
  if (p.direct_efficacy < 0 && clamps == PerezClamps::radiance) {
    p.clamps_applied.push_back(fmt::format("direct efficacy {:.4g} lm/W raised to 0 (gendaylit)", p.direct_efficacy));
    p.direct_efficacy = 0;
  }
  if (!(p.diffuse_efficacy > 0) || !std::isfinite(p.diffuse_efficacy))
    throw Error(fmt::format("the diffuse luminous efficacy of Perez 1990 (eq. 7) is {:.4g} lm/W for ε = {:.4g}, Δ = {:.4g}",
                            p.diffuse_efficacy, p.clearness, p.brightness));
  return p;
}

PerezSky::PerezSky(const PerezCondition& condition, const Vec3& sun, PerezClamps clamps)
    : condition_(condition), clamps_(clamps), sun_(normalized(sun)) {
  if (!(sun_.z > 0)) throw Error("the Perez sky needs the sun above the horizon");
  const double max_z = std::sin(kMaxAltitudeRadianceDeg * kDegree);
  if (clamps == PerezClamps::radiance && sun_.z > max_z) {
    // The azimuth is kept; a sun at the zenith itself has none, and is lowered towards +y.
    const double h = std::hypot(sun_.x, sun_.y);
    const Vec3 horizontal = h > 0 ? Vec3{sun_.x / h, sun_.y / h, 0} : Vec3{0, 1, 0};
    sun_ = std::cos(kMaxAltitudeRadianceDeg * kDegree) * horizontal + Vec3{0, 0, max_z};
  }
  const PerezCondition& p = condition_;
  // Where the published formula is no luminance: refused without clamps; with Radiance's, named
  // (clamps 4 and 5 of the header act there).
  const bool none = clamps == PerezClamps::none;
  auto problem = [&](const std::string& why, const std::string& radiance_note) {
    if (none)
      throw Error(fmt::format("the published Perez sky is not a luminance for this hour ({}; ε = {:.4g}, Δ = {:.4g}, "
                              "Z = {:.3f}°, a = {:.4g}, b = {:.4g}, c = {:.4g}, d = {:.4g}, e = {:.4g}); "
                              "--perez-clamps radiance applies Radiance's limits",
                              why, p.clearness, p.brightness, p.sun_zenith_used_deg, p.a, p.b, p.c, p.d, p.e));
    condition_.clamps_applied.push_back(radiance_note);
  };
  // The gradation 1 + a e^{b/t}, t = cos θ, is monotone in t: its extremes are at the zenith and
  // at the horizon (without clamps the limit t → 0: 1 for b < 0, 1 + a for b = 0, ±∞ for b > 0;
  // with Radiance's, t = 0.01).
  if (p.b > 0 && p.a != 0)
    problem("the gradation 1 + a·exp(b/cos θ) diverges at the horizon: b > 0",
            fmt::format("b = {:.4g} > 0: the gradation is held at cos θ = 0.01 near the horizon (perezlum.cal)", p.b));
  const double at_horizon = none ? (p.b < 0 ? 1 : 1 + p.a) : 1 + p.a * std::exp(p.b / kMinCosRadiance);
  bool negative = std::min(1 + p.a * std::exp(p.b), at_horizon) < 0;
  // The indicatrix 1 + c e^{dγ} + e cos²γ over the angles from the sun that the sky holds,
  // γ ∈ [0, Z + 90°], sampled every 0.05° (its minimum is smooth: the sampling misses at most
  // O(h²) of it, far below the values that matter).
  const double gamma_max = std::min(pi, std::acos(std::clamp(sun_.z, -1.0, 1.0)) + pi / 2);
  constexpr int kSamples = 3600;
  for (int i = 0; i <= kSamples && !negative; ++i) {
    const double g = gamma_max * i / kSamples;
    negative = 1 + p.c * std::exp(p.d * g) + p.e * std::cos(g) * std::cos(g) < 0;
  }
  if (negative)
    problem("the luminance is negative in part of the sky", "negative luminance in part of the sky set to 0 (gendaymtx)");
  zenith_value_ = luminance_function({0, 0, 1});
  if (!(zenith_value_ > 0)) throw Error("the Perez sky's zenith luminance is 0 for this hour (after the clamps)");
  // Where Radiance's floor at 0 acts, the luminance is no product of a gradation and an
  // indicatrix: cubature over the hemisphere. Elsewhere nested 1-D integrals in the sun's frame.
  horizontal_integral_ =
      negative ? sky_irradiance_quadrature([this](const Vec3& u) { return luminance_function(u); }, sun_,
                                           sky_hemisphere(), {0, 0, 1}, 1e-12)
                     .value
               : sun_frame_normalisation();
  if (!(horizontal_integral_ > 0) || !std::isfinite(horizontal_integral_))
    throw Error("the Perez sky's horizontal integral is not positive for this hour");
}

// The normalisation written about the sun: u = cos γ s + sin γ (cos ψ e₁ + sin ψ e₂), e₁ in the
// sun's vertical plane, so that cos θ = cos γ sin α + sin γ cos ψ cos α (α the sky's sun altitude)
// and, with G the gradation and f(γ) = 1 + c e^{dγ} + e cos²γ the indicatrix,
//     N = ∫₀^π f(γ) sin γ I(γ) dγ,   I(γ) = 2 ∫_{0}^{ψ₀(γ)} G(cos θ) cos θ dψ,
// ψ₀ where the circle of radius γ about the sun meets the horizon (cos θ = 0). The indicatrix
// (the circumsolar kink at γ = 0 included) is smooth in γ; I(γ) is smooth except where a circle
// touches the horizon (γ = α, γ = π − α), where it behaves as |γ − α|^{3/2}, or, under Radiance's
// clamps, the circle cos θ = 0.01 where the gradation is held: breakpoints there, and at ψ where
// cos θ = 0.01. What both rules below share.
struct PerezSky::SunFrame {
  const PerezCondition& p;
  double sin_a, cos_a, floor_t;
  std::vector<double> outer_points;  // 0, the breakpoints in γ, π

  SunFrame(const PerezCondition& condition, const Vec3& sun, PerezClamps clamps)
      : p(condition),
        sin_a(std::clamp(sun.z, -1.0, 1.0)),
        cos_a(std::sqrt(std::max(0.0, 1 - sin_a * sin_a))),
        floor_t(clamps == PerezClamps::radiance ? kMinCosRadiance : 0.0) {
    const double alpha = std::asin(sin_a);
    std::vector<double> cuts{alpha, pi - alpha};
    if (floor_t > 0) cuts.insert(cuts.end(), {alpha - std::asin(floor_t), pi - alpha - std::asin(floor_t)});
    std::sort(cuts.begin(), cuts.end());
    outer_points = {0};
    for (double g : cuts)
      if (g > outer_points.back() && g < pi) outer_points.push_back(g);
    outer_points.push_back(pi);
  }
  double gradation(double t) const noexcept {
    const double c = std::max(t, floor_t);
    return c > 0 ? 1 + p.a * std::exp(p.b / c) : (p.b < 0 ? 1.0 : 1 + p.a);  // the limit t → 0⁺ for b ≤ 0
  }
  double indicatrix(double gamma) const noexcept {
    const double cg = std::cos(gamma);
    return 1 + p.c * std::exp(p.d * gamma) + p.e * cg * cg;
  }
  // The inner integral's breakpoints in ψ for the circle of radius γ: 0, [ψ where cos θ = floor_t], ψ₀;
  // empty when the circle lies below the horizon.
  std::vector<double> inner_points(double cg, double sg) const {
    const auto psi_where = [&](double t) {  // cos ψ = (t − cos γ sin α)/(sin γ cos α), clamped to [0, π]
      if (!(sg * cos_a > 0)) return cg * sin_a + sg * cos_a > t ? pi : 0.0;
      return std::acos(std::clamp((t - cg * sin_a) / (sg * cos_a), -1.0, 1.0));
    };
    const double psi0 = psi_where(0);
    if (!(psi0 > 0)) return {};
    std::vector<double> points{0};
    const double psi1 = floor_t > 0 ? psi_where(floor_t) : 0;
    if (psi1 > 0 && psi1 < psi0) points.push_back(psi1);
    points.push_back(psi0);
    return points;
  }
};

namespace {

// Gauss–Legendre on [0, 1] through the smoothstep map x = 3u² − 2u³ (weights times the map's
// derivative 6u(1 − u)): the map's derivative vanishes at both ends, so an endpoint behaviour
// |x − x₀|^{3/2} (a circle about the sun touching the horizon) becomes u³ times a smooth function
// and the rule keeps its rate.
struct SmoothstepRule {
  std::vector<double> x, w;
};
SmoothstepRule smoothstep_rule(int n) {
  const quadrature::UnitGaussRule g = quadrature::gauss_legendre_unit(n);
  SmoothstepRule r;
  for (std::size_t i = 0; i < g.x.size(); ++i) {
    const double u = g.x[i];
    r.x.push_back(u * u * (3 - 2 * u));
    r.w.push_back(g.w[i] * 6 * u * (1 - u));
  }
  return r;
}

// Relative agreement of two successive orders that accepts the higher: the 1e-12 the
// normalisation promises. The difference estimates the lower order's error; the higher one's is
// smaller by the rule's gain per step (measured: 48 → 64 gains two to three digits on the skies of
// test_perez_sky, a hundredfold or more).
constexpr double kFixedRuleAgreement = 1e-12;

// The rules of PerezSky::kFixedOrders, built once.
const SmoothstepRule& fixed_rule(std::size_t k) {
  static const std::vector<SmoothstepRule> rules = [] {
    std::vector<SmoothstepRule> r;
    for (int n : PerezSky::kFixedOrders) r.push_back(smoothstep_rule(n));
    return r;
  }();
  return rules.at(k);
}

}  // namespace

// The same nested integral by one smoothstep-mapped Gauss–Legendre rule (kFixedOrders[k] points)
// on every panel in γ and in ψ.
double PerezSky::fixed_rule_normalisation(std::size_t k) const {
  const SunFrame frame(condition_, sun_, clamps_);
  const SmoothstepRule& rule = fixed_rule(k);
  const double t_floor = std::max(frame.floor_t, std::numeric_limits<double>::min());
  double sum = 0;
  for (std::size_t k = 0; k + 1 < frame.outer_points.size(); ++k) {
    const double lo = frame.outer_points[k], width = frame.outer_points[k + 1] - lo;
    for (std::size_t i = 0; i < rule.x.size(); ++i) {
      const double gamma = lo + width * rule.x[i];
      const double cg = std::cos(gamma), sg = std::sin(gamma);
      const std::vector<double> psi = frame.inner_points(cg, sg);
      double circle = 0;
      for (std::size_t m = 0; m + 1 < psi.size(); ++m) {
        const double h = psi[m + 1] - psi[m];
        circle += h * gradation_circle_sum(rule.x.data(), rule.w.data(), rule.x.size(), psi[m], h, cg * frame.sin_a,
                                           sg * frame.cos_a, condition_.a, condition_.b, t_floor);
      }
      sum += rule.w[i] * width * frame.indicatrix(gamma) * sg * 2 * circle;
    }
  }
  return sum;
}

// The nested integral by adaptive Gauss–Kronrod (GSL QAGP), outer and inner, to 1e-12 relative; a
// roundoff status from GSL (the tolerance beyond what double gives) is taken as met, any other
// falls back to the hemisphere's cubature.
double PerezSky::adaptive_normalisation() const {
  const SunFrame frame(condition_, sun_, clamps_);
  gsl_set_error_handler_off();  // errors come back as status codes, never abort()
  Qagp outer, inner;
  int status = 0;
  const auto circle = [&](double gamma) {
    const double cg = std::cos(gamma), sg = std::sin(gamma);
    const std::vector<double> points = frame.inner_points(cg, sg);
    if (points.empty()) return 0.0;
    auto f = [&](double psi) {
      const double t = std::max(cg * frame.sin_a + sg * std::cos(psi) * frame.cos_a, 0.0);
      return frame.gradation(t) * t;
    };
    const auto [v, e] = inner.integrate(f, points, 1e-12, 0);
    (void)e;
    if (inner.status() && inner.status() != GSL_EROUND) status = inner.status();
    return 2 * v;
  };
  auto outer_f = [&](double gamma) { return frame.indicatrix(gamma) * std::sin(gamma) * circle(gamma); };
  const auto [value, error] = outer.integrate(outer_f, frame.outer_points, 1e-12, 0);
  (void)error;
  if (outer.status() && outer.status() != GSL_EROUND) status = outer.status();
  if (status != 0)  // the adaptive rule could not reach its tolerance: the hemisphere's cubature
    return sky_irradiance_quadrature([this](const Vec3& u) { return luminance_function(u); }, sun_, sky_hemisphere(),
                                     {0, 0, 1}, 1e-12)
        .value;
  return value;
}

// The fixed rule at rising orders until two successive ones agree to kFixedRuleAgreement (the
// higher taken: each step gains two or more digits where the rule converges, measured 48 → 64 →
// 96); where no two agree, the adaptive rule.
double PerezSky::sun_frame_normalisation() {
  double previous = fixed_rule_normalisation(0);
  for (std::size_t k = 1; k < std::size(kFixedOrders); ++k) {
    const double next = fixed_rule_normalisation(k);
    if (std::isfinite(next) && std::abs(next - previous) <= kFixedRuleAgreement * std::abs(next)) {
      normalised_by_fixed_rule_ = true;
      return next;
    }
    previous = next;
  }
  return adaptive_normalisation();
}

double PerezSky::luminance_function(const Vec3& u) const noexcept {
  if (!(u.z > 0)) return 0;
  const PerezCondition& p = condition_;
  const double cos_theta = clamps_ == PerezClamps::radiance ? std::max(u.z, kMinCosRadiance) : u.z;
  // γ = atan2(|s × u|, s·u): full precision near the sun, where acos loses half the digits.
  const double gamma = std::atan2(norm(cross(sun_, u)), dot(sun_, u));
  const double cg = std::cos(gamma);
  const double lv = (1 + p.a * std::exp(p.b / cos_theta)) * (1 + p.c * std::exp(p.d * gamma) + p.e * cg * cg);
  return clamps_ == PerezClamps::radiance ? std::max(lv, 0.0) : lv;
}

double PerezSky::max_relative_luminance() const {
  double m = relative_luminance(sun_);
  constexpr int kCount = 40000;
  const double golden = pi * (3 - std::sqrt(5.0));  // a Fibonacci lattice: equal solid angles
  for (int i = 0; i < kCount; ++i) {
    const double z = 1 - (i + 0.5) / kCount, r = std::sqrt(1 - z * z);
    m = std::max(m, relative_luminance({r * std::cos(golden * i), r * std::sin(golden * i), z}));
  }
  return m;
}

double PerezSky::radiance_145_point_integral() const {
  constexpr int kRows[7] = {30, 30, 24, 24, 18, 12, 6};
  // defangle.dat's azimuths are counted from the sun's (gendaylit takes cos γ from them so).
  const double sun_azimuth = std::atan2(sun_.x, sun_.y);
  double sum = 0;
  for (int row = 0; row < 8; ++row) {
    const double altitude = (6 + 12 * row) * kDegree;
    const int count = row < 7 ? kRows[row] : 1;
    for (int j = 0; j < count; ++j) {
      const double azimuth = sun_azimuth + 2 * pi * j / count;
      const Vec3 u{std::cos(altitude) * std::sin(azimuth), std::cos(altitude) * std::cos(azimuth),
                   row < 7 ? std::sin(altitude) : 1.0};
      sum += luminance_function(row < 7 ? u : Vec3{0, 0, 1}) * u.z;
    }
  }
  return sum * 2 * pi / 144;
}

QuadratureResult perez_sky_irradiance_quadrature(const PerezSky& sky, const SphericalRegion& region, const Vec3& n,
                                                 double tolerance,
                                                 const std::function<double(const Vec3&)>& transmittance) {
  return sky_irradiance_quadrature([&](const Vec3& u) { return sky.relative_luminance(u); }, sky.sun(), region, n,
                                   tolerance, transmittance);
}

PerezHour perez_hour(const PerezHourInput& in) {
  PerezConditionInput c;
  c.sun_zenith_deg = in.sun_zenith_deg;
  c.extraterrestrial_normal = extraterrestrial_normal_irradiance(in.distance_au);
  c.dew_point_c = in.dew_point_c.value_or(11);
  int iterations = 0;
  if (in.diffuse_horizontal_irradiance && in.direct_normal_irradiance) {
    c.diffuse_horizontal_irradiance = *in.diffuse_horizontal_irradiance;
    c.direct_normal_irradiance = *in.direct_normal_irradiance;
  } else if (in.diffuse_horizontal_illuminance && in.direct_normal_illuminance) {
    constexpr double kStart = 1367.0 / 127500.0;
    c.diffuse_horizontal_irradiance = *in.diffuse_horizontal_illuminance * kStart;
    c.direct_normal_irradiance = *in.direct_normal_illuminance * kStart;
    for (iterations = 1; iterations <= 100; ++iterations) {
      const PerezCondition p = perez_condition(c, in.clamps);
      if (!(p.direct_efficacy > 0) && *in.direct_normal_illuminance > 0)
        throw Error("the direct luminous efficacy is 0: the direct normal irradiance cannot be found from the illuminance");
      const double dh = *in.diffuse_horizontal_illuminance / p.diffuse_efficacy;
      const double dn = *in.direct_normal_illuminance > 0 ? *in.direct_normal_illuminance / p.direct_efficacy : 0;
      const bool converged = std::abs(dh - c.diffuse_horizontal_irradiance) <= 1e-9 * dh &&
                             std::abs(dn - c.direct_normal_irradiance) <= 1e-9 * std::max(dn, 1.0);
      c.diffuse_horizontal_irradiance = dh;
      c.direct_normal_irradiance = dn;
      if (converged) break;
    }
    iterations = std::min(iterations, 100);
  } else {
    throw Error("the Perez sky needs the diffuse horizontal and direct normal irradiance (W/m²), or both illuminances (lux)");
  }
  const PerezCondition condition = perez_condition(c, in.clamps);
  if (!in.direct_normal_illuminance && c.direct_normal_irradiance > 0 && condition.direct_efficacy < 0)
    throw Error(fmt::format("the direct luminous efficacy of Perez 1990 (eq. 8) is negative ({:.4g} lm/W) for ε = {:.4g}, "
                            "Δ = {:.4g}, Z = {:.4g}°; give the direct normal illuminance, or use --perez-clamps radiance",
                            condition.direct_efficacy, condition.clearness, condition.brightness,
                            condition.sun_zenith_used_deg));
  PerezHour h{PerezSky(condition, in.sun, in.clamps)};
  h.diffuse_horizontal_irradiance = c.diffuse_horizontal_irradiance;
  h.direct_normal_irradiance = c.direct_normal_irradiance;
  h.iterations = iterations;
  h.dew_point_assumed = !in.dew_point_c;
  h.diffuse_lux_from_efficacy = !in.diffuse_horizontal_illuminance;
  h.direct_lux_from_efficacy = !in.direct_normal_illuminance;
  h.diffuse_horizontal_lux = in.diffuse_horizontal_illuminance.value_or(condition.diffuse_efficacy * c.diffuse_horizontal_irradiance);
  h.direct_normal_lux = in.direct_normal_illuminance.value_or(condition.direct_efficacy * c.direct_normal_irradiance);
  return h;
}

PerezHourInput perez_hour_input(const WeatherRecord& r, bool photometric) {
  PerezHourInput in;
  if (photometric) {
    in.direct_normal_illuminance = r.direct_normal_illuminance;
    in.diffuse_horizontal_illuminance = r.diffuse_horizontal_illuminance;
  } else {
    in.direct_normal_irradiance = r.direct_normal_irradiance;
    in.diffuse_horizontal_irradiance = r.diffuse_horizontal_irradiance;
    in.direct_normal_illuminance = r.direct_normal_illuminance;
    in.diffuse_horizontal_illuminance = r.diffuse_horizontal_illuminance;
  }
  in.dew_point_c = r.dew_point_c;
  return in;
}

}  // namespace daylit
