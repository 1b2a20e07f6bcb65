#pragma once
// The sun that stands for an hour of weather data.
//
// An EPW record stamped hour h covers the hour (h − 1, h] of local standard time (EnergyPlus,
// Auxiliary Programs: "hour 1 is the period from 00:01 to 01:00"); its values are means over
// that hour. The sun is taken at the middle of the hour, h − 0.5, when it is up for the whole
// hour; in the hour of sunrise or sunset, at the middle of the part of the hour during which it is
// up (the crossing found by bisection on SPA's apparent elevation, to 0.01 s), since only that
// part lit the sky; never, when it is down for the whole hour (checked at both ends and the
// middle: an hour in which the sun rises and sets again, possible only near the poles, is taken
// as up from the first to the last of those times at which it is up).
// A .wea record gives the instant itself (gendaymtx takes the sun at the hour written).

#include "sky/solar_position.hpp"
#include "sky/weather_file.hpp"

namespace daylit {

struct HourSun {
  bool up = false;
  double start_h = 0, end_h = 0;  // the part of the hour the sun is up (local standard decimal hours)
  double up_fraction = 0;         // (end − start) / 1 h
  CivilTime instant;              // when the sun is taken (local standard time, the file's UTC offset)
  SolarPosition position;         // SPA at that instant (refraction for the pressure and temperature given)
};

// `interval_end_h` is the EPW hour h (1–24) of the date year-month-day, local standard time with
// UTC offset time_zone_h; the site's latitude, longitude (east positive) and elevation in metres.
HourSun sun_for_hour_ending(int year, int month, int day, int interval_end_h, double time_zone_h, double latitude_deg,
                            double longitude_deg, double elevation_m, double pressure_hpa = 1013.25,
                            double temperature_c = 10);

// The sun at a decimal local standard hour in [0, 24] (a .wea record's time).
HourSun sun_at_hour(int year, int month, int day, double hour, double time_zone_h, double latitude_deg,
                    double longitude_deg, double elevation_m, double pressure_hpa = 1013.25, double temperature_c = 10);

}  // namespace daylit

namespace daylit {

// The record of a weather file that holds an instant, and its sun.
struct WeatherHour {
  const WeatherRecord* record = nullptr;
  CivilTime local_standard;  // the instant in the file's local standard time
  int hour_ending = 0;       // the hour (h − 1, h] that holds it (1–24)
  HourSun sun;               // the record's sun (EPW: hour-ending convention; .wea: its instant)
};

// The instant t (any UTC offset) in the file's local standard time; the EPW record whose hour
// (h − 1, h] holds it (an instant on the hour belongs to the hour it ends), or the .wea record of
// that month and day whose time lies in that hour; its sun for the site given (latitude, EAST
// longitude, elevation), in the year of t. Throws daylit::Error when the file has no such record,
// or (file:line) when the record's direct or diffuse value is missing.
WeatherHour weather_hour(const WeatherFile& file, const CivilTime& t, double latitude_deg, double longitude_deg,
                         double elevation_m, double pressure_hpa = 1013.25, double temperature_c = 10);

}  // namespace daylit
