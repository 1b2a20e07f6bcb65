// `daylit sun (--location LAT,LON[,ELEV] | --site site.json) --time ISO8601 [--pressure-hpa P]
// [--temperature-c T] [--delta-t-s S] [--delta-ut1-s S]`: prints
// {"zenith_deg":…,"azimuth_deg":…,"elevation_deg":…,"declination_deg":…,"equation_of_time_min":…,
//  "delta_t_s":…}
// with every double to full (round-trip) precision. Bad arguments are refused by CLI11 while
// parsing, with the option's name and what is wrong.

#include "cli/sun_command.hpp"

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli/number_checks.hpp"
#include "geometry/error.hpp"
#include "sky/site.hpp"
#include "sky/solar_position.hpp"

namespace daylit::cli {

namespace {

struct SunOptions {
  std::string location, site, time;
  double pressure_hpa = 1013.25;
  double temperature_c = 10;
  double delta_t_s = 0;
  double delta_ut1_s = 0;
  CLI::Option* delta_t_option = nullptr;
};

struct Location {
  double latitude_deg, longitude_deg, elevation_m;
};

// "LAT,LON" or "LAT,LON,ELEV" (degrees, degrees east, metres); throws daylit::Error.
Location parse_location(const std::string& text) {
  std::vector<double> v;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string field = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    double x = 0;
    const char* first = field.data();
    const char* last = field.data() + field.size();
    if (first != last && *first == '+') ++first;  // from_chars refuses a leading '+'
    const auto [end, ec] = std::from_chars(first, last, x);
    if (field.empty() || ec != std::errc() || end != last || !std::isfinite(x))
      throw Error(fmt::format("\"{}\" is not a number in \"{}\" (expected LAT,LON,ELEV in degrees north, "
                              "degrees east and metres, e.g. 39.742476,-105.1786,1830.14)",
                              field, text));
    v.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (v.size() < 2 || v.size() > 3)
    throw Error(fmt::format("\"{}\" has {} numbers; expected LAT,LON,ELEV (ELEV may be left out: 0 m)", text, v.size()));
  if (!(std::abs(v[0]) <= 90)) throw Error(fmt::format("latitude {} is not within [-90, 90] degrees", v[0]));
  if (!(std::abs(v[1]) <= 180)) throw Error(fmt::format("longitude {} is not within [-180, 180] degrees (east positive)", v[1]));
  const double elevation = v.size() == 3 ? v[2] : 0;
  if (!(elevation > -6378140)) throw Error(fmt::format("elevation {} m is below the centre of the Earth", elevation));
  return {v[0], v[1], elevation};
}

// A CLI11 validator from a parser that throws daylit::Error: its message becomes CLI11's.
template <class Parse>
CLI::Validator validator_from(Parse parse, const std::string& description) {
  return CLI::Validator(
      [parse](std::string& text) -> std::string {
        try {
          parse(text);
          return {};
        } catch (const Error& e) {
          return e.what();
        }
      },
      description);
}

// The observer: from --location, or from the site file that `df` and `illuminance` take (its origin,
// with the height above the ellipsoid as the elevation: SPA uses it only for the parallax, where
// the geoid's tens of metres move the sun by under 1e-5 degrees).
Location observer(const SunOptions& opt) {
  if (!opt.location.empty()) return parse_location(opt.location);
  const GeographicPosition origin = read_site_file(opt.site).origin();
  return {origin.latitude_deg, origin.longitude_deg, origin.height_m};
}

int run_sun(const SunOptions& opt) {
  const Location site = observer(opt);
  SolarPositionInput in;
  in.time = parse_iso8601_time(opt.time);
  in.latitude_deg = site.latitude_deg;
  in.longitude_deg = site.longitude_deg;
  in.elevation_m = site.elevation_m;
  in.pressure_hpa = opt.pressure_hpa;
  in.temperature_c = opt.temperature_c;
  in.delta_ut1_s = opt.delta_ut1_s;
  if (opt.delta_t_option->count() > 0) in.delta_t_s = opt.delta_t_s;
  const SolarPosition p = solar_position(in);

  nlohmann::ordered_json out;
  out["zenith_deg"] = p.zenith_deg;
  out["azimuth_deg"] = p.azimuth_deg;
  out["elevation_deg"] = p.elevation_deg;
  out["declination_deg"] = p.declination_deg;
  out["equation_of_time_min"] = p.equation_of_time_min;
  out["delta_t_s"] = p.steps.delta_t_s;
  std::cout << out.dump() << '\n';
  return std::cout ? 0 : 1;
}

}  // namespace

std::function<int()> add_sun_command(CLI::App& app) {
  auto opt = std::make_shared<SunOptions>();
  CLI::App* sun = app.add_subcommand("sun", "The sun's zenith and azimuth at a site and an instant (NREL SPA)");
  sun->description(
      "Prints the sun's topocentric zenith and azimuth (degrees; azimuth clockwise from true north;\n"
      "refraction included) as one line of JSON, by the Solar Position Algorithm of Reda and Andreas\n"
      "(NREL/TP-560-34302): +-0.0003 degrees for the years -2000 to 6000 with the right Delta T and\n"
      "UT1 - UTC. Also printed: elevation, topocentric declination, the equation of time and the Delta T\n"
      "used.");
  // Where the observer is: exactly one of the two (an option group requiring one of its options).
  CLI::Option_group* observer = sun->add_option_group("observer", "Where the sun is seen from (one of):");
  observer
      ->add_option("--location", opt->location,
                   "LAT,LON,ELEV: latitude (degrees, north positive), longitude (degrees, east positive), elevation "
                   "(m; may be left out: 0), e.g. 39.742476,-105.1786,1830.14")
      ->check(validator_from(parse_location, "LAT,LON,ELEV"));
  observer->add_option("--site", opt->site, "Site file (JSON), as df and illuminance take it: the sun at its origin")
      ->check(CLI::ExistingFile);
  observer->require_option(1);
  sun->add_option("--time", opt->time,
                  "ISO 8601 instant with a UTC offset, e.g. 2003-10-17T12:30:30-07:00 (= 2003-10-17T19:30:30Z)")
      ->required()
      ->check(validator_from(parse_iso8601_time, "ISO8601"));
  sun->add_option("--pressure-hpa", opt->pressure_hpa, "Annual mean local air pressure for refraction, hPa")
      ->capture_default_str()
      ->check(number_in(0.0, 5000.0));
  sun->add_option("--temperature-c", opt->temperature_c, "Annual mean local air temperature for refraction, degrees C")
      ->capture_default_str()
      ->check(number_in(-273.0, 6000.0));  // −273 itself is refused by solar_position()
  opt->delta_t_option =
      sun->add_option("--delta-t-s", opt->delta_t_s,
                      "Delta T = TT - UT1, seconds (default: Espenak and Meeus's polynomial, within 5 s "
                      "in recent years; 5 s moves the sun by 6e-5 degrees)")
          ->check(number_in(-1e5, 1e5));
  sun->add_option("--delta-ut1-s", opt->delta_ut1_s,
                  "UT1 - UTC, seconds, from IERS Bulletin A (default 0; each second moves the sun 0.004 degrees "
                  "in hour angle)")
      ->capture_default_str()
      ->check(number_in(-1.0, 1.0));
  return [opt] { return run_sun(*opt); };
}

}  // namespace daylit::cli
