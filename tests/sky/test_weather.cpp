// Weather files (sky/weather_file.hpp) and the sun of an hour (sky/hour_sun.hpp): a real EPW read
// field by field (an extract of NREL's TMY3 file for Chicago O'Hare, tests/data), the same hours
// as a .wea, a generated leap-year file holding every missing-value code of the fields read, bad
// files refused with file:line, and the hour-ending convention with its sunrise and sunset hours.

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "geometry/error.hpp"
#include "sky/hour_sun.hpp"
#include "sky/weather_file.hpp"

using namespace daylit;

namespace {

const std::string kData = DAYLIT_TEST_DATA_DIR;

// A minimal valid EPW: header, then `records` (each a full line).
std::string epw(const std::vector<std::string>& records, const std::string& leap = "No", const std::string& per_hour = "1") {
  std::string t = "LOCATION,Here,,XX,test,0,40.0,-105.0,-7.0,1600\nDESIGN CONDITIONS,0\nTYPICAL/EXTREME PERIODS,0\n"
                  "GROUND TEMPERATURES,0\nHOLIDAYS/DAYLIGHT SAVINGS," + leap + ",0,0,0\nCOMMENTS 1,x\nCOMMENTS 2,x\n"
                  "DATA PERIODS,1," + per_hour + ",Data,Sunday, 1/ 1,12/31\n";
  for (const auto& r : records) t += r + "\n";
  return t;
}

// A record with the fields daylit reads set, the others plausible.
std::string record(int year, int month, int day, int hour, std::string dni = "500", std::string dhi = "100",
                   std::string dew = "2.0") {
  return std::to_string(year) + "," + std::to_string(month) + "," + std::to_string(day) + "," + std::to_string(hour) +
         ",60,X,10.0," + dew + ",50,83000,0,1415,250,400," + dni + "," + dhi +
         ",40000,50000,12000,0,180,2.0,0,0,30.0,77777,9,999999999,5,0.05,0,88,0.2,0.0,1.0";
}

void check_error(const std::function<void()>& f, const std::string& expected) {
  try {
    f();
    FAIL("no error; expected: " << expected);
  } catch (const Error& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find(expected) != std::string::npos);
  }
}

}  // namespace

TEST_CASE("a real EPW is read field by field (Chicago O'Hare TMY3, 1-3 January)") {
  const WeatherFile f = read_weather_file(kData + "/chicago-ohare-tmy3-jan1-3.epw");
  CHECK(f.format == WeatherFormat::epw);
  CHECK(f.location.place == "Chicago Ohare Intl Ap, IL, USA");
  CHECK(f.location.latitude_deg == 41.98);
  CHECK(f.location.longitude_deg == -87.92);
  CHECK(f.location.time_zone_h == -6.0);
  CHECK(f.location.elevation_m == 201.0);
  CHECK(f.leap_year_observed == false);
  REQUIRE(f.records.size() == 72);
  CHECK(f.unusable_records == 0);
  // Line 20: 1986,1,1,12,... dew point −9.4 °C, E_dn 521, E_dh 144 W/m², 50467 and 16854 lux, albedo 999 (missing).
  const WeatherRecord& r = f.records[11];
  CHECK(r.line == 20);
  CHECK(r.year == 1986);
  CHECK(r.month == 1);
  CHECK(r.day == 1);
  CHECK(r.hour == 12);
  CHECK(*r.dew_point_c == -9.4);
  CHECK(*r.direct_normal_irradiance == 521);
  CHECK(*r.diffuse_horizontal_irradiance == 144);
  CHECK(*r.direct_normal_illuminance == 50467);
  CHECK(*r.diffuse_horizontal_illuminance == 16854);
  CHECK(!r.ground_reflectance);
  CHECK(r.usable);
  const WeatherRecord* found = find_record(f, 1, 1, 13);
  REQUIRE(found);
  CHECK(found->line == 21);
  CHECK(*found->direct_normal_irradiance == 151);
  CHECK(*found->diffuse_horizontal_illuminance == 18939);
  CHECK(find_record(f, 1, 4, 1) == nullptr);
  // 1/1 hour 17 (line 25): E_dh 5 W/m² beside 0 lux, a TMY3 low-sun hour: the zero is no
  // measurement and is taken as missing; five such values in these 72 hours (counted by awk).
  const WeatherRecord* dusk = find_record(f, 1, 1, 17);
  REQUIRE(dusk);
  CHECK(*dusk->diffuse_horizontal_irradiance == 5);
  CHECK(!dusk->diffuse_horizontal_illuminance);
  CHECK(*dusk->direct_normal_illuminance == 0);  // beside E_dn = 0: a true zero
  CHECK(f.zero_illuminances_taken_as_missing == 5);
  CHECK(f.records.back().day == 3);
  CHECK(f.records.back().hour == 24);
}

TEST_CASE("a .wea is read with its west-positive longitude and time zone") {
  const WeatherFile f = read_weather_file(kData + "/chicago-ohare-tmy3-jan1-3.wea");
  CHECK(f.format == WeatherFormat::wea);
  CHECK(f.location.place == "Chicago Ohare Intl Ap_USA");
  CHECK(f.location.latitude_deg == 41.98);
  CHECK(f.location.longitude_deg == -87.92);
  CHECK(f.location.time_zone_h == -6.0);
  CHECK(f.location.elevation_m == 201);
  CHECK(!f.photometric);
  REQUIRE(f.records.size() == 72);
  const WeatherRecord* r = find_record(f, 1, 1, 12);
  REQUIRE(r);
  CHECK(r->hour == 11.5);
  CHECK(r->line == 18);
  CHECK(*r->direct_normal_irradiance == 521);
  CHECK(*r->diffuse_horizontal_irradiance == 144);
  CHECK(!r->dew_point_c);
}

TEST_CASE("a leap-year EPW keeps 29 February, and every missing-value code is read as missing") {
  const WeatherFile f = read_weather_file(kData + "/leap-2020-feb28-mar1.epw");
  CHECK(f.leap_year_observed == true);
  REQUIRE(f.records.size() == 72);
  const WeatherRecord* feb29 = find_record(f, 2, 29, 1);
  REQUIRE(feb29);
  CHECK(feb29->year == 2020);
  CHECK(feb29->line == 9 + 24);
  // make_weather_samples.py's MISSING: each code in one record, every other field present.
  auto at = [&](int m, int d, int h) { return *find_record(f, m, d, h); };
  CHECK(!at(2, 28, 12).dew_point_c);
  CHECK(at(2, 28, 13).dew_point_c);
  CHECK(!at(2, 29, 11).direct_normal_irradiance);
  CHECK(at(2, 29, 11).diffuse_horizontal_irradiance);
  CHECK(!at(2, 29, 11).usable);
  CHECK(!at(2, 29, 12).diffuse_horizontal_irradiance);
  CHECK(!at(2, 29, 12).usable);
  CHECK(!at(2, 29, 13).direct_normal_illuminance);
  CHECK(at(2, 29, 13).diffuse_horizontal_illuminance);
  CHECK(at(2, 29, 13).usable);  // illuminance falls back to the efficacies
  CHECK(!at(2, 29, 14).diffuse_horizontal_illuminance);
  CHECK(!at(3, 1, 12).ground_reflectance);
  CHECK(*at(3, 1, 13).ground_reflectance == 0.2);
  CHECK(f.unusable_records == 2);
  CHECK(f.missing_dew_points == 1);
  CHECK(f.missing_illuminances == 2);
  // Values just below a code are values (the dictionary's rule is "≥ code is missing").
  const WeatherFile g = parse_epw(epw({record(2001, 1, 1, 1, "9998.9", "100", "99.8")}), "g.epw");
  CHECK(*g.records[0].direct_normal_irradiance == 9998.9);
  CHECK(*g.records[0].dew_point_c == 99.8);
}

TEST_CASE("bad weather files are refused with file and line") {
  check_error([] { parse_epw("LOCATION,a,b,c,d,e,40,-105,-7,1600\nDESIGN CONDITIONS\n", "f.epw"); },
              "f.epw:3: the header ends before its TYPICAL/EXTREME PERIODS line");
  check_error([] { parse_epw("LOCATION,a,b,c,d,e,north,-105,-7,1600\n" + epw({}).substr(epw({}).find('\n') + 1), "f.epw"); },
              "f.epw:1: latitude (field 7) is 'north', not a number");
  check_error([] { parse_epw(epw({}).replace(0, 8, "LOCATIO"), "f.epw"); }, "f.epw:1: expected the header line LOCATION");
  check_error([] { parse_epw(epw({record(2001, 1, 1, 1)}, "Maybe"), "f.epw"); }, "f.epw:5: the leap-year field is 'MAYBE'");
  check_error([] { parse_epw(epw({record(2001, 1, 1, 1)}, "No", "4"), "f.epw"); }, "f.epw:8: 4 records per hour");
  check_error([] { parse_epw(epw({}), "f.epw"); }, "f.epw: no hourly records");
  check_error([] { parse_epw(epw({"2001,1,1,1,60,X,10"}), "f.epw"); }, "f.epw:9: 7 fields, at least 33 expected");
  check_error([] { parse_epw(epw({record(2001, 1, 1, 1), record(2001, 1, 1, 2, "lots")}), "f.epw"); },
              "f.epw:10: direct normal irradiance (field 15) is 'lots', not a number");
  check_error([] { parse_epw(epw({record(2001, 1, 1, 1, "500", "-3")}), "f.epw"); },
              "f.epw:9: diffuse horizontal irradiance -3 is negative");
  check_error([] { parse_epw(epw({record(2001, 1, 1, 0)}), "f.epw"); }, "f.epw:9: hour 0 is not 1–24");
  check_error([] { parse_epw(epw({record(2001, 4, 31, 1)}), "f.epw"); }, "f.epw:9: day 31 does not exist in month 4");
  check_error([] { parse_epw(epw({record(2019, 2, 29, 1)}, "Yes"), "f.epw"); }, "f.epw:9: 29 February 2019 does not exist");
  check_error([] { parse_epw(epw({record(2020, 2, 29, 1)}, "No"), "f.epw"); }, "f.epw:9: a 29 February record, but the header");
  check_error([] { parse_epw(epw({record(2001, 1, 1, 1), record(2001, 1, 1, 3)}), "f.epw"); },
              "f.epw:10: record 1/1 hour 3 does not follow 1/1 hour 1 by one hour");
  check_error([] { parse_epw(epw({record(2001, 2, 28, 24), record(2001, 2, 29, 1)}, "No"), "f.epw"); }, "f.epw:10:");
  check_error([] { parse_epw(epw({record(2001, 1, 1, 1), "", record(2001, 1, 1, 2)}), "f.epw"); },
              "f.epw:10: blank line between records");
  {
    // 2 of 10 records without irradiance: 20 % > 10 %.
    std::vector<std::string> r;
    for (int h = 1; h <= 10; ++h) r.push_back(record(2001, 1, 1, h, h <= 2 ? "9999" : "500"));
    check_error([&] { parse_epw(epw(r), "f.epw"); }, "f.epw: 2 of 10 records (20.0 %) lack");
    r[1] = record(2001, 1, 1, 2);
    CHECK(parse_epw(epw(r), "f.epw").unusable_records == 1);  // 10 % is accepted
  }
  const std::string wea = "place X\nlatitude 40\nlongitude 105\ntime_zone 105\nsite_elevation 1600\nweather_data_file_units 1\n";
  CHECK(parse_wea(wea + "1 1 12.5 500 100\n", "f.wea").location.time_zone_h == -7);
  check_error([&] { parse_wea("place X\nlat 40\n", "f.wea"); }, "f.wea:2: expected 'latitude', found 'lat'");
  check_error([&] { parse_wea(wea.substr(0, wea.size() - 2) + "2\n1 1 12.5 500 100\n", "f.wea"); },
              "f.wea:6: weather_data_file_units 2 (direct horizontal irradiance) is not read");
  check_error([&] { parse_wea(wea + "1 1 12.5 500\n", "f.wea"); }, "f.wea:7: 4 values, 5 expected");
  check_error([&] { parse_wea(wea + "1 1 25 500 100\n", "f.wea"); }, "f.wea:7: hour 25 is outside [0, 24)");
  check_error([&] { parse_wea(wea + "1 1 12 -1 100\n", "f.wea"); }, "f.wea:7: negative direct or diffuse value");
  check_error([&] { std::string w = wea;
    parse_wea(w.replace(w.find("time_zone 105"), 13, "time_zone 300"), "f.wea"); },
              "f.wea:3: time zone -20 h is beyond ±14 h");
  check_error([] { read_weather_file("weather.csv"); }, "weather.csv: a weather file must be an EnergyPlus .epw or a Radiance .wea");
  check_error([] { read_weather_file(kData + "/absent.epw"); }, "absent.epw: cannot read");
}

TEST_CASE("an hour-ending record's sun is taken at the half hour, or in the middle of the part of the hour it is up") {
  // Chicago O'Hare, 1 January 1986, UTC−6.
  const double lat = 41.98, lon = -87.92, h = 201;
  SolarPositionInput in;
  in.time = {1986, 1, 1, 11, 30, 0, -360};
  in.latitude_deg = lat;
  in.longitude_deg = lon;
  in.elevation_m = h;
  const HourSun noon = sun_for_hour_ending(1986, 1, 1, 12, -6, lat, lon, h);
  CHECK(noon.up);
  CHECK(noon.up_fraction == 1);
  CHECK(noon.instant.hour == 11);
  CHECK(noon.instant.minute == 30);
  CHECK(noon.position.zenith_deg == solar_position(in).zenith_deg);

  // Sunrise near 07:18 and sunset near 16:30 local standard time.
  const HourSun rise = sun_for_hour_ending(1986, 1, 1, 8, -6, lat, lon, h);
  REQUIRE(rise.up);
  CHECK(rise.start_h > 7.2);
  CHECK(rise.start_h < 7.4);
  CHECK(rise.end_h == 8);
  CHECK(rise.up_fraction == Approx(8 - rise.start_h).epsilon(1e-12));
  // At the crossing the apparent elevation is 0 (to the bisection's 0.01 s: 4e-5° at most).
  in.time = {1986, 1, 1, 7, int((rise.start_h - 7) * 60), 0, -360};
  in.time.second = (rise.start_h - 7) * 3600 - 60 * in.time.minute;
  CHECK(std::abs(solar_position(in).elevation_deg) < 1e-4);
  CHECK(rise.position.elevation_deg > 0);
  const double mid = 0.5 * (rise.start_h + 8);
  CHECK(rise.instant.hour * 3600 + rise.instant.minute * 60 + rise.instant.second == Approx(mid * 3600).epsilon(1e-12));

  const HourSun set = sun_for_hour_ending(1986, 1, 1, 17, -6, lat, lon, h);
  REQUIRE(set.up);
  CHECK(set.start_h == 16);
  CHECK(set.end_h > 16.4);
  CHECK(set.end_h < 16.6);
  CHECK(!sun_for_hour_ending(1986, 1, 1, 3, -6, lat, lon, h).up);
  CHECK(!sun_for_hour_ending(1986, 1, 1, 18, -6, lat, lon, h).up);
  // The last hour of the day ends at 24:00 and is night; the leap day has a sun.
  CHECK(!sun_for_hour_ending(1986, 1, 1, 24, -6, lat, lon, h).up);
  CHECK(sun_for_hour_ending(2020, 2, 29, 12, -7, 40, -105, 1600).up);
}

TEST_CASE("an instant picks the weather record whose hour holds it, in the file's local standard time") {
  const WeatherFile f = read_weather_file(kData + "/chicago-ohare-tmy3-jan1-3.epw");
  auto pick = [&](const char* iso) { return weather_hour(f, parse_iso8601_time(iso), 41.98, -87.92, 201); };
  // 12:00 local standard time ends the hour 11:00–12:00: record 1/1 hour 12 (line 20); the same
  // instant in UTC or in daylight time (UTC−5) picks it too.
  CHECK(pick("2026-01-01T12:00:00-06:00").record->line == 20);
  CHECK(pick("2026-01-01T18:00:00Z").record->line == 20);
  CHECK(pick("2026-01-01T13:00:00-05:00").record->line == 20);
  CHECK(pick("2026-01-01T11:00:00.001-06:00").record->line == 20);
  CHECK(pick("2026-01-01T12:00:00.001-06:00").record->line == 21);
  // Midnight ends the day's 24th hour: the record of 1 January, hour 24 (line 32).
  const WeatherHour midnight = pick("2026-01-02T00:00:00-06:00");
  CHECK(midnight.record->line == 32);
  CHECK(midnight.hour_ending == 24);
  CHECK(!midnight.sun.up);
  const WeatherHour noon = pick("2026-01-01T12:00:00-06:00");
  CHECK(noon.sun.up);
  CHECK(noon.sun.instant.year == 2026);  // the sun of the year asked, the record's values (1986)
  CHECK(noon.sun.instant.hour == 11);
  CHECK(noon.sun.instant.minute == 30);
  check_error([&] { pick("2026-01-04T12:00:00-06:00"); }, "no record for 01-04 hour 12 (11:00–12:00 local standard time, UTC-6)");
  // A record with a missing code is refused by file and line when it is the hour asked for.
  const WeatherFile leap = read_weather_file(kData + "/leap-2020-feb28-mar1.epw");
  check_error([&] { weather_hour(leap, parse_iso8601_time("2020-02-29T11:00:00-07:00"), 40, -105, 1600); },
              "leap-2020-feb28-mar1.epw:43: the direct normal or diffuse horizontal value of this hour is missing");
  CHECK(weather_hour(leap, parse_iso8601_time("2020-02-29T09:30:00-07:00"), 40, -105, 1600).record->line == 42);
  // A .wea record is the one of that day whose time lies in the hour; its sun is at that time.
  const WeatherFile wea = read_weather_file(kData + "/chicago-ohare-tmy3-jan1-3.wea");
  const WeatherHour w = weather_hour(wea, parse_iso8601_time("2026-01-01T12:00:00-06:00"), 41.98, -87.92, 201);
  CHECK(w.record->hour == 11.5);
  CHECK(w.sun.instant.hour == 11);
  CHECK(w.sun.instant.minute == 30);
  CHECK(w.sun.position.zenith_deg == noon.sun.position.zenith_deg);
}
