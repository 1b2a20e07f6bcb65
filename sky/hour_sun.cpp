#include "sky/hour_sun.hpp"

#include <algorithm>
#include <cmath>

namespace daylit {

namespace {

struct Where {
  int year, month, day;
  double time_zone_h, latitude_deg, longitude_deg, elevation_m, pressure_hpa, temperature_c;
};

// The civil time of a decimal hour t ∈ [0, 24] of the day (24 is 24:00:00, the day's end).
CivilTime civil(const Where& w, double t) {
  CivilTime c;
  c.year = w.year;
  c.month = w.month;
  c.day = w.day;
  c.utc_offset_min = int(std::lround(w.time_zone_h * 60));
  const double seconds = std::clamp(t, 0.0, 24.0) * 3600;
  c.hour = int(seconds / 3600);
  c.minute = int((seconds - 3600.0 * c.hour) / 60);
  c.second = seconds - 3600.0 * c.hour - 60.0 * c.minute;
  if (c.hour == 24) c.minute = 0, c.second = 0;
  if (c.second >= 60) c.second = 59.999999;  // rounding at a minute's end
  return c;
}

SolarPosition sun_at(const Where& w, double t) {
  SolarPositionInput in;
  in.time = civil(w, t);
  in.latitude_deg = w.latitude_deg;
  in.longitude_deg = w.longitude_deg;
  in.elevation_m = w.elevation_m;
  in.pressure_hpa = w.pressure_hpa;
  in.temperature_c = w.temperature_c;
  return solar_position(in);
}

bool up(const SolarPosition& p) { return p.elevation_deg > 0; }

// The time in [lo, hi] at which the sun crosses the horizon, `up_at_lo` saying on which side lo is.
double crossing(const Where& w, double lo, double hi, bool up_at_lo) {
  while (hi - lo > 0.01 / 3600) {
    const double mid = 0.5 * (lo + hi);
    if (up(sun_at(w, mid)) == up_at_lo) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

HourSun at(const Where& w, double t, double start, double end) {
  HourSun s;
  s.up = true;
  s.start_h = start;
  s.end_h = end;
  s.up_fraction = end - start;
  s.instant = civil(w, t);
  s.position = sun_at(w, t);
  return s;
}

}  // namespace

HourSun sun_for_hour_ending(int year, int month, int day, int h, double time_zone_h, double latitude_deg,
                            double longitude_deg, double elevation_m, double pressure_hpa, double temperature_c) {
  const Where w{year, month, day, time_zone_h, latitude_deg, longitude_deg, elevation_m, pressure_hpa, temperature_c};
  const double t0 = h - 1, t1 = h, tm = h - 0.5;
  const bool u0 = up(sun_at(w, t0)), u1 = up(sun_at(w, t1)), um = up(sun_at(w, tm));
  if (u0 && u1) return at(w, tm, t0, t1);
  if (!u0 && !u1 && !um) {
    HourSun s;
    s.start_h = s.end_h = tm;
    s.instant = civil(w, tm);
    s.position = sun_at(w, tm);
    return s;
  }
  // Sunrise (down at the start), sunset (down at the end), or both: the part that is up.
  double start = t0, end = t1;
  if (!u0) start = crossing(w, t0, um ? tm : t1, false);
  if (!u1) end = crossing(w, um ? tm : t0, t1, true);
  if (!(end > start)) end = start;
  return at(w, 0.5 * (start + end), start, end);
}

HourSun sun_at_hour(int year, int month, int day, double hour, double time_zone_h, double latitude_deg,
                    double longitude_deg, double elevation_m, double pressure_hpa, double temperature_c) {
  const Where w{year, month, day, time_zone_h, latitude_deg, longitude_deg, elevation_m, pressure_hpa, temperature_c};
  HourSun s = at(w, hour, hour, hour);
  s.up = up(s.position);
  s.up_fraction = 0;
  return s;
}

}  // namespace daylit
