// The annual run (simulation/annual.hpp, annual_metrics.hpp): the metrics' arithmetic on hourly
// series made by hand, the LM-83 blinds rule on a two-group room where the 2 % rule is enumerated
// by rays, ASE of a simple room against a brute-force count (a ray to the true sun of every hour
// against the window rectangle), and the .npy header NumPy expects.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <numbers>

#include "test_scenes.hpp"
#include "report/npy_writer.hpp"
#include "simulation/annual.hpp"
#include "simulation/annual_metrics.hpp"
#include "simulation/illuminance.hpp"
#include "sky/hour_sun.hpp"

using namespace daylit;

namespace {

// Whether the ray p + t u (t > 0) crosses the axis-aligned rectangle in the plane y = y0 with
// x ∈ [x0, x1], z ∈ [z0, z1]: the brute force the exact path is checked against.
bool ray_through_y_rectangle(const Vec3& p, const Vec3& u, double y0, double x0, double x1, double z0, double z1) {
  if (u.y == 0) return false;
  const double t = (y0 - p.y) / u.y;
  if (!(t > 0)) return false;
  const double x = p.x + t * u.x, z = p.z + t * u.z;
  return x > x0 && x < x1 && z > z0 && z < z1;
}

// The direct sun (lux) at p (normal n) through that rectangle by rays: the ray to the sun's centre
// where the centre is farther than 1.5 disk radii (in angle, a safe margin) from every edge, then
// E_dn (n·s) or 0; else 200 × 200 rays over the disk (midpoints of equal-area polar cells, uniform
// in solid angle to O(ρ²)), E_dn times the mean of (n·u) over the rays that pass.
double sun_lux_by_rays(const Vec3& p, const Vec3& n, const Vec3& s, double E_dn, double x0, double x1, double z0, double z1) {
  const double rho = kSunHalfAngleDeg * std::numbers::pi / 180;
  if (s.y >= 0) return 0;
  const double t = -p.y / s.y;
  const double x = p.x + t * s.x, z = p.z + t * s.z;
  const double margin = std::min({std::abs(x - x0), std::abs(x - x1), std::abs(z - z0), std::abs(z - z1)}) / (t * norm(s));
  if (margin > 1.5 * rho / std::abs(normalized(s).y))  // the plane y = 0 foreshortens angles by at most 1/|s_y|
    return ray_through_y_rectangle(p, s, 0, x0, x1, z0, z1) ? E_dn * dot(n, s) : 0.0;
  const Vec3 e1 = normalized(cross(s, std::abs(s.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0})), e2 = cross(s, e1);
  constexpr int kRings = 200, kSpokes = 200;
  double sum = 0;
  for (int i = 0; i < kRings; ++i) {
    const double r = rho * std::sqrt((i + 0.5) / kRings);
    for (int j = 0; j < kSpokes; ++j) {
      const double phi = 2 * std::numbers::pi * (j + 0.5) / kSpokes;
      const Vec3 u = normalized(s + (r * std::cos(phi)) * e1 + (r * std::sin(phi)) * e2);
      if (ray_through_y_rectangle(p, u, 0, x0, x1, z0, z1)) sum += dot(n, u);
    }
  }
  return E_dn * sum / (kRings * kSpokes);
}

// One Perez sky for every hour below: the tests here are about the sun, the blinds and the
// arithmetic, and the diffuse part only has to be the same path as in a run.
PerezSky test_sky() {
  PerezConditionInput in;
  in.diffuse_horizontal_irradiance = 100;
  in.direct_normal_irradiance = 600;
  in.sun_zenith_deg = 40;
  return PerezSky(perez_condition(in, PerezClamps::radiance), normalized(Vec3{0, -1, 1.2}), PerezClamps::radiance);
}

}  // namespace

TEST_CASE("the annual metrics follow their definitions on hourly series made by hand") {
  // Two sensors, ten hours; hours 0–7 occupied, hours 2–9 daylight hours.
  const std::size_t hours = 10;
  const std::vector<bool> occupied{true, true, true, true, true, true, true, true, false, false};
  const std::vector<bool> daylight{false, false, true, true, true, true, true, true, true, true};
  // Sensor 0: 50, 150, 300, 2999, 3000, 3001, 0, 600 | 800, 800.  Sensor 1: all 400 lx.
  const std::vector<float> lux{50, 150, 300, 2999, 3000, 3001, 0, 600, 800, 800, 400, 400, 400, 400, 400, 400, 400, 400, 400, 400};
  // Direct sun: sensor 0 gets ≥ 1000 lx in occupied hours 3, 4 (1000 exactly counts) and 8 (unoccupied).
  std::vector<float> sun(20, 0.0f);
  sun[3] = 1200;
  sun[4] = 1000;
  sun[5] = 999;
  sun[8] = 5000;
  const auto m = sensor_metrics(lux, sun, 2, hours, occupied, daylight);
  CHECK(m[0].direct_sun_hours == 2);
  CHECK(m[1].direct_sun_hours == 0);
  // DA300: hours ≥ 300 among the 8 occupied: 300, 2999, 3000, 3001, 600 → 5/8.
  CHECK(m[0].da_300_percent == Approx(62.5));
  // cDA: (50 + 150)/300 + 5 full hours + 0 → (2/3 + 5)/8.
  CHECK(m[0].cda_300_percent == Approx(100 * (200.0 / 300 + 5) / 8));
  // UDI: < 100: 50, 0 → 2; [100, 300): 150 → 1; [300, 3000]: 300, 2999, 3000, 600 → 4; > 3000: 1.
  CHECK(m[0].udi_fell_short_percent == Approx(25));
  CHECK(m[0].udi_supplementary_percent == Approx(12.5));
  CHECK(m[0].udi_autonomous_percent == Approx(50));
  CHECK(m[0].udi_exceeded_percent == Approx(12.5));
  CHECK(m[1].da_300_percent == Approx(100));
  CHECK(m[1].udi_autonomous_percent == Approx(100));
  // EN 17037 per sensor over the 8 daylight hours: sensor 0 is 300, 2999, 3000, 3001, 0, 600, 800, 800.
  CHECK(m[0].en17037_hours_at_300_percent == Approx(87.5));
  CHECK(m[0].en17037_hours_at_750_percent == Approx(62.5));
  CHECK(m[1].en17037_hours_at_300_percent == Approx(100));
  CHECK(m[1].en17037_hours_at_500_percent == Approx(0));

  const GridMetrics g = grid_metrics(lux, m, hours, occupied, daylight);
  CHECK(g.occupied_hours == 8);
  CHECK(g.daylight_hours == 8);
  CHECK(g.sda_300_50_percent == Approx(100));  // both sensors have DA300 ≥ 50 %
  CHECK(g.ase_1000_250_percent == Approx(0));
  CHECK(g.leed_sda_points == 3);
  // EN 17037 minimum level (300 over 50 %, 100 over 95 %), hour by hour over the daylight hours:
  // with two sensors, "≥ 50 %" needs one and "≥ 95 %" needs both. Target met in every daylight
  // hour (sensor 1 has 400); minimum (both ≥ 100) fails only in hour 6 (sensor 0 has 0): 7/8.
  REQUIRE(g.en17037.size() == 3);
  CHECK(g.en17037[0].name == "minimum");
  CHECK(g.en17037[0].hours_target_met_percent == Approx(100));
  CHECK(g.en17037[0].hours_minimum_met_percent == Approx(87.5));
  CHECK(g.en17037[0].pass);
  // Medium (500 over 50 %, 300 over 95 %): target needs sensor 0 ≥ 500: 2999, 3000, 3001, 600, 800,
  // 800 → 6/8; minimum needs both ≥ 300: the same six plus hour 2 (300) → 7/8.
  CHECK(g.en17037[1].hours_target_met_percent == Approx(75));
  CHECK(g.en17037[1].hours_minimum_met_percent == Approx(87.5));
  CHECK(g.en17037[1].pass);
  // High (750 over 50 %, 500 over 95 %): target: sensor 0 ≥ 750 → 5/8; minimum: both ≥ 500 fails
  // always (sensor 1 has 400) → 0.
  CHECK(g.en17037[2].hours_target_met_percent == Approx(62.5));
  CHECK(g.en17037[2].hours_minimum_met_percent == Approx(0));
  CHECK_FALSE(g.en17037[2].pass);
  // The per-sensor variant of the medium level: sensors reaching 500 in ≥ 50 % of the hours:
  // sensor 0 (6/8), not sensor 1 → 50 %; reaching 300: both → 100 %: passes.
  CHECK(g.en17037[1].sensors_target_percent == Approx(50));
  CHECK(g.en17037[1].sensors_minimum_percent == Approx(100));
  CHECK(g.en17037[1].pass_per_sensor);

  // LEED points at the thresholds, and ASE just above 250 hours.
  std::vector<SensorMetrics> s(20);
  for (std::size_t i = 0; i < 20; ++i) s[i].da_300_percent = i < 11 ? 50 : 49.99;  // 11/20 = 55 %
  s[0].direct_sun_hours = 251;
  s[1].direct_sun_hours = 250;
  const std::vector<float> none(20 * 1, 0.0f);
  const GridMetrics l = grid_metrics(none, s, 1, {true}, {true});
  CHECK(l.sda_300_50_percent == Approx(55));
  CHECK(l.leed_sda_points == 2);
  CHECK(l.ase_1000_250_percent == Approx(5));  // only the sensor with 251 h (more than 250)
  CHECK(l.leed_ase_at_most_10_percent);
}

TEST_CASE("EN 17037's daylight hours are the 4380 of highest sun") {
  std::vector<double> altitude;
  for (int i = 0; i < 8760; ++i) altitude.push_back(std::sin(i * 0.001) * 60 - (i % 3));
  const std::vector<bool> day = en17037_daylight_hours(altitude);
  CHECK(std::count(day.begin(), day.end(), true) == 4380);
  double lowest_in = 1e9, highest_out = -1e9;
  for (std::size_t i = 0; i < altitude.size(); ++i)
    (day[i] ? lowest_in : highest_out) = day[i] ? std::min(lowest_in, altitude[i]) : std::max(highest_out, altitude[i]);
  CHECK(lowest_in >= highest_out);
}

TEST_CASE("the LM-83 blinds rule closes a group when more than 2 % of the sensors get 1000 lx of its sun") {
  // The rule itself, on sun values given by hand: 100 sensors, two groups.
  std::vector<float> sun(200, 0.0f);
  for (int i = 0; i < 2; ++i) sun[std::size_t(i) * 2 + 0] = 1000;   // group 0: 2 sensors (= 2 %): stays open
  for (int i = 0; i < 3; ++i) sun[std::size_t(i) * 2 + 1] = 5000;   // group 1: 3 sensors (> 2 %): closes
  sun[10 * 2 + 0] = 999.9f;                                          // just below: does not count
  auto closed = blinds_rule(sun, 100, 2, 1000, 0.02);
  CHECK(closed == std::vector<std::uint8_t>{0, 1});
  sun[10 * 2 + 0] = 1000;                                            // now 3 in group 0 as well
  closed = blinds_rule(sun, 100, 2, 1000, 0.02);
  CHECK(closed == std::vector<std::uint8_t>{1, 1});

  // A room with two windows in the wall y = 0 (the room at y > 0), each its own group ("east" and
  // "west" glass names), 10 × 10 sensors on the floor, and a few suns: the sensors a group lights
  // with ≥ 1000 lx are enumerated by rays through its rectangle (sun_lux_by_rays), and the group
  // must close exactly when more than 2 of the 100 are.
  Scene scene;
  Aperture west{test::polygon({{0.5, 0, 0.8}, {1.5, 0, 0.8}, {1.5, 0, 2.0}, {0.5, 0, 2.0}}), 1.0};
  west.polygon.material = "west";
  Aperture east{test::polygon({{3.5, 0, 0.8}, {4.5, 0, 0.8}, {4.5, 0, 2.0}, {3.5, 0, 2.0}}), 1.0};
  east.polygon.material = "east";
  scene.apertures = {west, east};
  SensorGrid grid;
  grid.name = "floor";
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) grid.sensors.push_back({{0.25 + 0.5 * i, 0.25 + 0.5 * j, 0.0}, {0, 0, 1}});
  const VisibilityEngine engine(scene, GeometryMode::exact);
  const PerezSky sky = test_sky();
  AnnualOptions options;
  options.degree = 8;
  AnnualSky year;
  const std::vector<Vec3> suns{normalized(Vec3{0.3, -1, 0.45}), normalized(Vec3{-0.5, -1, 0.3}), normalized(Vec3{0.05, -1, 1.5}),
                               normalized(Vec3{0.8, -1, 0.25})};
  for (const Vec3& s : suns) {
    AnnualHour h = annual_hour(sky, s, 10000, 8000 / std::max(0.05, s.z), options);
    h.occupied = true;
    year.hours.push_back(std::move(h));
  }
  const AnnualGridResult r = annual_grid(engine, scene, grid, year, options);
  REQUIRE(r.groups == 2);
  const WindowGroups groups = window_groups(scene);
  for (std::size_t h = 0; h < suns.size(); ++h) {
    const Vec3& s = suns[h];
    const double E = year.hours[h].direct_normal_lux * s.z;
    REQUIRE(E >= 5000);
    for (std::size_t g = 0; g < 2; ++g) {
      const double x0 = groups.names[g] == "west" ? 0.5 : 3.5;
      std::size_t lit = 0;
      for (const Sensor& sensor : grid.sensors)
        lit += sun_lux_by_rays(sensor.position, sensor.normal, s, year.hours[h].direct_normal_lux, x0, x0 + 1, 0.8, 2.0) >= 1000;
      INFO("hour " << h << ", group " << groups.names[g] << ": " << lit << " sensors lit");
      CHECK(bool(r.blinds_closed[h * 2 + g]) == (lit > 2));
    }
  }
  // The suns were chosen so that both outcomes occur (else the rule would not be tested).
  const auto closed_count = std::count(r.blinds_closed.begin(), r.blinds_closed.end(), std::uint8_t(1));
  CHECK(closed_count > 0);
  CHECK(closed_count < std::ptrdiff_t(r.blinds_closed.size()));
}

TEST_CASE("ASE of a simple room equals a brute-force count of rays to the true sun of every hour") {
  // A south-facing window (y = 0, the room at y > 0; +y north, so the window looks south) in
  // Chicago (41.98° N, 87.92° W, UTC−6), every hour of 2025; 5 × 4 sensors at desk height.
  const double lat = 41.98, lon = -87.92, tz = -6;
  const Site site = Site::geographic(lat, lon, 201, 0);
  Scene scene;
  scene.apertures.push_back({test::polygon({{0.5, 0, 0.9}, {3.5, 0, 0.9}, {3.5, 0, 2.2}, {0.5, 0, 2.2}}), 1.0});
  SensorGrid grid;
  grid.name = "room";
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 4; ++j) grid.sensors.push_back({{0.4 + 0.8 * i, 0.5 + 1.1 * j, 0.8}, {0, 0, 1}});
  const VisibilityEngine engine(scene, GeometryMode::exact);
  const PerezSky sky = test_sky();
  AnnualOptions options;
  options.degree = 4;
  options.circumsolar_tolerance = 1e-3;  // the sky does not enter ASE; keep its cubature short
  AnnualSky year;
  std::vector<bool> occupied;
  const int days[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  for (int month = 1; month <= 12; ++month)
    for (int day = 1; day <= days[month - 1]; ++day)
      for (int h = 9; h <= 18; ++h) {  // only the occupied hours count for ASE
        const HourSun sun = sun_for_hour_ending(2025, month, day, h, tz, lat, lon, 201);
        if (!sun.up) continue;
        const Vec3 s = site.model_direction(sun.position.azimuth_deg, 90 - sun.position.zenith_deg);
        // E_dn such that E_dn (n·s) = 2000 lx: a fully seen disk gives twice the threshold, so
        // only a disk about half hidden is near it; there the brute force counts rays over the disk.
        AnnualHour hour = annual_hour(sky, s, 10000, 2000 / s.z, options);
        hour.occupied = true;
        year.hours.push_back(std::move(hour));
        occupied.push_back(true);
      }
  const AnnualGridResult r = annual_grid(engine, scene, grid, year, options);
  const auto metrics = sensor_metrics(r.illuminance, r.direct_sun, r.sensors, r.hours, occupied, occupied);
  std::size_t differing = 0, total = 0;
  for (std::size_t i = 0; i < grid.sensors.size(); ++i) {
    int brute = 0;
    for (const AnnualHour& hour : year.hours)
      brute += sun_lux_by_rays(grid.sensors[i].position, grid.sensors[i].normal, hour.sun, hour.direct_normal_lux, 0.5, 3.5,
                               0.9, 2.2) >= 1000;
    INFO("sensor " << i << ": exact " << metrics[i].direct_sun_hours << " h, rays " << brute << " h");
    CHECK(metrics[i].direct_sun_hours == brute);
    differing += metrics[i].direct_sun_hours != brute;
    total += std::size_t(brute);
  }
  CHECK(total > 0);  // the window does see the sun
  CHECK(differing == 0);
}

TEST_CASE("the .npy header is what NumPy's format 1.0 reads") {
  const std::string h = cli::npy_header_float32(2400, 8760);
  REQUIRE(h.size() % 64 == 0);
  CHECK(std::memcmp(h.data(), "\x93NUMPY", 6) == 0);
  CHECK(h[6] == 1);
  CHECK(h[7] == 0);
  const std::size_t length = std::size_t((unsigned char)h[8]) | (std::size_t((unsigned char)h[9]) << 8);
  CHECK(length == h.size() - 10);
  const std::string dict = h.substr(10);
  CHECK(dict.back() == '\n');
  CHECK(dict.rfind("{'descr': '<f4', 'fortran_order': False, 'shape': (2400, 8760), }", 0) == 0);
  CHECK(dict.find_first_not_of(' ', dict.find('}') + 1) == dict.size() - 1);  // only spaces, then '\n'
}

TEST_CASE("Reinhart patch centres: Tregenza's rows at MF 1, split rows at MF 4, the cap") {
  // MF 1: rows of 12°; (azimuth 5°, altitude 40°) lies in row 3 (36°–48°) of 24 patches of 15°,
  // patch round(5/15) = 0 → centre (0°, 42°); (100°, 40°) → patch round(100/15) = 7 → (105°, 42°).
  auto c = reinhart_patch_centre(5, 40, 1);
  CHECK(c.azimuth_deg == Approx(0));
  CHECK(c.altitude_deg == Approx(42));
  c = reinhart_patch_centre(100, 40, 1);
  CHECK(c.azimuth_deg == Approx(105));
  CHECK(c.altitude_deg == Approx(42));
  c = reinhart_patch_centre(100, 3, 1);
  CHECK(c.altitude_deg == Approx(6));
  CHECK(c.azimuth_deg == Approx(96));  // 30 patches of 12°: round(100/12) = 8
  // The cap above 84° at MF 1, above 90 − 90/(2·28.5) = 88.42° at MF 4.
  CHECK(reinhart_patch_centre(200, 85, 1).altitude_deg == 90);
  CHECK(reinhart_patch_centre(200, 88.5, 4).altitude_deg == 90);
  CHECK(reinhart_patch_centre(200, 88.3, 4).altitude_deg == Approx(27.5 * 90 / 28.5));
  // MF 4: rows of 90/28.5 = 3.158°; row 0 has 120 patches of 3°.
  c = reinhart_patch_centre(10.4, 1, 4);
  CHECK(c.altitude_deg == Approx(90 / 28.5 / 2));
  CHECK(c.azimuth_deg == Approx(9));
  // The centre's patch is itself (a fixed point) at every MF.
  for (int mf = 1; mf <= 6; ++mf)
    for (double alt : {1.0, 20.0, 55.0, 80.0})
      for (double az : {0.0, 91.0, 359.0}) {
        const auto a = reinhart_patch_centre(az, alt, mf);
        const auto b = reinhart_patch_centre(a.azimuth_deg, a.altitude_deg, mf);
        CHECK(b.azimuth_deg == Approx(a.azimuth_deg));
        CHECK(b.altitude_deg == Approx(a.altitude_deg));
      }
}
