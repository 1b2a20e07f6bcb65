// The Monte Carlo path tracer of bench/path_tracer.hpp against independent exact values: the exact
// sky component on the bundled samples, closed forms outdoors, in a closed box, under a canopy and
// in an open-ceiling box (Howell's factors, bench/reflection_cases.hpp), and the flux balance of a
// box with an opening, bounce by bounce.
//
// Statistical bounds: each estimate is held within 5 standard errors (σ estimated from the paths;
// conservative under stratification) of the exact value, plus a 1e-9 relative allowance for the
// rounding of the reference, and every σ is required to be small enough (a stated fraction of the
// value) that the check can fail. The seeds are fixed, so every run draws the same numbers: a pass
// is reproducible, and the chance that a correct tracer fails some 5σ check here is below 1e-4.

#include <catch2/catch.hpp>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <numbers>

#include "bench/path_tracer.hpp"
#include "bench/reflection_cases.hpp"
#include "geometry/error.hpp"
#include "geometry/visibility.hpp"
#include "illumination/xoshiro256.hpp"
#include "materials/scene_materials.hpp"
#include "simulation/sky_component.hpp"

using namespace daylit;
namespace rc = daylit::reflection_cases;

namespace {

// |estimate − exact| within 5σ (plus the reference's rounding).
bool within(const TracedEstimate& e, double exact) {
  return std::abs(e.value - exact) <= 5 * e.standard_error + 1e-9 * std::abs(exact);
}

PathTracerOptions options(long samples, int bounces, SkyModel sky, double ground = 0.2, std::uint64_t seed = 7) {
  PathTracerOptions o;
  o.samples_per_sensor = samples;
  o.max_bounces = bounces;
  o.sky = sky;
  o.ground_reflectance = ground;
  o.seed = seed;
  return o;
}

}  // namespace

TEST_CASE("path tracer: SC of the samples' sensors within 5 sigma of the exact sky component (glazed and open)") {
  struct Sample {
    const char* name;
    std::vector<std::size_t> indices;
  };
  for (const Sample& sample : {Sample{"office", {0, 137, 620, 1201, 1530, 2399}}, Sample{"hall", {0, 700, 2333, 4000}}}) {
    const std::string base = std::string(DAYLIT_SAMPLES_DIR) + "/" + sample.name;
    const Scene scene = load_scene({base + "/scene.rad"}, {base + "/apertures.rad"});
    const SensorGrid grid = read_sensor_grid(base + "/grid.pts");
    std::vector<Sensor> sensors;
    for (std::size_t i : sample.indices) sensors.push_back(grid.sensors[i]);
    const auto traced = path_trace(scene, sensors, options(65536, 0, SkyModel::cie_overcast));
    const VisibilityEngine engine(scene, GeometryMode::exact);
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      VisibilityCounters counters;
      const double exact = sky_component_percent(engine, scene, sensors[i], SkyModel::cie_overcast, counters);
      INFO(sample.name << " sensor " << sample.indices[i] << ": traced " << traced[i].sc.value << " ± "
                       << traced[i].sc.standard_error << ", exact " << exact);
      CHECK(within(traced[i].sc, exact));
      // At 65,536 paths σ is below 5 % of SC (or 0.01 % DF where SC is a sliver; the hall's
      // rooflights, 2 % of the hemisphere's view, give the widest): a 5σ band that a wrong
      // transmittance or a leak would leave.
      CHECK(traced[i].sc.standard_error < 0.05 * exact + 0.01);
    }
  }
}

TEST_CASE("path tracer: outdoors, an upward sensor sees the sky alone and a downward one rho_g E_out") {
  for (const SkyModel sky : {SkyModel::cie_overcast, SkyModel::uniform}) {
    // Nothing but the far ground.
    const Scene empty;
    const auto r = path_trace(empty, {{{0, 0, 1}, {0, 0, 1}}, {{0, 0, 1}, {0, 0, -1}}}, options(4096, 4, sky, 0.3));
    CHECK(within(r[0].sc, 100));
    CHECK(r[0].sc.standard_error < 0.5);
    CHECK(r[0].erc.value == 0);
    CHECK(r[0].irc.value == 0);
    // The far ground's luminance is uniform: every path carries π·ρ_g·E_out/π exactly.
    CHECK(r[1].erc.value == Approx(30).epsilon(1e-12));
    CHECK(r[1].erc_by_bounce[0].value == Approx(30).epsilon(1e-12));
    CHECK(r[1].sc.value == 0);
    CHECK(r[1].df.value == Approx(30).epsilon(1e-12));

    // A ground surface of ρ = 0.3, 10 km square, lit by the whole sky: exitance ρ·E_out, the same
    // luminance as the far ground beyond its edge, so a downward sensor 1 m up sees 100 ρ % in all,
    // and all of it at the first bounce (the ground is hit directly: IRC by the definitions).
    Scene ground;
    ground.materials["ground"] = rc::grey_plastic("ground", 0.3);
    ground.occluders.push_back(rc::rectangle({-5000, -5000, 0}, {10000, 0, 0}, {0, 10000, 0}, "ground", "ground"));
    const auto g = path_trace(ground, {{{0, 0, 1}, {0, 0, -1}}, {{0, 0, 1}, {0, 0, 1}}}, options(4096, 4, sky, 0.3));
    CHECK(within(g[0].df, 30));
    CHECK(g[0].df.standard_error < 0.3);
    CHECK(within(g[0].irc_by_bounce[1], 30));
    CHECK(g[0].irc_by_bounce[2].value == 0);
    CHECK(within(g[1].sc, 100));
    CHECK(g[1].irc.value == 0);
    CHECK(g[1].erc.value == 0);
  }
}

TEST_CASE("path tracer: the sun outdoors, on an open sensor, in the far ground and on a lit ground surface") {
  // The sun 40° from the zenith, its direct normal irradiance 3 E_out. An upward sensor in the
  // open gets 300 cos 40° % of it directly (the disk's mean cosine about its centre is
  // 1 − ρ²/4 ≈ 1 − 5e-6: within 1e-4), nothing reflected; a downward one the far ground, whose
  // luminance now carries the sun's horizontal part: 100 ρ_g (1 + 3 cos 40°) %, on every path.
  const double ratio = 3, zenith = 40 * std::numbers::pi / 180;
  PathTracerOptions o = options(4096, 4, SkyModel::cie_overcast, 0.3);
  o.sun = {0, std::sin(zenith), std::cos(zenith)};
  o.sun_normal = ratio;
  const Scene empty;
  const auto r = path_trace(empty, {{{0, 0, 1}, {0, 0, 1}}, {{0, 0, 1}, {0, 0, -1}}}, o);
  CHECK(r[0].sun.value == Approx(100 * ratio * std::cos(zenith)).epsilon(1e-4));
  CHECK(within(r[0].sc, 100));
  CHECK(r[0].erc.value == 0);
  CHECK(r[0].irc.value == 0);
  CHECK(r[0].df.value == Approx(r[0].sc.value + r[0].sun.value).epsilon(1e-12));
  CHECK(r[1].sun.value == 0);
  CHECK(r[1].erc.value == Approx(30 * (1 + ratio * std::cos(zenith))).epsilon(1e-12));
  // A ground surface of ρ = 0.3, 10 km square, lit by sky and sun: exitance ρ (E_out + E_sun
  // cos 40°), the far ground's luminance beyond its edge, so downward sensors 1 m and 50 m up
  // (their shadows points) see 100 ρ (1 + 3 cos 40°) % in all, the sun's part by next-event
  // estimation at the ground.
  Scene ground;
  ground.materials["ground"] = rc::grey_plastic("ground", 0.3);
  ground.occluders.push_back(rc::rectangle({-5000, -5000, 0}, {10000, 0, 0}, {0, 10000, 0}, "ground", "ground"));
  const auto g = path_trace(ground, {{{0, 0, 1}, {0, 0, -1}}, {{0, 0, 50}, {0, 0, -1}}}, o);
  for (const auto& t : g) {
    INFO("traced " << t.df.value << " ± " << t.df.standard_error);
    CHECK(within(t.df, 30 * (1 + ratio * std::cos(zenith))));
    CHECK(t.df.standard_error < 0.5);
    CHECK(t.sun.value == 0);
  }
}

TEST_CASE("path tracer: a closed box without apertures is dark at every bounce (no leaks at edges and corners)") {
  Scene box;
  box.materials["white"] = rc::grey_plastic("white", 0.9);
  const double W = 3, D = 4, H = 2.5;
  box.occluders = {rc::rectangle({0, 0, 0}, {W, 0, 0}, {0, D, 0}, "white", "floor"),
                   rc::rectangle({0, 0, H}, {0, D, 0}, {W, 0, 0}, "white", "ceiling"),
                   rc::rectangle({0, 0, 0}, {0, 0, H}, {W, 0, 0}, "white", "south"),
                   rc::rectangle({0, D, 0}, {W, 0, 0}, {0, 0, H}, "white", "north"),
                   rc::rectangle({0, 0, 0}, {0, D, 0}, {0, 0, H}, "white", "west"),
                   rc::rectangle({W, 0, 0}, {0, 0, H}, {0, D, 0}, "white", "east")};
  const std::vector<Sensor> sensors{{{1.5, 2, 0.85}, {0, 0, 1}}, {{1e-6, 1e-6, 1e-6}, {1, 1, 1}},
                                    {{W - 1e-9, D - 1e-9, H - 1e-9}, normalized(Vec3{-1, -1, -1})}, {{1.5, 1e-7, 1}, {0, 1, 0}}};
  const auto r = path_trace(box, sensors, options(4096, 12, SkyModel::cie_overcast));
  for (const PathTracedSensor& s : r) CHECK(s.df.value == 0);
}

TEST_CASE("path tracer: a plate over upward sensors (closed form: IRC = 100 rho rho_g F at the first bounce only)") {
  const rc::ReflectionCase c = rc::canopy_case();
  for (const SkyModel sky : {SkyModel::uniform, SkyModel::cie_overcast}) {
    const auto r = path_trace(c.scene, c.sensors, options(16384, 4, sky, c.ground_reflectance));
    for (std::size_t i = 0; i < c.sensors.size(); ++i) {
      INFO("sensor " << i << ": IRC " << r[i].irc.value << " ± " << r[i].irc.standard_error << ", exact " << c.irc[i]);
      CHECK(within(r[i].irc, c.irc[i]));
      CHECK(within(r[i].irc_by_bounce[1], c.irc[i]));
      CHECK(r[i].irc.standard_error < 0.03 * c.irc[i]);
      CHECK(r[i].irc_by_bounce[2].value == 0);
      CHECK(r[i].erc.value == 0);
      // The exact SC is the uniform sky's; the overcast one is not a closed form here.
      if (sky == SkyModel::uniform) CHECK(within(r[i].sc, c.sc[i]));
    }
  }
}

TEST_CASE("path tracer: a box with an open ceiling (IRC of downward sensors by Howell's F over the floor)") {
  const rc::ReflectionCase c = rc::open_ceiling_box_case();
  // The reference itself: the 8 × 8-panel quadrature agrees with 16 × 16 panels to 1e-13.
  {
    const Vec3 p = c.sensors[0].position;
    const auto f = [&](long double x, long double y) {
      const long double r2 = (x - p.x) * (x - p.x) + (y - p.y) * (y - p.y) + p.z * p.z;
      return rc::parallel_rectangle_factor(x, y, 3, 0, 4, 0, 5) * p.z * p.z / (r2 * r2);
    };
    const long double coarse = rc::rectangle_integral(f, 0, 4, 0, 5, 8), fine = rc::rectangle_integral(f, 0, 4, 0, 5, 16);
    CHECK(double(std::abs(coarse - fine) / fine) < 1e-13);
  }
  const auto r = path_trace(c.scene, c.sensors, options(16384, 6, c.sky, c.ground_reflectance));
  for (std::size_t i = 0; i < c.sensors.size(); ++i) {
    INFO("sensor " << i << ": SC " << r[i].sc.value << " (exact " << c.sc[i] << "), IRC " << r[i].irc.value << " ± "
                   << r[i].irc.standard_error << " (exact " << c.irc[i] << ")");
    CHECK(within(r[i].sc, c.sc[i]));
    CHECK(within(r[i].irc, c.irc[i]));
    CHECK(r[i].erc.value == 0);
    CHECK(r[i].irc.standard_error <= 0.02 * c.irc[i] + 1e-12);
    for (std::size_t k = 2; k < r[i].irc_by_bounce.size(); ++k) CHECK(r[i].irc_by_bounce[k].value == 0);
  }
  // An opening of transmittance 0.6 scales every value by 0.6: the next-event rays and the
  // continuations that leave through it both carry it.
  rc::ReflectionCase dimmed = c;
  dimmed.scene.apertures[0].transmittance = 0.6;
  const auto d = path_trace(dimmed.scene, dimmed.sensors, options(16384, 3, c.sky, c.ground_reflectance, 8));
  for (std::size_t i = 0; i < c.sensors.size(); ++i) {
    INFO("sensor " << i << " behind tau = 0.6: SC " << d[i].sc.value << ", IRC " << d[i].irc.value << " ± " << d[i].irc.standard_error);
    CHECK(within(d[i].sc, 0.6 * c.sc[i]));
    CHECK(within(d[i].irc, 0.6 * c.irc[i]));
  }
}

TEST_CASE("path tracer: the open ceiling cut into three apertures of unequal areas gives the same closed forms") {
  // Next-event estimation draws an aperture by area and a point on it: with several apertures the
  // density is 1/(their total area) wherever it lands. The ceiling as strips of 1, 1.5 and 2.5 m
  // (the same opening) must give the one-aperture closed forms; an area summed wrongly for any but
  // the first (once, by an uninitialised sum: 1/9 instead of 1/5.4 on a two-window room) shows as
  // an IRC up to 2/3 high, tens of standard errors here.
  rc::ReflectionCase c = rc::open_ceiling_box_case();
  const double W = 4, H = 3;
  c.scene.apertures.clear();
  double y0 = 0;
  for (const double width : {1.0, 1.5, 2.5}) {
    Aperture strip;
    strip.polygon = rc::rectangle({0, y0, H}, {0, width, 0}, {W, 0, 0}, "void", "strip");  // normal −z
    c.scene.apertures.push_back(strip);
    y0 += width;
  }
  const auto r = path_trace(c.scene, c.sensors, options(16384, 6, c.sky, c.ground_reflectance, 9));
  for (std::size_t i = 0; i < c.sensors.size(); ++i) {
    INFO("sensor " << i << ": SC " << r[i].sc.value << " (exact " << c.sc[i] << "), IRC " << r[i].irc.value << " ± "
                   << r[i].irc.standard_error << " (exact " << c.irc[i] << ")");
    CHECK(within(r[i].sc, c.sc[i]));
    CHECK(within(r[i].irc, c.irc[i]));
    CHECK(r[i].irc.standard_error <= 0.02 * c.irc[i] + 1e-12);
  }
}

TEST_CASE("path tracer: flux balance of a box with a ceiling opening, bounce by bounce") {
  // A 4 × 5 × 3 m box of uniform ρ = 0.5 with a 2 × 2 m opening in the ceiling, under the uniform
  // sky (L = 1). Φ_k: flux arriving on the interior surfaces after k reflections; Λ_k: flux leaving
  // through the opening after k reflections. Energy: ρ·Φ_k = Φ_{k+1} + Λ_{k+1}, and Φ_0 = π·A_open
  // (the opening sees the whole sky). Φ_k is the area integral of the bounce-k irradiance (SC for
  // k = 0, IRC_k after), estimated by tracing from sensors at uniformly random points of the
  // surfaces, facing in; Λ_k from sensors on the opening facing down. Sensors are independent, so
  // each mean's σ is the sensors' spread over √M; for a sum of correlated means the σ's add.
  const double W = 4, D = 5, H = 3, rho = 0.5;
  Scene scene;
  scene.materials["m"] = rc::grey_plastic("m", rho);
  auto& o = scene.occluders;
  o = {rc::rectangle({0, 0, 0}, {W, 0, 0}, {0, D, 0}, "m", "floor"), rc::rectangle({0, 0, 0}, {0, 0, H}, {W, 0, 0}, "m", "south"),
       rc::rectangle({0, D, 0}, {W, 0, 0}, {0, 0, H}, "m", "north"), rc::rectangle({0, 0, 0}, {0, D, 0}, {0, 0, H}, "m", "west"),
       rc::rectangle({W, 0, 0}, {0, 0, H}, {0, D, 0}, "m", "east"),
       // the ceiling around the opening x 1..3, y 1.5..3.5
       rc::rectangle({0, 0, H}, {0, 1.5, 0}, {W, 0, 0}, "m", "ceiling_south"),
       rc::rectangle({0, 3.5, H}, {0, 1.5, 0}, {W, 0, 0}, "m", "ceiling_north"),
       rc::rectangle({0, 1.5, H}, {0, 2, 0}, {1, 0, 0}, "m", "ceiling_west"),
       rc::rectangle({3, 1.5, H}, {0, 2, 0}, {1, 0, 0}, "m", "ceiling_east")};
  Aperture opening;
  opening.polygon = rc::rectangle({1, 1.5, H}, {0, 2, 0}, {2, 0, 0}, "void", "opening");
  scene.apertures.push_back(opening);
  const double a_open = 4;

  // Uniform random points on the surfaces (by area), facing into the box, 1e-7 m off the surface.
  Xoshiro256 rng(2024);
  double a_surf = 0;
  std::vector<double> cumulative;
  for (const Polygon& p : o) cumulative.push_back(a_surf += 0.5 * norm(newell_normal(p.vertices)));  // Newell: twice the area
  const int M = 3000, K = 600, samples = 64, B = 5;
  std::vector<Sensor> surface, leaving;
  for (int m = 0; m < M; ++m) {
    const double u = rng.uniform() * a_surf;
    std::size_t i = 0;
    while (cumulative[i] <= u && i + 1 < cumulative.size()) ++i;
    const auto& v = o[i].vertices;
    const Vec3 n = normalized(newell_normal(v));
    const Vec3 p = v[0] + rng.uniform() * (v[1] - v[0]) + rng.uniform() * (v[3] - v[0]) + 1e-7 * n;
    surface.push_back({p, n});
  }
  for (int k = 0; k < K; ++k) leaving.push_back({{1 + 2 * rng.uniform(), 1.5 + 2 * rng.uniform(), H - 1e-7}, {0, 0, -1}});
  const auto rs = path_trace(scene, surface, options(samples, B, SkyModel::uniform, 0.2, 11));
  const auto rl = path_trace(scene, leaving, options(samples, B, SkyModel::uniform, 0.2, 12));
  // Mean and σ of the mean of bounce-k irradiance (units of L, E_out = π) over sensors.
  const auto flux = [](const std::vector<PathTracedSensor>& r, std::size_t k, double area) {
    double sum = 0, squares = 0;
    for (const PathTracedSensor& s : r) {
      const double e = (k == 0 ? s.sc.value : s.irc_by_bounce[k].value + s.erc_by_bounce[k].value) * std::numbers::pi / 100;
      sum += e, squares += e * e;
    }
    const double n = double(r.size()), mean = sum / n;
    return TracedEstimate{area * mean, area * std::sqrt((squares / n - mean * mean) / (n - 1))};
  };
  const TracedEstimate phi0 = flux(rs, 0, a_surf);
  INFO("Phi_0 = " << phi0.value << " ± " << phi0.standard_error << ", exact " << std::numbers::pi * a_open);
  CHECK(within(phi0, std::numbers::pi * a_open));
  CHECK(phi0.standard_error < 0.03 * phi0.value);
  for (int k = 0; k < B; ++k) {
    const TracedEstimate phi = flux(rs, k, a_surf), next = flux(rs, k + 1, a_surf), out = flux(rl, k + 1, a_open);
    const double residual = rho * phi.value - next.value - out.value;
    const double sigma = rho * phi.standard_error + next.standard_error + out.standard_error;
    INFO("bounce " << k << ": rho Phi_k = " << rho * phi.value << ", Phi_k+1 = " << next.value << ", Lambda_k+1 = " << out.value
                   << ", residual " << residual << " ± " << sigma);
    CHECK(std::abs(residual) < 5 * sigma);
    // The residual's σ stays well below the flux it balances (the check has teeth).
    CHECK(sigma < 0.1 * rho * phi.value);
  }
}

TEST_CASE("path tracer: results do not depend on the thread count, and the seed decides them") {
  const rc::ReflectionCase c = rc::side_lit_room_case();
  const std::vector<Sensor> sensors(c.sensors.begin(), c.sensors.begin() + 12);
  const PathTracerOptions o = options(256, 4, c.sky, c.ground_reflectance, 3);
  const auto many = path_trace(c.scene, sensors, o);
  std::vector<PathTracedSensor> one;
  tbb::task_arena(1).execute([&] { one = path_trace(c.scene, sensors, o); });
  const auto other_seed = path_trace(c.scene, sensors, options(256, 4, c.sky, c.ground_reflectance, 4));
  bool seed_matters = false;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    CHECK(many[i].df.value == one[i].df.value);
    CHECK(many[i].irc.standard_error == one[i].irc.standard_error);
    seed_matters = seed_matters || other_seed[i].irc.value != many[i].irc.value;
  }
  CHECK(seed_matters);
}

TEST_CASE("path tracer: bad options are refused") {
  const rc::ReflectionCase c = rc::canopy_case();
  CHECK_THROWS_AS(path_trace(c.scene, c.sensors, options(0, 2, c.sky)), Error);
  CHECK_THROWS_AS(path_trace(c.scene, c.sensors, options(16, -1, c.sky)), Error);
  CHECK_THROWS_AS(path_trace(c.scene, c.sensors, options(16, 2, c.sky, 1.5)), Error);
}
