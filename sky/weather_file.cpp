#include "sky/weather_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "geometry/error.hpp"

namespace daylit {

namespace {

// The text's lines, each without its end-of-line ("\n" or "\r\n").
std::vector<std::string_view> split_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = end + 1;
  }
  return lines;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split(std::string_view line, char separator) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = line.find(separator, start);
    fields.push_back(line.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return fields;
}

std::vector<std::string_view> split_whitespace(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) fields.push_back(line.substr(start, i - start));
  }
  return fields;
}

// A finite number filling the whole field, or an error naming the field.
double number(std::string_view field, const SourceLocation& where, std::string_view what) {
  const std::string_view s = trim(field);
  double value = 0;
  const char* first = s.data();
  if (!s.empty() && s.front() == '+') ++first;
  const auto [end, error] = std::from_chars(first, s.data() + s.size(), value);
  if (s.empty() || error != std::errc() || end != s.data() + s.size() || !std::isfinite(value))
    throw input_error(where, fmt::format("{} is '{}', not a number", what, s));
  return value;
}

int integer(std::string_view field, const SourceLocation& where, std::string_view what) {
  const double v = number(field, where, what);
  if (v != std::floor(v) || std::abs(v) > 1e9) throw input_error(where, fmt::format("{} is '{}', not an integer", what, trim(field)));
  return int(v);
}

bool is_leap(int year) noexcept { return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0; }

int days_in_month(int month, bool leap) noexcept {
  constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return month == 2 && leap ? 29 : kDays[month - 1];
}

void check_location(const WeatherLocation& l, const SourceLocation& where) {
  if (!(l.latitude_deg >= -90 && l.latitude_deg <= 90))
    throw input_error(where, fmt::format("latitude {:g}° is outside [−90°, 90°]", l.latitude_deg));
  if (!(l.longitude_deg >= -180 && l.longitude_deg <= 180))
    throw input_error(where, fmt::format("longitude {:g}° is outside [−180°, 180°]", l.longitude_deg));
  if (!(std::abs(l.time_zone_h) <= 14))
    throw input_error(where, fmt::format("time zone {:g} h is beyond ±14 h of UTC", l.time_zone_h));
  if (!(l.elevation_m > -1000 && l.elevation_m < 10000))
    throw input_error(where, fmt::format("elevation {:g} m is outside (−1000 m, 10000 m)", l.elevation_m));
}

// A value, or nothing where it is at or above the field's missing code (EPW data dictionary:
// "if values in this field are >= the following number, it is considered missing").
std::optional<double> unless_missing(double value, double missing_code) {
  if (value >= missing_code) return std::nullopt;
  return value;
}

void check_share(const WeatherFile& f) {
  if (f.records.empty()) throw Error(f.path + ": no hourly records");
  const double share = double(f.unusable_records) / double(f.records.size());
  if (share > kMaxMissingShare)
    throw Error(fmt::format("{}: {} of {} records ({:.1f} %) lack the direct normal or diffuse horizontal value (missing "
                            "codes); more than {:g} % is refused",
                            f.path, f.unusable_records, f.records.size(), 100 * share, 100 * kMaxMissingShare));
}

}  // namespace

std::string_view weather_format_name(WeatherFormat format) noexcept { return format == WeatherFormat::epw ? "epw" : "wea"; }

WeatherFile parse_epw(std::string_view text, const std::string& name) {
  WeatherFile f;
  f.path = name;
  f.format = WeatherFormat::epw;
  const std::vector<std::string_view> lines = split_lines(text);
  // The eight header lines, each named by its first field.
  constexpr std::string_view kHeaders[8] = {"LOCATION", "DESIGN CONDITIONS", "TYPICAL/EXTREME PERIODS", "GROUND TEMPERATURES",
                                            "HOLIDAYS/DAYLIGHT SAVINGS", "COMMENTS 1", "COMMENTS 2", "DATA PERIODS"};
  for (int i = 0; i < 8; ++i) {
    const SourceLocation where{name, i + 1};
    if (std::size_t(i) >= lines.size()) throw input_error(where, fmt::format("the header ends before its {} line", kHeaders[i]));
    const std::string_view head = trim(split(lines[i], ',').front());
    if (head != kHeaders[i])
      throw input_error(where, fmt::format("expected the header line {}, found '{}'", kHeaders[i], head.substr(0, 40)));
  }
  {
    const SourceLocation where{name, 1};
    const auto l = split(lines[0], ',');
    if (l.size() < 10) throw input_error(where, fmt::format("LOCATION has {} fields, 10 expected", l.size()));
    f.location.place = std::string(trim(l[1]));
    if (!trim(l[2]).empty()) f.location.place += ", " + std::string(trim(l[2]));
    if (!trim(l[3]).empty()) f.location.place += ", " + std::string(trim(l[3]));
    f.location.latitude_deg = number(l[6], where, "latitude (field 7)");
    f.location.longitude_deg = number(l[7], where, "longitude (field 8)");
    f.location.time_zone_h = number(l[8], where, "time zone (field 9)");
    f.location.elevation_m = number(l[9], where, "elevation (field 10)");
    check_location(f.location, where);
  }
  {
    const SourceLocation where{name, 5};
    const auto h = split(lines[4], ',');
    if (h.size() < 2) throw input_error(where, "HOLIDAYS/DAYLIGHT SAVINGS lacks its leap-year field");
    std::string flag(trim(h[1]));
    std::transform(flag.begin(), flag.end(), flag.begin(), [](unsigned char c) { return char(std::toupper(c)); });
    if (flag == "YES" || flag == "Y") f.leap_year_observed = true;
    else if (flag == "NO" || flag == "N") f.leap_year_observed = false;
    else throw input_error(where, "the leap-year field is '" + flag + "', not Yes or No");
  }
  {
    const SourceLocation where{name, 8};
    const auto d = split(lines[7], ',');
    if (d.size() < 3) throw input_error(where, "DATA PERIODS lacks the number of records per hour");
    const int per_hour = integer(d[2], where, "records per hour (field 3)");
    if (per_hour != 1)
      throw input_error(where, fmt::format("{} records per hour: only hourly files (1) are read", per_hour));
  }
  const WeatherRecord* previous = nullptr;
  for (std::size_t i = 8; i < lines.size(); ++i) {
    const SourceLocation where{name, int(i) + 1};
    if (trim(lines[i]).empty()) {
      // Blank lines are allowed at the end only.
      if (std::all_of(lines.begin() + std::ptrdiff_t(i), lines.end(), [](std::string_view l) { return trim(l).empty(); })) break;
      throw input_error(where, "blank line between records");
    }
    const auto v = split(lines[i], ',');
    if (v.size() < 33) throw input_error(where, fmt::format("{} fields, at least 33 expected (35 in EPW)", v.size()));
    WeatherRecord r;
    r.line = where.line;
    r.year = integer(v[0], where, "year (field 1)");
    r.month = integer(v[1], where, "month (field 2)");
    r.day = integer(v[2], where, "day (field 3)");
    const int hour = integer(v[3], where, "hour (field 4)");
    r.hour = hour;
    if (r.month < 1 || r.month > 12) throw input_error(where, fmt::format("month {} is not 1–12", r.month));
    if (hour < 1 || hour > 24) throw input_error(where, fmt::format("hour {} is not 1–24 (EPW hours end at their time stamp)", hour));
    if (r.day < 1 || r.day > days_in_month(r.month, true))
      throw input_error(where, fmt::format("day {} does not exist in month {}", r.day, r.month));
    if (r.month == 2 && r.day == 29) {
      if (!is_leap(r.year)) throw input_error(where, fmt::format("29 February {} does not exist ({} is not a leap year)", r.year, r.year));
      if (f.leap_year_observed == false)
        throw input_error(where, "a 29 February record, but the header (HOLIDAYS/DAYLIGHT SAVINGS) says the leap year is not observed");
    }
    if (previous) {
      // One hour after the previous record (month, day and hour; typical years mix source years).
      int m = previous->month, d = previous->day, h = int(previous->hour) + 1;
      if (h > 24) {
        h = 1;
        const bool leap_next = r.month == 2 && r.day == 29;  // Feb 28 is followed by Feb 29 only in a leap file
        if (++d > days_in_month(m, leap_next || (m == 2 && previous->day == 29))) {
          d = 1;
          m = m % 12 + 1;
        }
      }
      if (r.month != m || r.day != d || hour != h)
        throw input_error(where, fmt::format("record {}/{} hour {} does not follow {}/{} hour {} by one hour", r.month, r.day,
                                             hour, previous->month, previous->day, int(previous->hour)));
    }
    r.dew_point_c = unless_missing(number(v[7], where, "dew point (field 8)"), 99.9);
    r.direct_normal_irradiance = unless_missing(number(v[14], where, "direct normal irradiance (field 15)"), 9999);
    r.diffuse_horizontal_irradiance = unless_missing(number(v[15], where, "diffuse horizontal irradiance (field 16)"), 9999);
    r.direct_normal_illuminance = unless_missing(number(v[17], where, "direct normal illuminance (field 18)"), 999999);
    r.diffuse_horizontal_illuminance = unless_missing(number(v[18], where, "diffuse horizontal illuminance (field 19)"), 999999);
    r.ground_reflectance = unless_missing(number(v[32], where, "albedo (field 33)"), 999);
    for (const auto& [value, what] : {std::pair{r.direct_normal_irradiance, "direct normal irradiance"},
                                      std::pair{r.diffuse_horizontal_irradiance, "diffuse horizontal irradiance"},
                                      std::pair{r.direct_normal_illuminance, "direct normal illuminance"},
                                      std::pair{r.diffuse_horizontal_illuminance, "diffuse horizontal illuminance"}})
      if (value && *value < 0) throw input_error(where, fmt::format("{} {:g} is negative", what, *value));
    if (r.ground_reflectance && (*r.ground_reflectance < 0 || *r.ground_reflectance > 1))
      throw input_error(where, fmt::format("albedo {:g} is outside [0, 1]", *r.ground_reflectance));
    // TMY3 writes 0 lux where its illuminance model was not run (low suns) although the
    // irradiance is positive (271 diffuse and 320 direct values in the Chicago O'Hare file): such
    // a zero is no measurement, and is taken as missing.
    for (auto [lux, irradiance] : {std::pair{&r.direct_normal_illuminance, r.direct_normal_irradiance},
                                   std::pair{&r.diffuse_horizontal_illuminance, r.diffuse_horizontal_irradiance}})
      if (*lux == 0.0 && irradiance > 0.0) {
        lux->reset();
        ++f.zero_illuminances_taken_as_missing;
      }
    r.usable = r.direct_normal_irradiance && r.diffuse_horizontal_irradiance;
    f.unusable_records += !r.usable;
    f.missing_dew_points += !r.dew_point_c;
    f.missing_illuminances += !r.direct_normal_illuminance || !r.diffuse_horizontal_illuminance;
    f.records.push_back(r);
    previous = &f.records.back();
  }
  check_share(f);
  return f;
}

WeatherFile parse_wea(std::string_view text, const std::string& name) {
  WeatherFile f;
  f.path = name;
  f.format = WeatherFormat::wea;
  const std::vector<std::string_view> lines = split_lines(text);
  constexpr std::string_view kKeys[6] = {"place", "latitude", "longitude", "time_zone", "site_elevation",
                                         "weather_data_file_units"};
  double values[6] = {};
  for (int i = 0; i < 6; ++i) {
    const SourceLocation where{name, i + 1};
    if (std::size_t(i) >= lines.size()) throw input_error(where, fmt::format("the header ends before '{}'", kKeys[i]));
    const std::string_view line = trim(lines[i]);
    const std::size_t space = line.find_first_of(" \t");
    const std::string_view key = line.substr(0, space);
    if (key != kKeys[i]) throw input_error(where, fmt::format("expected '{}', found '{}'", kKeys[i], key.substr(0, 40)));
    const std::string_view rest = space == std::string_view::npos ? std::string_view{} : trim(line.substr(space));
    if (i == 0) f.location.place = std::string(rest);
    else values[i] = number(rest, where, kKeys[i]);
  }
  f.location.latitude_deg = values[1];
  f.location.longitude_deg = -values[2];   // .wea: west positive
  f.location.time_zone_h = -values[3] / 15;  // .wea: the standard meridian, west positive
  f.location.elevation_m = values[4];
  check_location(f.location, {name, 3});
  const double units = values[5];
  if (units == 2)
    throw input_error({name, 6}, "weather_data_file_units 2 (direct horizontal irradiance) is not read; use 1 (direct "
                                 "normal) or 3 (illuminance)");
  if (units != 1 && units != 3) throw input_error({name, 6}, fmt::format("weather_data_file_units {:g} is not 1, 2 or 3", units));
  f.photometric = units == 3;
  for (std::size_t i = 6; i < lines.size(); ++i) {
    const SourceLocation where{name, int(i) + 1};
    const auto v = split_whitespace(lines[i]);
    if (v.empty()) continue;
    if (v.size() != 5) throw input_error(where, fmt::format("{} values, 5 expected (month day hour direct diffuse)", v.size()));
    WeatherRecord r;
    r.line = where.line;
    r.month = integer(v[0], where, "month");
    r.day = integer(v[1], where, "day");
    r.hour = number(v[2], where, "hour");
    if (r.month < 1 || r.month > 12) throw input_error(where, fmt::format("month {} is not 1–12", r.month));
    if (r.day < 1 || r.day > days_in_month(r.month, true))
      throw input_error(where, fmt::format("day {} does not exist in month {}", r.day, r.month));
    if (!(r.hour >= 0 && r.hour < 24)) throw input_error(where, fmt::format("hour {:g} is outside [0, 24)", r.hour));
    const double direct = number(v[3], where, "direct"), diffuse = number(v[4], where, "diffuse");
    if (direct < 0 || diffuse < 0) throw input_error(where, "negative direct or diffuse value");
    (f.photometric ? r.direct_normal_illuminance : r.direct_normal_irradiance) = direct;
    (f.photometric ? r.diffuse_horizontal_illuminance : r.diffuse_horizontal_irradiance) = diffuse;
    r.usable = true;
    f.missing_dew_points += 1;
    f.records.push_back(r);
  }
  check_share(f);
  return f;
}

WeatherFile read_weather_file(const std::string& path) {
  std::string extension = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (extension != ".epw" && extension != ".wea")
    throw Error(path + ": a weather file must be an EnergyPlus .epw or a Radiance .wea");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot read");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path + ": cannot read");
  return extension == ".epw" ? parse_epw(text.str(), path) : parse_wea(text.str(), path);
}

const WeatherRecord* find_record(const WeatherFile& file, int month, int day, int hour_ending) {
  for (const WeatherRecord& r : file.records)
    if (r.month == month && r.day == day &&
        (file.format == WeatherFormat::epw ? int(r.hour) == hour_ending : r.hour > hour_ending - 1 && r.hour <= hour_ending))
      return &r;
  return nullptr;
}

}  // namespace daylit
