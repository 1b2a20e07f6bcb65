#pragma once
// Hourly weather for daylight: EnergyPlus weather files (EPW) and Radiance's .wea (gendaymtx's input).
//
// EPW (EnergyPlus, Auxiliary Programs, "Weather Converter Program", EPW data dictionary): eight
// header lines, the first LOCATION,city,state,country,source,WMO,latitude,longitude,time zone,
// elevation (latitude north positive, longitude EAST positive, time zone in hours of local standard
// time − UTC, elevation in metres); HOLIDAYS/DAYLIGHT SAVINGS's first field says whether the leap
// year is observed; DATA PERIODS gives the records per hour (1 is read here). Then one record per
// hour of 35 comma-separated fields, of which these are read (0-based):
//   0 year, 1 month, 2 day, 3 hour (1–24: the hour ENDING at that time, local standard time),
//   7 dew point (°C, missing ≥ 99.9), 14 direct normal and 15 diffuse horizontal irradiance
//   (Wh/m² over the hour, i.e. mean W/m²; missing ≥ 9999), 17 direct normal and 18 diffuse
//   horizontal illuminance (lux; missing ≥ 999999), 32 albedo (ground reflectance, missing ≥ 999).
// "Missing" is the data dictionary's rule: a value at or above the code is missing.
//
// .wea (Radiance gendaymtx): header lines `place NAME`, `latitude φ` (north positive), `longitude λ`
// (WEST positive), `time_zone M` (the standard meridian in degrees, WEST positive: 90 for UTC−6),
// `site_elevation h`, `weather_data_file_units U` (1: direct normal and diffuse horizontal
// irradiance in W/m²; 3: the same as illuminances in lux; 2, direct horizontal, is refused), then
// lines `month day hour direct diffuse` with the hour a decimal local standard time at which the sun
// is taken (epw2wea writes the EPW hour minus 0.5).
//
// Missing-value policy: a record whose direct normal or diffuse horizontal irradiance (or, for a
// .wea in lux, illuminance) is missing is kept but marked unusable, and counted; a file in which
// more than kMaxMissingShare of the records are unusable is refused. Missing illuminances fall back
// to Perez's luminous efficacies, a missing dew point to 11 °C (gendaymtx's default), a missing
// albedo to none given: each user of the file says which it did. An EPW illuminance of 0 beside
// a positive irradiance is taken as missing too (TMY3's low-sun hours).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace daylit {

inline constexpr double kMaxMissingShare = 0.10;

struct WeatherLocation {
  std::string place;
  double latitude_deg = 0;     // north positive
  double longitude_deg = 0;    // EAST positive (a .wea's west-positive value is turned)
  double time_zone_h = 0;      // local standard time − UTC, hours (−6 for Chicago)
  double elevation_m = 0;      // above sea level, as the file gives it
};

struct WeatherRecord {
  int line = 0;                // 1-based line in the file
  int year = 0;                // EPW only (0 in a .wea)
  int month = 1, day = 1;
  // EPW: the hour ending at this time, 1–24 (the record covers (hour − 1, hour]).
  // .wea: the decimal hour at which the sun is taken, [0, 24).
  double hour = 1;
  std::optional<double> dew_point_c;
  std::optional<double> direct_normal_irradiance;        // W/m²
  std::optional<double> diffuse_horizontal_irradiance;   // W/m²
  std::optional<double> direct_normal_illuminance;       // lux
  std::optional<double> diffuse_horizontal_illuminance;  // lux
  std::optional<double> ground_reflectance;              // albedo, 0..1

  // Whether the sky of this hour can be built: direct normal and diffuse horizontal irradiance
  // (EPW, .wea units 1) or illuminance (.wea units 3) both present.
  bool usable = false;
};

enum class WeatherFormat { epw, wea };

struct WeatherFile {
  std::string path;
  WeatherFormat format = WeatherFormat::epw;
  WeatherLocation location;
  bool photometric = false;            // .wea units 3: direct/diffuse are lux, not W/m²
  std::optional<bool> leap_year_observed;  // EPW header
  std::vector<WeatherRecord> records;
  std::size_t unusable_records = 0;    // missing direct or diffuse (see the policy above)
  std::size_t missing_dew_points = 0, missing_illuminances = 0;  // records lacking either (codes or zeros below)
  // EPW: illuminances of 0 lux beside a positive irradiance, taken as missing (TMY3 writes 0 where
  // its illuminance model was not run).
  std::size_t zero_illuminances_taken_as_missing = 0;
};

// Parse the text of an EPW or .wea file; `name` is used in messages (file:line: problem). Throws
// daylit::Error on anything that cannot be read as the format says: a short or malformed header,
// a record with fewer fields or a field that is not a number, a date that does not exist (a 29
// February in a year that is not leap, or in a file whose header says the leap year is not
// observed), records not one hour apart, a time zone beyond ±14 h, coordinates out of range,
// negative irradiances that are not missing codes, and more than kMaxMissingShare of the records
// unusable.
WeatherFile parse_epw(std::string_view text, const std::string& name);
WeatherFile parse_wea(std::string_view text, const std::string& name);
// By extension: .epw or .wea (any case); anything else is an error.
WeatherFile read_weather_file(const std::string& path);

// The record for an hour given as a local standard date and time (month, day, and hour-ending
// 1–24 for an EPW; for a .wea the record whose hour lies in (hour − 1, hour]). nullptr when absent.
const WeatherRecord* find_record(const WeatherFile& file, int month, int day, int hour_ending);

std::string_view weather_format_name(WeatherFormat format) noexcept;

}  // namespace daylit
