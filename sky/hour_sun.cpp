#include "sky/hour_sun.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "geometry/error.hpp"

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

namespace daylit {

namespace {

// Days from 1970-01-01 of a proleptic Gregorian date, and back (the era arithmetic of
// H. Hinnant's "chrono-compatible low-level date algorithms").
long days_from_civil(long y, int m, int d) {
  y -= m <= 2;
  const long era = (y >= 0 ? y : y - 399) / 400;
  const long yoe = y - era * 400;
  const long doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const long doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + doe - 719468;
}

void civil_from_days(long z, int& y, int& m, int& d) {
  z += 719468;
  const long era = (z >= 0 ? z : z - 146096) / 146097;
  const long doe = z - era * 146097;
  const long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const long doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const long mp = (5 * doy + 2) / 153;
  d = int(doy - (153 * mp + 2) / 5 + 1);
  m = int(mp < 10 ? mp + 3 : mp - 9);
  y = int(yoe + era * 400 + (m <= 2));
}

}  // namespace

WeatherHour weather_hour(const WeatherFile& file, const CivilTime& t, double latitude_deg, double longitude_deg,
                         double elevation_m, double pressure_hpa, double temperature_c) {
  const int offset_min = int(std::lround(file.location.time_zone_h * 60));
  // Seconds since 1970 in the file's local standard time.
  const double local = double(days_from_civil(t.year, t.month, t.day)) * 86400 + t.hour * 3600.0 + t.minute * 60.0 +
                       t.second + 60.0 * (offset_min - t.utc_offset_min);
  // The hour (h − 1, h] that holds it: an instant on the hour belongs to the hour it ends.
  const double hours = std::ceil(local / 3600);
  long day = long(std::floor((hours - 1) / 24));
  const int h = int(hours - 24.0 * day);  // 1..24
  WeatherHour w;
  w.hour_ending = h;
  int y, m, d;
  const double in_day = local - double(day) * 86400;
  civil_from_days(day, y, m, d);
  w.local_standard = {y, m, d, int(in_day / 3600), 0, 0, offset_min};
  w.local_standard.minute = int((in_day - 3600.0 * w.local_standard.hour) / 60);
  w.local_standard.second = in_day - 3600.0 * w.local_standard.hour - 60.0 * w.local_standard.minute;
  w.record = find_record(file, m, d, h);
  if (!w.record)
    throw Error(fmt::format("{}: no record for {:02}-{:02} hour {} ({:02}:00–{:02}:00 local standard time, UTC{:+g})", file.path,
                            m, d, h, h - 1, h, file.location.time_zone_h));
  if (!w.record->usable)
    throw Error(fmt::format("{}:{}: the direct normal or diffuse horizontal value of this hour is missing (a missing-value code)",
                            file.path, w.record->line));
  w.sun = file.format == WeatherFormat::epw
              ? sun_for_hour_ending(y, m, d, h, file.location.time_zone_h, latitude_deg, longitude_deg, elevation_m,
                                    pressure_hpa, temperature_c)
              : sun_at_hour(y, m, d, w.record->hour, file.location.time_zone_h, latitude_deg, longitude_deg, elevation_m,
                            pressure_hpa, temperature_c);
  return w;
}

}  // namespace daylit
