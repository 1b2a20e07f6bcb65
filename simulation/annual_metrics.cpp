#include "simulation/annual_metrics.hpp"

#include <algorithm>
#include <numeric>

namespace daylit {

namespace {

constexpr double kEnTargets[4] = {100, 300, 500, 750};

double percent(std::size_t part, std::size_t whole) { return whole ? 100.0 * double(part) / double(whole) : 0.0; }

}  // namespace

std::vector<SensorMetrics> sensor_metrics(const std::vector<float>& illuminance, const std::vector<float>& direct_sun,
                                          std::size_t sensors, std::size_t hours, const std::vector<bool>& occupied,
                                          const std::vector<bool>& daylight) {
  std::vector<SensorMetrics> out(sensors);
  const std::size_t occ = std::size_t(std::count(occupied.begin(), occupied.end(), true));
  const std::size_t day = std::size_t(std::count(daylight.begin(), daylight.end(), true));
  for (std::size_t i = 0; i < sensors; ++i) {
    SensorMetrics& m = out[i];
    std::size_t da = 0, short_ = 0, supp = 0, auto_ = 0, exceeded = 0;
    std::size_t en[4] = {0, 0, 0, 0};
    double cda = 0;
    for (std::size_t h = 0; h < hours; ++h) {
      const double e = illuminance[i * hours + h];
      if (occupied[h]) {
        m.direct_sun_hours += direct_sun[i * hours + h] >= 1000;
        da += e >= 300;
        cda += std::min(1.0, e / 300);
        if (e < 100) ++short_;
        else if (e < 300) ++supp;
        else if (e <= 3000) ++auto_;
        else ++exceeded;
      }
      if (daylight[h])
        for (int t = 0; t < 4; ++t) en[t] += e >= kEnTargets[t];
    }
    m.da_300_percent = percent(da, occ);
    m.cda_300_percent = occ ? 100 * cda / double(occ) : 0;
    m.udi_fell_short_percent = percent(short_, occ);
    m.udi_supplementary_percent = percent(supp, occ);
    m.udi_autonomous_percent = percent(auto_, occ);
    m.udi_exceeded_percent = percent(exceeded, occ);
    m.en17037_hours_at_100_percent = percent(en[0], day);
    m.en17037_hours_at_300_percent = percent(en[1], day);
    m.en17037_hours_at_500_percent = percent(en[2], day);
    m.en17037_hours_at_750_percent = percent(en[3], day);
  }
  return out;
}

GridMetrics grid_metrics(const std::vector<float>& illuminance, const std::vector<SensorMetrics>& sensors,
                         std::size_t hours, const std::vector<bool>& occupied, const std::vector<bool>& daylight) {
  GridMetrics g;
  const std::size_t n = sensors.size();
  g.occupied_hours = std::size_t(std::count(occupied.begin(), occupied.end(), true));
  g.daylight_hours = std::size_t(std::count(daylight.begin(), daylight.end(), true));
  std::size_t sda = 0, ase = 0;
  for (const SensorMetrics& m : sensors) {
    sda += m.da_300_percent >= 50;
    ase += m.direct_sun_hours > 250;
    g.mean_da_300_percent += m.da_300_percent / double(n);
    g.mean_udi_autonomous_percent += m.udi_autonomous_percent / double(n);
  }
  g.sda_300_50_percent = percent(sda, n);
  g.ase_1000_250_percent = percent(ase, n);
  g.leed_sda_points = g.sda_300_50_percent >= 75 ? 3 : g.sda_300_50_percent >= 55 ? 2 : g.sda_300_50_percent >= 40 ? 1 : 0;
  g.leed_ase_at_most_10_percent = g.ase_1000_250_percent <= 10;
  // EN 17037 Table A.1: (target, minimum target) = (300, 100), (500, 300), (750, 500) lx.
  const struct {
    const char* name;
    int target, minimum;
  } levels[3] = {{"minimum", 1, 0}, {"medium", 2, 1}, {"high", 3, 2}};
  for (const auto& level : levels) {
    En17037IlluminanceLevel l;
    l.name = level.name;
    l.target_lux = kEnTargets[level.target];
    l.minimum_target_lux = kEnTargets[level.minimum];
    std::size_t target_hours = 0, minimum_hours = 0;
    for (std::size_t h = 0; h < hours; ++h) {
      if (!daylight[h]) continue;
      std::size_t at_target = 0, at_minimum = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const double e = illuminance[i * hours + h];
        at_target += e >= l.target_lux;
        at_minimum += e >= l.minimum_target_lux;
      }
      target_hours += double(at_target) >= 0.5 * double(n);
      minimum_hours += double(at_minimum) >= 0.95 * double(n);
    }
    l.hours_target_met_percent = percent(target_hours, g.daylight_hours);
    l.hours_minimum_met_percent = percent(minimum_hours, g.daylight_hours);
    l.pass = l.hours_target_met_percent >= 50 && l.hours_minimum_met_percent >= 50;
    const auto share_of = [&](int t) {
      std::size_t count = 0;
      for (const SensorMetrics& m : sensors) {
        const double v[4] = {m.en17037_hours_at_100_percent, m.en17037_hours_at_300_percent,
                             m.en17037_hours_at_500_percent, m.en17037_hours_at_750_percent};
        count += v[t] >= 50;
      }
      return percent(count, n);
    };
    l.sensors_target_percent = share_of(level.target);
    l.sensors_minimum_percent = share_of(level.minimum);
    l.pass_per_sensor = l.sensors_target_percent >= 50 && l.sensors_minimum_percent >= 95;
    g.en17037.push_back(l);
  }
  return g;
}

std::vector<bool> en17037_daylight_hours(const std::vector<double>& sun_altitude_deg, std::size_t count) {
  std::vector<std::size_t> order(sun_altitude_deg.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return sun_altitude_deg[a] > sun_altitude_deg[b]; });
  std::vector<bool> out(sun_altitude_deg.size(), false);
  for (std::size_t k = 0; k < std::min(count, order.size()); ++k) out[order[k]] = true;
  return out;
}

}  // namespace daylit
