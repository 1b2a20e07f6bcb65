// The Perez all-weather sky (sky/perez_sky.hpp): its condition and luminance against the published
// formulas evaluated here in long double (the coefficients typed again from Perez, Seals and
// Michalsky 1993, Table 1, for the bins used), its normalisation ∫ lv cos θ dσ against a tensor
// Gauss–Legendre rule in (θ, φ) in long double, graded towards the sun and the horizon, one hour's
// illuminance through an unobstructed and an obstructed window against a 2-D Gauss–Legendre rule
// over the visible part of the window, and what Radiance's clamps change (and what they do not).

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <optional>
#include <set>
#include <vector>

#include "reference_quadrature.hpp"
#include "test_scenes.hpp"
#include "geometry/error.hpp"
#include "simulation/illuminance.hpp"
#include "simulation/annual.hpp"
#include "sky/perez_sky.hpp"

using namespace daylit;
using test::LVec3;

namespace {

using ld = long double;
const ld kPi = 3.141592653589793238462643383279502884L;

// Table 1 rows (a, b, c, d, e; four coefficients each) of the bins the cases below fall in.
struct Row {
  int bin;
  ld x[5][4];
};
const Row kRows[] = {
    {1, {{1.3525L, -0.2576L, -0.2690L, -1.4366L}, {-0.7670L, 0.0007L, 1.2734L, -0.1233L}, {2.8000L, 0.6004L, 1.2375L, 1.0000L},
         {1.8734L, 0.6297L, 0.9738L, 0.2809L}, {0.0356L, -0.1246L, -0.5718L, 0.9938L}}},
    {5, {{-0.6000L, -0.3566L, -2.5000L, 2.3250L}, {0.2937L, 0.0496L, -5.6812L, 1.8415L}, {21.0000L, -4.7656L, -21.5906L, 7.2492L},
         {-3.5000L, -0.1554L, 1.4062L, 0.3988L}, {0.0032L, 0.0766L, -0.0656L, -0.1294L}}},
    {8, {{-1.0500L, 0.0289L, 0.4260L, 0.3590L}, {-0.3250L, 0.1156L, 0.7781L, 0.0025L}, {31.0625L, -14.5000L, -46.1148L, 55.3750L},
         {-7.2312L, 0.4050L, 13.3500L, 0.6234L}, {1.5000L, -0.6426L, 1.8564L, 0.5636L}}},
};

struct Reference {
  ld epsilon, delta, air_mass, a, b, c, d, e;
  int bin;
};

// Perez 1990 eqs. 1–2 with Kasten–Young's air mass, Perez 1993 eqs. 6–8, in long double.
Reference reference(ld Ed, ld I, ld zenith_deg, ld E0) {
  Reference r;
  const ld Z = zenith_deg * kPi / 180, k = 1.041L * Z * Z * Z;
  r.epsilon = ((Ed + I) / Ed + k) / (1 + k);
  r.air_mass = 1 / (std::cos(Z) + 0.50572L * std::pow(96.07995L - zenith_deg, -1.6364L));
  r.delta = Ed * r.air_mass / E0;
  const ld bounds[] = {1, 1.065L, 1.23L, 1.5L, 1.95L, 2.8L, 4.5L, 6.2L};
  r.bin = 0;
  for (int i = 0; i < 8; ++i)
    if (r.epsilon >= bounds[i]) r.bin = i + 1;
  const Row* row = nullptr;
  for (const Row& candidate : kRows)
    if (candidate.bin == r.bin) row = &candidate;
  REQUIRE(row);
  auto eq6 = [&](int k) { return row->x[k][0] + row->x[k][1] * Z + r.delta * (row->x[k][2] + row->x[k][3] * Z); };
  r.a = eq6(0), r.b = eq6(1), r.e = eq6(4);
  if (r.bin == 1) {
    r.c = std::exp(std::pow(r.delta * (row->x[2][0] + row->x[2][1] * Z), row->x[2][2])) - row->x[2][3];
    r.d = -std::exp(r.delta * (row->x[3][0] + row->x[3][1] * Z)) + row->x[3][2] + r.delta * row->x[3][3];
  } else {
    r.c = eq6(2), r.d = eq6(3);
  }
  return r;
}

ld lv(const Reference& r, const LVec3& sun, const LVec3& u) {
  const ld cos_gamma = std::clamp(sun.x * u.x + sun.y * u.y + sun.z * u.z, -1.0L, 1.0L);
  const ld gamma = std::acos(cos_gamma);
  return (1 + r.a * std::exp(r.b / u.z)) * (1 + r.c * std::exp(r.d * gamma) + r.e * cos_gamma * cos_gamma);
}

LVec3 lunit(ld theta, ld phi) { return {std::sin(theta) * std::sin(phi), std::sin(theta) * std::cos(phi), std::cos(theta)}; }

// Breakpoints of [lo, hi] halving towards each focus down to `smallest` (geometric grading: the
// hp-refinement that gives Gauss–Legendre exponential convergence at a kink or an essential
// flattening such as e^{b/cos θ} at the horizon).
std::vector<ld> graded(ld lo, ld hi, const std::vector<ld>& foci, ld smallest) {
  std::vector<ld> b{lo, hi};
  for (ld f : foci) {
    b.push_back(f);
    for (ld d = (hi - lo) / 4; d > smallest; d /= 2) {
      if (f - d > lo) b.push_back(f - d);
      if (f + d < hi) b.push_back(f + d);
    }
  }
  std::sort(b.begin(), b.end());
  std::vector<ld> out;
  for (ld x : b)
    if (x >= lo && x <= hi && (out.empty() || x - out.back() > 1e-15L)) out.push_back(x);
  return out;
}

// ∫ lv cos θ dσ over the sky hemisphere by tensor Gauss–Legendre in (θ, φ), long double.
ld reference_normalisation(const Reference& r, ld sun_zenith, ld sun_azimuth) {
  const LVec3 s = lunit(sun_zenith, sun_azimuth);
  const auto bt = graded(0, kPi / 2, {sun_zenith, kPi / 2}, 1e-9L);
  const auto bp = graded(sun_azimuth - kPi, sun_azimuth + kPi, {sun_azimuth}, 1e-9L);
  std::vector<ld> x, w;
  test::gauss_legendre(20, x, w);
  ld sum = 0;
  for (std::size_t i = 0; i + 1 < bt.size(); ++i)
    for (std::size_t j = 0; j + 1 < bp.size(); ++j) {
      const ld ht = (bt[i + 1] - bt[i]) / 2, hp = (bp[j + 1] - bp[j]) / 2;
      for (std::size_t a = 0; a < x.size(); ++a) {
        const ld theta = bt[i] + ht * (x[a] + 1);
        const ld radial = std::cos(theta) * std::sin(theta);
        for (std::size_t b = 0; b < x.size(); ++b) {
          const ld phi = bp[j] + hp * (x[b] + 1);
          sum += w[a] * w[b] * ht * hp * radial * lv(r, s, lunit(theta, phi));
        }
      }
    }
  return sum;
}

PerezConditionInput input(double Ed, double I, double zenith_deg) {
  PerezConditionInput in;
  in.diffuse_horizontal_irradiance = Ed;
  in.direct_normal_irradiance = I;
  in.sun_zenith_deg = zenith_deg;
  in.extraterrestrial_normal = 1400;
  in.dew_point_c = 5;
  return in;
}

Vec3 sun_at(double zenith_deg, double azimuth_deg) {
  const double z = zenith_deg * std::numbers::pi / 180, a = azimuth_deg * std::numbers::pi / 180;
  return {std::sin(z) * std::sin(a), std::sin(z) * std::cos(a), std::cos(z)};
}

struct Case {
  double Ed, I, zenith_deg, azimuth_deg;
  int bin;
};
// Overcast (bin 1), intermediate (bin 5, Δ < 0.2) and clear (bin 8); each a luminance under the
// published model (positive, b < 0).
const Case kCases[] = {{200, 0, 40, 150, 1}, {150, 300, 50, 200, 5}, {80, 850, 30, 170, 8}};

}  // namespace

TEST_CASE("the Perez condition and luminance agree with the published formulas in long double") {
  for (const Case& k : kCases) {
    INFO("bin " << k.bin);
    const PerezCondition p = perez_condition(input(k.Ed, k.I, k.zenith_deg), PerezClamps::none);
    const Reference r = reference(k.Ed, k.I, k.zenith_deg, 1400);
    REQUIRE(p.bin == k.bin);
    REQUIRE(r.bin == k.bin);
    // Double against long double of the same formulas: a few ulp, amplified by the exponentials
    // and powers of eqs. 7–8 (bin 1) to at most ~1e-14.
    CHECK(p.clearness == Approx(double(r.epsilon)).epsilon(1e-14));
    CHECK(p.brightness == Approx(double(r.delta)).epsilon(1e-14));
    CHECK(p.air_mass == Approx(double(r.air_mass)).epsilon(1e-14));
    for (auto [got, want] : {std::pair{p.a, r.a}, {p.b, r.b}, {p.c, r.c}, {p.d, r.d}, {p.e, r.e}})
      CHECK(got == Approx(double(want)).epsilon(1e-13).margin(1e-14));
    CHECK(p.clamps_applied.empty());
    const PerezSky sky(p, sun_at(k.zenith_deg, k.azimuth_deg), PerezClamps::none);
    const LVec3 s = test::lvec(sky.sun());
    for (double theta : {0.0, 10.0, 35.0, 60.0, 85.0, 89.9})
      for (double phi : {0.0, 45.0, 150.0, 151.0, 200.0, 300.0}) {
        const ld t = theta * kPi / 180, f = phi * kPi / 180;
        const LVec3 u = lunit(t, f);
        const Vec3 ud{double(u.x), double(u.y), double(u.z)};
        CHECK(sky.luminance_function(ud) == Approx(double(lv(r, s, test::lvec(ud)))).epsilon(1e-13));
      }
  }
}

TEST_CASE("the Perez sky's normalisation agrees with tensor Gauss-Legendre in long double to 1e-12") {
  for (const Case& k : kCases) {
    INFO("bin " << k.bin);
    const PerezCondition p = perez_condition(input(k.Ed, k.I, k.zenith_deg), PerezClamps::none);
    const PerezSky sky(p, sun_at(k.zenith_deg, k.azimuth_deg), PerezClamps::none);
    const Reference r = reference(k.Ed, k.I, k.zenith_deg, 1400);
    const ld zenith = std::acos((ld)sky.sun().z), azimuth = std::atan2((ld)sky.sun().x, (ld)sky.sun().y);
    const ld want = reference_normalisation(r, zenith, azimuth);
    CHECK(sky.horizontal_integral() == Approx(double(want)).epsilon(1e-12));
    // gendaylit's sum over 145 directions, for the record (the issue measured up to 2.8 %).
    WARN("bin " << k.bin << ": normalisation / Gauss-Legendre - 1 = " << double(sky.horizontal_integral() / want - 1)
                << "; 145-point sum / exact = " << sky.radiance_145_point_integral() / sky.horizontal_integral());
    CHECK(std::abs(sky.radiance_145_point_integral() / sky.horizontal_integral() - 1) > 1e-4);
  }
}

namespace {

// One hour's sky through the window of test_illuminance (y = 0, x ∈ [0, 2], z ∈ [1, 2.2], the
// room at y > 0) seen from p with n = z, optionally behind a wall at y = −0.5, x ∈ [−5, 7], up to
// z = 1.6, which hides from p the window below z = 0.85 + 0.75 (1.6 − 0.85) = 1.4125 (central
// projection onto y = 0: t = 1.5/2). ∫ over the visible window rectangle of (L/L_z)(u) (n·u)
// |m·(x − p)| / r³ dA, graded towards the sun's point on the window plane (the indicatrix's kink).
ld window_reference(const Reference& r, const LVec3& s, ld lv_zenith, const Vec3& p, bool obstructed) {
  const ld z0 = obstructed ? 0.85L + 0.75L * (1.6L - 0.85L) : 1.0L;
  const LVec3 origin{0, 0, z0}, e1{2, 0, 0}, e2{0, 0, 2.2L - z0};
  const ld sun_s = 0.5L, sun_t = (1.8L - z0) / (2.2L - z0);
  const LVec3 lp = test::lvec(p);
  return test::integrate_parallelogram_graded(
      origin, e1, e2,
      [&](const LVec3& x) {
        const LVec3 d{x.x - lp.x, x.y - lp.y, x.z - lp.z};
        const ld r2 = d.x * d.x + d.y * d.y + d.z * d.z, rr = std::sqrt(r2);
        const LVec3 u{d.x / rr, d.y / rr, d.z / rr};
        return lv(r, s, u) / lv_zenith * u.z * std::abs(d.y) / (r2 * rr);
      },
      sun_s, sun_t, 1e-3L, 1e-3L, 16);
}

Scene window_scene_for_perez(bool obstructed) {
  Scene scene;
  scene.apertures.push_back({test::polygon({{0, 0, 1}, {2, 0, 1}, {2, 0, 2.2}, {0, 0, 2.2}}), 1.0});
  if (obstructed) scene.occluders.push_back(test::polygon({{-5, -0.5, 0}, {7, -0.5, 0}, {7, -0.5, 1.6}, {-5, -0.5, 1.6}}));
  return scene;
}

// The hour of the annual cases for a sensor at p: the sun through the window's point (1, 0, 1.8),
// so that the circumsolar peak lies in the region; its Perez sky (published model) and the
// long-double reference's condition.
struct WindowHour {
  Vec3 sun;
  double zenith_deg;
  PerezSky sky;
  Reference r;
  LVec3 s;
  ld lv_zenith;
};
WindowHour window_hour(const Vec3& p) {
  const Vec3 sun = normalized(Vec3{1, 0, 1.8} - p);
  const double zenith_deg = std::acos(sun.z) * 180 / std::numbers::pi;
  const Reference r = reference(70, 800, zenith_deg, 1400);
  const LVec3 s = test::lvec(sun);
  return {sun, zenith_deg, PerezSky(perez_condition(input(70, 800, zenith_deg), PerezClamps::none), sun, PerezClamps::none),
          r, s, lv(r, s, {0, 0, 1})};
}

}  // namespace

TEST_CASE("the fixed-rule normalisation agrees with tensor Gauss-Legendre in long double to 1e-12 on hard skies") {
  // Coefficients given directly (the integral is what is tested, whatever the condition): those of
  // the Chicago TMY3 hour (sun at 3.86°; printed to six digits) where the fixed rule's orders 48
  // to 200 agreed to 1e-15 and the adaptive Gauss–Kronrod rule differed from them by 4.7e-11; a
  // gradation almost a step at the horizon (b = −0.04: the fixed rule's orders disagree and the
  // adaptive rule serves it); a steep one (b = −5.5, the sun 0.1° up: measured, the fixed rule
  // 4e-14 from the reference, the adaptive 7.7e-12); a sun at the zenith.
  struct Coefficients {
    double a, b, c, d, e, zenith_deg;
  };
  const Coefficients skies[] = {{0.389785, -0.508183, 1.34042, -0.910215, 0.0667805, 90 - 3.85822},
                                {-0.865997, -0.0384017, 14.8567, -4.52875, 0.943091, 85},
                                {0.421822, -5.53626, 39.5627, -3.00531, -0.708587, 89.9},
                                {-1.02566, -0.28055, 28.4281, -6.46856, 1.60605, 0}};
  for (const Coefficients& k : skies) {
    PerezCondition p;
    p.a = k.a, p.b = k.b, p.c = k.c, p.d = k.d, p.e = k.e;
    const PerezSky sky(p, sun_at(k.zenith_deg, 120), PerezClamps::none);
    Reference r{};
    r.a = k.a, r.b = k.b, r.c = k.c, r.d = k.d, r.e = k.e;
    const ld zenith = std::acos((ld)sky.sun().z), azimuth = std::atan2((ld)sky.sun().x, (ld)sky.sun().y);
    const ld want = reference_normalisation(r, zenith, azimuth);
    INFO("a " << k.a << ", b " << k.b << ", sun zenith " << k.zenith_deg);
    CHECK(sky.horizontal_integral() == Approx(double(want)).epsilon(1e-12));
    WARN("fixed rule " << sky.normalised_by_fixed_rule() << ": / reference - 1 = "
                       << double(sky.horizontal_integral() / want - 1) << "; adaptive / reference - 1 = "
                       << double(sky.adaptive_normalisation() / want - 1));
  }
}

TEST_CASE("the fixed-rule normalisation serves nearly every sky and agrees with the adaptive rule") {
  // A grid of conditions across the eight ε bins (diffuse 20–400 W/m², direct 0–1000), sun zeniths
  // from the zenith itself to 0.1° above the horizon (where circles about the sun touch the
  // horizon at both ends), with and without Radiance's clamps. Conditions the published model
  // refuses (negative luminance, b > 0) are skipped; those Radiance floors at 0 take the
  // hemisphere's cubature and do not reach the fixed rule.
  int skies = 0, fixed = 0;
  double worst = 0;
  for (PerezClamps clamps : {PerezClamps::none, PerezClamps::radiance})
    for (double Ed : {20.0, 80.0, 200.0, 400.0})
      for (double I : {0.0, 100.0, 400.0, 850.0, 1000.0})
        for (double zenith : {0.0, 15.0, 40.0, 60.0, 75.0, 85.0, 89.0, 89.9}) {
          std::optional<PerezSky> sky;
          try {
            sky.emplace(perez_condition(input(Ed, I, zenith), clamps), sun_at(zenith, 120), clamps);
          } catch (const Error&) {
            continue;
          }
          ++skies;
          if (!sky->normalised_by_fixed_rule()) continue;
          ++fixed;
          const double adaptive = sky->adaptive_normalisation();
          INFO("Ed " << Ed << ", I " << I << ", zenith " << zenith << ", clamps " << int(clamps));
          // Both promise 1e-12, but the adaptive rule's own error reaches 7.7e-12 here (sun 0.1°
          // up, b = −5.5, against the long-double reference above) and differed from the fixed
          // rule by 4.7e-11 on one hour of the Chicago TMY3 year, where the fixed rule's orders
          // 48 to 200 agreed to 1e-15: the adaptive rule is the looser of the two.
          CHECK(sky->horizontal_integral() == Approx(adaptive).epsilon(1e-10));
          worst = std::max(worst, std::abs(sky->horizontal_integral() / adaptive - 1));
        }
  WARN(fixed << " of " << skies << " skies by the fixed rule; largest difference from the adaptive rule " << worst);
  CHECK(skies > 250);
  // The fixed rule is the fast path: it must serve nearly every sky, or the adaptive cost returns
  // (measured: 236 of 263 here, the others mostly Radiance's clamps with the sun within 5° of the
  // horizon or b > 0; all 4,691 sky hours of the Chicago TMY3 year).
  CHECK(fixed >= 0.85 * skies);
}

TEST_CASE("one Perez hour through an unobstructed and an obstructed window agrees with a 2-D quadrature to 1e-6") {
  // The window of test_illuminance (y = 0, x ∈ [0, 2], z ∈ [1, 2.2], the room at y > 0); the sun
  // seen through it from the sensor, so that the circumsolar peak lies in the region. The
  // obstruction: a wall at y = −0.5, x ∈ [−5, 7], up to z = 1.6, which hides from p the window below
  // z = 0.85 + 0.75 (1.6 − 0.85) = 1.4125 (central projection onto y = 0: t = 1.5/2).
  const Vec3 p{0.6, 1.5, 0.85}, n{0, 0, 1};
  const Vec3 sun = normalized(Vec3{1, 0, 1.8} - p);
  const double zenith_deg = std::acos(sun.z) * 180 / std::numbers::pi;
  const PerezCondition condition = perez_condition(input(70, 800, zenith_deg), PerezClamps::none);
  REQUIRE(condition.bin == 8);
  DaylightConditions c;
  c.sky = DaylightConditions::Sky::perez;
  c.perez.emplace(condition, sun, PerezClamps::none);
  c.quadrature_tolerance = 1e-10;
  const double E_dh = 12000;  // lux
  c.zenith_luminance = E_dh / unobstructed_sky_irradiance(c);
  const Reference r = reference(70, 800, zenith_deg, 1400);
  const LVec3 s = test::lvec(sun);
  const ld lv_zenith = lv(r, s, {0, 0, 1});
  SensorGrid grid;
  grid.sensors = {{p, n}};
  for (bool obstructed : {false, true}) {
    INFO((obstructed ? "obstructed" : "unobstructed"));
    const Scene scene = window_scene_for_perez(obstructed);
    const VisibilityEngine engine(scene, GeometryMode::exact);
    const IlluminanceResult got = illuminance(engine, scene, grid, c);
    const ld integral = window_reference(r, s, lv_zenith, p, obstructed);
    const double want = double(integral) * c.zenith_luminance;
    WARN((obstructed ? "obstructed" : "unobstructed") << ": " << got.sky_lux[0] << " lux, / reference - 1 = " << got.sky_lux[0] / want - 1);
    CHECK(got.sky_lux[0] == Approx(want).epsilon(1e-6));
    CHECK(got.sky_error_lux[0] < 1e-6 * want);
  }
}

TEST_CASE("the annual daylight coefficients of one Perez hour agree with a 2-D quadrature to 1e-6, by basis degree") {
  // The same hour and window as above, through the annual path (simulation/annual.hpp): the smooth
  // part as a dot product of the sensor's moments with the hour's fit, the circumsolar term by
  // cubature in the sun's frame. The table shows the error and the hour's bound against the
  // basis degree D; from D = 24 on the bound itself is below 1e-6 (measured: see the WARN lines).
  const Vec3 p{0.6, 1.5, 0.85}, n{0, 0, 1};
  const WindowHour h = window_hour(p);
  const Vec3& sun = h.sun;
  const PerezSky& sky = h.sky;
  const Reference& r = h.r;
  const LVec3& s = h.s;
  const ld lv_zenith = h.lv_zenith;
  const double E_dh = 12000;
  const double zenith_luminance = E_dh / sky.horizontal_irradiance_over_zenith();
  const Sensor sensor{p, n};
  for (bool obstructed : {false, true}) {
    INFO((obstructed ? "obstructed" : "unobstructed"));
    const Scene scene = window_scene_for_perez(obstructed);
    const VisibilityEngine engine(scene, GeometryMode::exact);
    const WindowGroups groups = window_groups(scene);
    const double want = double(window_reference(r, s, lv_zenith, p, obstructed)) * zenith_luminance;
    for (int degree : {4, 8, 12, 16, 24, 32}) {
      AnnualOptions options;
      options.degree = degree;
      options.circumsolar_tolerance = 1e-10;
      const AnnualHour hour = annual_hour(sky, sun, E_dh, 0, options);
      VisibilityCounters counters;
      const SensorCoefficients coefficients = sensor_coefficients(engine, scene, sensor, groups, degree, counters);
      const HourIlluminance got = hour_illuminance(scene, sensor, coefficients, hour, options);
      const double error = std::abs(got.sky_lux / want - 1);
      WARN((obstructed ? "obstructed" : "unobstructed") << " D = " << degree << ": |annual / reference - 1| = " << error
                                                        << ", bound / reference = " << got.bound_lux / want
                                                        << ", gradation fit error " << hour.fit.gradation_max_error);
      // The bound must hold at every degree (it is what the annual run reports)...
      CHECK(std::abs(got.sky_lux - want) <= got.bound_lux + 1e-9 * want);
      // ...and at D ≥ 24 the result is within 1e-6.
      if (degree >= 24) CHECK(error < 1e-6);
    }
    // The production path (the sensor's fixed rules, adaptive cubature where the sun is near the
    // region) at the annual default tolerance of the circumsolar term: the sun is in view, so the
    // fixed rules must give way.
    AnnualOptions options;
    const AnnualHour hour = annual_hour(sky, sun, E_dh, 0, options);
    VisibilityCounters counters;
    const SensorCoefficients coefficients = sensor_coefficients(engine, scene, sensor, groups, options.degree, counters);
    const CircumsolarRule rule = circumsolar_rule(scene, sensor, coefficients);
    const HourIlluminance got = hour_illuminance(scene, sensor, coefficients, hour, options, &rule);
    WARN("production path: |annual / reference - 1| = " << std::abs(got.sky_lux / want - 1));
    CHECK(got.adaptive);
    CHECK(std::abs(got.sky_lux / want - 1) < 1e-6);
    // A sun far from the window (the same zenith angle, so the same bin, turned by 180° about z to
    // shine on the room's back): the sensor's fixed rules carry the circumsolar term, and must
    // agree with the reference as well.
    const Vec3 far_sun{-sun.x, -sun.y, sun.z};
    const double far_zenith = std::acos(far_sun.z) * 180 / std::numbers::pi;
    const PerezSky far_sky(perez_condition(input(70, 800, far_zenith), PerezClamps::none), far_sun, PerezClamps::none);
    const Reference far_r = reference(70, 800, far_zenith, 1400);
    const LVec3 fs = test::lvec(far_sun);
    const double far_want = double(window_reference(far_r, fs, lv(far_r, fs, {0, 0, 1}), p, obstructed)) * E_dh /
                            far_sky.horizontal_irradiance_over_zenith();
    const HourIlluminance far = hour_illuminance(scene, sensor, coefficients, annual_hour(far_sky, far_sun, E_dh, 0, options),
                                                 options, &rule);
    WARN("far sun, fixed rules: |annual / reference - 1| = " << std::abs(far.sky_lux / far_want - 1));
    CHECK_FALSE(far.adaptive);
    CHECK(std::abs(far.sky_lux / far_want - 1) < 1e-6);
    // The far pieces take order 8 where orders 6 and 8 agree within the tolerance, else order 12
    // where 8 and 12 do, else the whole term goes to cubature: from a loose tolerance to one
    // beyond order 12 (6 and 8 agree to about 1e-9 here, 8 and 12 to 1e-10 or 1e-13), each step
    // is taken, and the bound holds against the reference at each.
    std::set<int> orders;
    bool cubature = false;
    for (double tolerance : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13, 1e-14, 1e-15}) {
      AnnualOptions tight;
      tight.circumsolar_tolerance = tolerance;
      const HourIlluminance h = hour_illuminance(scene, sensor, coefficients,
                                                 annual_hour(far_sky, far_sun, E_dh, 0, tight), tight, &rule);
      INFO("tolerance " << tolerance << ", far order " << h.far_order);
      orders.insert(h.far_order);
      cubature = cubature || h.adaptive;
      CHECK(std::abs(h.sky_lux - far_want) <= h.bound_lux + 1e-9 * far_want);
    }
    CHECK(orders == std::set<int>{0, kCircumsolarOrderLow, kCircumsolarOrderHigh});
    CHECK(cubature);
  }
}

TEST_CASE("a sensor 0.25 m from the window: the moments' two orders agree, the hour and its bound are tight") {
  // Seen from 0.25 m, the window spans about 150° across: its fan triangles' chord planes pass
  // near the sensor's centre of directions, where an unsplit product rule converges slowly (the
  // two orders differed by 3 % of the Lambert weight here, and the hour's bound said so: 11 % of
  // the result, though the higher order was within 1e-7). Split to sides of kMomentMaxSide (fan_product_rule.hpp), the orders agree to
  // roundoff and the bound is the fit's. The sun through the window's point (1, 0, 1.8), so that
  // the circumsolar peak lies in the region, as in the cases above.
  const Vec3 p{1.0, 0.25, 0.85}, n{0, 0, 1};
  const WindowHour h = window_hour(p);
  const Vec3& sun = h.sun;
  const PerezSky& sky = h.sky;
  const double E_dh = 12000;
  const double want = double(window_reference(h.r, h.s, h.lv_zenith, p, false)) * E_dh / sky.horizontal_irradiance_over_zenith();
  const Scene scene = window_scene_for_perez(false);
  const VisibilityEngine engine(scene, GeometryMode::exact);
  const Sensor sensor{p, n};
  AnnualOptions options;
  options.circumsolar_tolerance = 1e-10;
  VisibilityCounters counters;
  const SensorCoefficients coefficients = sensor_coefficients(engine, scene, sensor, window_groups(scene), options.degree, counters);
  const HourIlluminance got = hour_illuminance(scene, sensor, coefficients, annual_hour(sky, sun, E_dh, 0, options), options);
  WARN("near sensor: moment error " << coefficients.moment_error << ", |annual / reference - 1| = "
                                    << std::abs(got.sky_lux / want - 1) << ", bound / reference = " << got.bound_lux / want);
  // Orders 20 and 28 on every split triangle: a double-precision sum of some 10⁴ terms.
  CHECK(coefficients.moment_error < 1e-12);
  CHECK(std::abs(got.sky_lux / want - 1) < 1e-6);
  CHECK(std::abs(got.sky_lux - want) <= got.bound_lux + 1e-9 * want);
  // The bound is then the gradation fit's (measured 1e-6 of the result at D = 32), not the rule's.
  CHECK(got.bound_lux < 1e-5 * want);
}

TEST_CASE("Radiance's clamps change what they should and nothing else") {
  SECTION("Δ is raised to 0.2 for the coefficients of 1.065 < ε < 2.8, the condition and efficacies unchanged") {
    const PerezCondition none = perez_condition(input(150, 300, 50), PerezClamps::none);
    const PerezCondition rad = perez_condition(input(150, 300, 50), PerezClamps::radiance);
    REQUIRE(none.brightness < 0.2);
    CHECK(rad.brightness == none.brightness);
    CHECK(rad.clearness == none.clearness);
    CHECK(rad.air_mass == none.air_mass);
    CHECK(rad.diffuse_efficacy == none.diffuse_efficacy);
    CHECK(rad.direct_efficacy == none.direct_efficacy);
    CHECK(rad.brightness_used == 0.2);
    CHECK(rad.sun_zenith_used_deg == 50);
    REQUIRE(rad.clamps_applied.size() == 1);
    CHECK(rad.clamps_applied[0].find("raised to 0.2") != std::string::npos);
    const Reference r02 = reference(150 * 0.2 / none.brightness, 300 * 0.2 / none.brightness, 50, 1400);
    CHECK(rad.a == Approx(double(r02.a)).epsilon(1e-12));  // the coefficients of Δ = 0.2, same ε
    CHECK(rad.e == Approx(double(r02.e)).epsilon(1e-12));
  }
  SECTION("a clear sky outside the clamps' reach keeps its luminance above 0.57° altitude") {
    const PerezCondition none = perez_condition(input(80, 850, 30), PerezClamps::none);
    const PerezCondition rad = perez_condition(input(80, 850, 30), PerezClamps::radiance);
    CHECK(rad.clamps_applied.empty());
    const PerezSky a(none, sun_at(30, 170), PerezClamps::none), b(rad, sun_at(30, 170), PerezClamps::radiance);
    for (double alt : {1.0, 5.0, 30.0, 60.0, 89.0})
      for (double az : {0.0, 90.0, 170.0, 250.0}) {
        const Vec3 u = sun_at(90 - alt, az);
        CHECK(a.luminance_function(u) == b.luminance_function(u));
      }
    // Below cos θ = 0.01 the gradation is held at its value there: the change in N is about
    // |a| e^{b/0.01} × (the band's weight ~1e-4), far below 1e-8 here.
    CHECK(b.horizontal_integral() == Approx(a.horizontal_integral()).epsilon(1e-8));
  }
  SECTION("the sun above 87° is lowered for the sky only under the radiance clamps") {
    const PerezCondition none = perez_condition(input(100, 600, 2), PerezClamps::none);
    const PerezCondition rad = perez_condition(input(100, 600, 2), PerezClamps::radiance);
    CHECK(none.sun_zenith_used_deg == 2);
    CHECK(rad.sun_zenith_used_deg == 3);
    const PerezSky b(rad, sun_at(2, 120), PerezClamps::radiance);
    CHECK(b.sun().z == Approx(std::sin(87 * std::numbers::pi / 180)).epsilon(1e-15));
    CHECK(std::atan2(b.sun().x, b.sun().y) * 180 / std::numbers::pi == Approx(120).epsilon(1e-12));
    CHECK(PerezSky(none, sun_at(2, 120), PerezClamps::none).sun().z == Approx(std::cos(2 * std::numbers::pi / 180)));
  }
  SECTION("a negative direct efficacy (a low sun) is refused only where the direct illuminance must come from it") {
    const PerezCondition none = perez_condition(input(30, 5, 85), PerezClamps::none);
    REQUIRE(none.bin == 1);
    REQUIRE(none.direct_efficacy < 0);
    CHECK(none.clamps_applied.empty());
    const PerezCondition rad = perez_condition(input(30, 5, 85), PerezClamps::radiance);
    CHECK(rad.direct_efficacy == 0);
    REQUIRE(rad.clamps_applied.size() == 1);
    CHECK(rad.clamps_applied[0].find("direct efficacy") != std::string::npos);
    CHECK(rad.a == none.a);  // nothing else moves
    CHECK(rad.diffuse_efficacy == none.diffuse_efficacy);
    PerezHourInput h;
    h.diffuse_horizontal_irradiance = 30;
    h.direct_normal_irradiance = 5;
    h.dew_point_c = 5;
    h.sun_zenith_deg = 85;
    h.sun = sun_at(85, 100);
    h.distance_au = std::sqrt(kSolarConstant / 1400);  // E_0 = 1400 W/m², as input() gives
    CHECK_THROWS_WITH(perez_hour(h), Catch::Contains("direct luminous efficacy"));
    h.direct_normal_illuminance = 400;
    CHECK(perez_hour(h).direct_normal_lux == 400);
    h.direct_normal_illuminance.reset();
    h.clamps = PerezClamps::radiance;
    CHECK(perez_hour(h).direct_normal_lux == 0);
    h.direct_normal_irradiance = 0;  // no direct light: no efficacy needed
    h.clamps = PerezClamps::none;
    CHECK(perez_hour(h).direct_normal_lux == 0);
  }
  SECTION("a gradation that diverges at the horizon (b > 0) is refused without clamps, finite with them") {
    const PerezCondition none = perez_condition(input(30, 21, 20), PerezClamps::none);
    REQUIRE(none.bin == 4);
    REQUIRE(none.b > 0);
    try {
      PerezSky(none, sun_at(20, 180), PerezClamps::none);
      FAIL("accepted");
    } catch (const Error& e) {
      CHECK(std::string(e.what()).find("diverges at the horizon") != std::string::npos);
      CHECK(std::string(e.what()).find("--perez-clamps radiance") != std::string::npos);
    }
    const PerezSky rad(perez_condition(input(30, 21, 20), PerezClamps::radiance), sun_at(20, 180), PerezClamps::radiance);
    CHECK(rad.condition().b < 0);
    CHECK(std::isfinite(rad.horizontal_integral()));
    CHECK(rad.horizontal_integral() > 0);
  }
}

TEST_CASE("the Perez condition refuses what it cannot use") {
  CHECK_THROWS_AS(perez_condition(input(0, 100, 30), PerezClamps::none), Error);
  CHECK_THROWS_AS(perez_condition(input(100, -1, 30), PerezClamps::none), Error);
  CHECK_THROWS_AS(perez_condition(input(100, 100, 90), PerezClamps::none), Error);
  CHECK_THROWS_AS(perez_condition(input(NAN, 100, 30), PerezClamps::none), Error);
  CHECK(parse_perez_clamps("radiance") == PerezClamps::radiance);
  CHECK_THROWS_AS(parse_perez_clamps("gendaylit"), Error);
}

TEST_CASE("illuminances alone give back the irradiances whose efficacies made them (the .wea-in-lux path)") {
  for (const Case& k : kCases) {
    INFO("bin " << k.bin);
    PerezHourInput h;
    h.diffuse_horizontal_irradiance = k.Ed;
    h.direct_normal_irradiance = k.I;
    h.dew_point_c = 5;
    h.sun_zenith_deg = k.zenith_deg;
    h.sun = sun_at(k.zenith_deg, k.azimuth_deg);
    const PerezHour forward = perez_hour(h);
    CHECK(forward.iterations == 0);
    CHECK(forward.diffuse_lux_from_efficacy);
    PerezHourInput back = h;
    back.diffuse_horizontal_irradiance.reset();
    back.direct_normal_irradiance.reset();
    back.diffuse_horizontal_illuminance = forward.diffuse_horizontal_lux;
    back.direct_normal_illuminance = forward.direct_normal_lux;
    const PerezHour inverse = perez_hour(back);
    // A fixed point of E = lux / efficacy(ε(E), Δ(E)), iterated to 1e-9 relative.
    CHECK(inverse.iterations > 0);
    CHECK(inverse.iterations < 100);
    CHECK(inverse.diffuse_horizontal_irradiance == Approx(k.Ed).epsilon(1e-8));
    CHECK(inverse.direct_normal_irradiance == Approx(k.I).epsilon(1e-8).margin(1e-9));
    CHECK(inverse.sky.condition().bin == k.bin);
  }
}

TEST_CASE("under Radiance's clamps a sky that is negative near the zenith is cut at 0, named, and normalised exactly") {
  // A hand-made condition: gradation 1 − 1.5 e^{−0.2/cos θ} < 0 for cos θ > 0.2/ln 1.5 (θ < 60.4°).
  PerezCondition p;
  p.a = -1.5, p.b = -0.2, p.c = 5, p.d = -2, p.e = 0.3;
  const Vec3 sun = sun_at(70, 200);
  CHECK_THROWS_WITH(PerezSky(p, sun, PerezClamps::none), Catch::Contains("negative in part of the sky"));
  // Without the zenith (gradation < 0 there) the radiance sky's zenith luminance is 0: refused.
  CHECK_THROWS_WITH(PerezSky(p, sun, PerezClamps::radiance), Catch::Contains("zenith luminance is 0"));
  // With the gradation positive at the zenith and negative nowhere, but the indicatrix negative
  // away from the sun (e < −1 − c e^{dγ} there), the floor acts on a band of γ.
  p.a = -0.5, p.b = -0.3, p.c = 0.5, p.d = -3, p.e = -1.3;
  const PerezSky sky(p, sun, PerezClamps::radiance);
  REQUIRE(sky.condition().clamps_applied.size() == 1);
  CHECK(sky.condition().clamps_applied[0].find("set to 0") != std::string::npos);
  // Reference, in the sun's polar frame u = cos γ s + sin γ (cos ψ e1 + sin ψ e2), e1 towards the
  // zenith: there the indicatrix depends on γ alone, so its zero set (where the floor acts) is a
  // set of γ-circles, found by bisection and made panel ends; for each γ the directions above the
  // horizon, and above cos θ = 0.01 (the gradation's clamp), are exact ψ-arcs |ψ| ≤ acos q with
  // q = (h − cos γ cos Z)/(sin γ sin Z) (h = 0, 0.01). Panels in γ are graded towards the
  // tangencies γ = acos h ± Z, where the arcs' lengths have square-root ends.
  const ld Z = std::acos((ld)sky.sun().z);
  auto F = [&](ld g) { return 1 + (ld)p.c * std::exp((ld)p.d * g) + (ld)p.e * std::cos(g) * std::cos(g); };
  auto G = [&](ld t) { return 1 + (ld)p.a * std::exp((ld)p.b / std::max<ld>(t, 0.01L)); };
  std::vector<ld> foci;
  for (ld h : {0.0L, 0.01L})
    for (ld g : {std::acos(h) - Z, std::acos(h) + Z})
      if (g > 0 && g < kPi) foci.push_back(g);
  constexpr int kScan = 20000;
  for (int i = 0; i < kScan; ++i) {
    ld lo = kPi * i / kScan, hi = kPi * (i + 1) / kScan;
    if ((F(lo) < 0) == (F(hi) < 0)) continue;
    for (int k = 0; k < 200; ++k) {
      const ld mid = (lo + hi) / 2;
      ((F(mid) < 0) == (F(lo) < 0) ? lo : hi) = mid;
    }
    foci.push_back((lo + hi) / 2);
  }
  REQUIRE(foci.size() >= 5);  // four tangencies and at least one zero of the indicatrix
  auto arc = [&](ld g, ld h) {  // the half-width of the arc of ψ where u_z ≥ h
    const ld q = (h - std::cos(g) * std::cos(Z)) / (std::sin(g) * std::sin(Z));
    return q <= -1 ? kPi : q >= 1 ? 0.0L : std::acos(q);
  };
  auto integrate = [&](int order) {
    std::vector<ld> x, w;
    test::gauss_legendre(order, x, w);
    auto gl = [&](ld lo, ld hi, const std::function<ld(ld)>& f) {
      ld sum = 0;
      for (std::size_t k = 0; k < x.size(); ++k) sum += w[k] * f(lo + (hi - lo) * (x[k] + 1) / 2);
      return sum * (hi - lo) / 2;
    };
    const auto bg = graded(0, kPi, foci, 1e-12L);
    ld total = 0;
    for (std::size_t i = 0; i + 1 < bg.size(); ++i)
      total += gl(bg[i], bg[i + 1], [&](ld g) {
        const ld f = F(g);
        if (f <= 0) return 0.0L;
        const ld a0 = arc(g, 0), a1 = arc(g, 0.01L);
        auto inner = [&](ld psi) {
          const ld t = std::cos(g) * std::cos(Z) + std::sin(g) * std::sin(Z) * std::cos(psi);
          return G(t) * t;
        };
        return 2 * f * std::sin(g) * (gl(0, a1, inner) + gl(a1, a0, inner));
      });
    return total;
  };
  // The reference converges algebraically (orders 8, 16, 24, 32 against 40: 5e-6, 1e-7, 5e-10,
  // 1e-11), so orders 32 and 40 bound its own error.
  const ld fine = integrate(40), coarse = integrate(32);
  const double reference_spread = double(std::abs(fine - coarse) / fine);
  WARN("floored sky: cubature / reference - 1 = " << double(sky.horizontal_integral() / fine - 1)
                                                   << " (reference orders 32 and 40 differ by " << reference_spread << ")");
  REQUIRE(reference_spread < 1e-10);
  // The cubature meets the floor's kink along curves its triangles do not follow; it is held to
  // 1e-9 here (measured: see the warning), not the 1e-12 of the smooth skies.
  CHECK(sky.horizontal_integral() == Approx(double(fine)).epsilon(1e-9));
}
