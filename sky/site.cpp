#include "sky/site.hpp"

#include <GeographicLib/LocalCartesian.hpp>
#include <GeographicLib/Math.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include <cmath>

#include <fmt/format.h>

#include "geometry/error.hpp"
#include "geometry/json_input.hpp"

namespace daylit {

namespace {

constexpr double kMinElevation = -11000, kMaxElevation = 100000;  // metres: deepest trench to the Kármán line

void check_elevation(double elevation_m) {
  if (!(elevation_m >= kMinElevation && elevation_m <= kMaxElevation))
    throw Error(fmt::format("elevation_m {} is outside [{}, {}] m", elevation_m, kMinElevation, kMaxElevation));
}

void check_ground(double ground_z_m) {
  if (!std::isfinite(ground_z_m)) throw Error("ground_z_m must be finite");
}

}  // namespace

Site Site::geographic(double latitude_deg, double longitude_deg, double elevation_m, double north_deg,
                      double ground_z_m) {
  // At a pole "north" names no direction: the east-north-up frame is undefined there.
  if (!(latitude_deg > -90 && latitude_deg < 90))
    throw Error(fmt::format("latitude_deg {} is not strictly between -90 and 90", latitude_deg));
  if (!(longitude_deg >= -180 && longitude_deg <= 180))
    throw Error(fmt::format("longitude_deg {} is outside [-180, 180]", longitude_deg));
  check_elevation(elevation_m);
  if (!(north_deg >= -360 && north_deg <= 360)) throw Error(fmt::format("north_deg {} is outside [-360, 360]", north_deg));
  check_ground(ground_z_m);
  Site s;
  s.origin_ = {latitude_deg, longitude_deg, elevation_m};
  s.ground_z_m_ = ground_z_m;
  s.set_north(north_deg);
  s.enu_ = std::make_shared<const GeographicLib::LocalCartesian>(latitude_deg, longitude_deg, elevation_m);
  return s;
}

Site Site::utm(int zone, bool northern, double easting_m, double northing_m, double elevation_m, double ground_z_m) {
  if (zone < GeographicLib::UTMUPS::MINUTMZONE || zone > GeographicLib::UTMUPS::MAXUTMZONE)
    throw Error(fmt::format("UTM zone {} is outside 1..60", zone));
  if (!std::isfinite(easting_m) || !std::isfinite(northing_m)) throw Error("UTM easting and northing must be finite");
  UtmGrid grid{zone, northern, easting_m, northing_m, 0, 1};
  double latitude_deg = 0, longitude_deg = 0;
  try {
    // Throws GeographicErr when (easting, northing) lies outside the zone's legal UTM range.
    GeographicLib::UTMUPS::Reverse(zone, northern, easting_m, northing_m, latitude_deg, longitude_deg,
                                   grid.convergence_deg, grid.scale);
  } catch (const GeographicLib::GeographicErr& e) {
    throw Error(fmt::format("UTM zone {}{} easting {} northing {}: {}", zone, northern ? "n" : "s", easting_m,
                            northing_m, e.what()));
  }
  // γ is the bearing of grid north (the model's +y) clockwise from true north, so true north lies
  // γ anticlockwise from +y: north_deg = −γ.
  Site s = geographic(latitude_deg, longitude_deg, elevation_m, -grid.convergence_deg, ground_z_m);
  s.utm_ = grid;
  return s;
}

void Site::set_north(double north_deg) {
  north_deg_ = north_deg;
  double sin_n = 0, cos_n = 1;
  GeographicLib::Math::sincosd(north_deg, sin_n, cos_n);  // exact at multiples of 90°
  north_ = {sin_n, cos_n, 0};
  east_ = {cos_n, -sin_n, 0};
}

Vec3 Site::model_from_enu(const Vec3& enu) const noexcept { return enu.x * east_ + enu.y * north_ + Vec3{0, 0, enu.z}; }

Vec3 Site::enu_from_model(const Vec3& model) const noexcept {
  return {dot(model, east_), dot(model, north_), model.z};
}

Vec3 Site::model_from_wgs84(double latitude_deg, double longitude_deg, double height_m) const {
  Vec3 enu;
  enu_->Forward(latitude_deg, longitude_deg, height_m, enu.x, enu.y, enu.z);
  return model_from_enu(enu);
}

GeographicPosition Site::wgs84_from_model(const Vec3& model) const {
  const Vec3 enu = enu_from_model(model);
  GeographicPosition g;
  enu_->Reverse(enu.x, enu.y, enu.z, g.latitude_deg, g.longitude_deg, g.height_m);
  return g;
}

Vec3 Site::model_direction(double azimuth_deg, double altitude_deg) const noexcept {
  double sin_a = 0, cos_a = 1, sin_h = 0, cos_h = 1;
  GeographicLib::Math::sincosd(azimuth_deg, sin_a, cos_a);
  GeographicLib::Math::sincosd(altitude_deg, sin_h, cos_h);
  return model_from_enu({cos_h * sin_a, cos_h * cos_a, sin_h});
}

std::string Site::description() const {
  std::string text = fmt::format("{:.6f}° {} {:.6f}° {}, {:g} m above the WGS84 ellipsoid; true north {:g}° clockwise from +y",
                                 std::abs(origin_.latitude_deg), origin_.latitude_deg >= 0 ? "N" : "S",
                                 std::abs(origin_.longitude_deg), origin_.longitude_deg >= 0 ? "E" : "W",
                                 origin_.height_m, north_deg_);
  if (utm_)
    text += fmt::format(" (UTM zone {}{} grid north; meridian convergence {:.6f}°)", utm_->zone,
                        utm_->northern ? "n" : "s", utm_->convergence_deg);
  return text;
}

// ---------------------------------------------------------------------------------------------
// The JSON site description.

namespace {

struct Fields {
  const nlohmann::json& object;
  const std::string& file;

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw Error(file + ": field '" + field + "': " + problem);
  }

  const nlohmann::json* find(const std::string& key) const {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
  }

  double number(const std::string& key, const std::string& path, std::optional<double> fallback = {}) const {
    const nlohmann::json* v = find(key);
    if (!v) {
      if (fallback) return *fallback;
      fail(path, "missing (a number is required)");
    }
    if (!v->is_number()) fail(path, "must be a number, not " + json_input::kind_of(*v));
    const double x = v->get<double>();
    if (!std::isfinite(x)) fail(path, "must be finite");
    return x;
  }
};

Site site_from_json(const nlohmann::json& doc, const std::string& name) {
  if (!doc.is_object()) throw Error(name + ": a site description must be a JSON object, not " + json_input::kind_of(doc));
  const Fields f{doc, name};
  const bool has_utm = doc.contains("utm");
  const bool has_geographic = doc.contains("latitude_deg") || doc.contains("longitude_deg");
  for (const auto& [key, value] : doc.items()) {
    static const char* const kCommon[] = {"elevation_m", "ground_z_m", "name", "description", "comment"};
    static const char* const kGeographic[] = {"latitude_deg", "longitude_deg", "north_deg"};
    static const char* const kUtm[] = {"utm", "origin_easting_m", "origin_northing_m"};
    // (key is copied by reference explicitly: clang 14 cannot capture a structured binding.)
    const auto in = [&, &key_ = key](const auto& keys) {
      for (const char* k : keys)
        if (key_ == k) return true;
      return false;
    };
    if (in(kCommon)) {
      if ((key == "name" || key == "description" || key == "comment") && !value.is_string())
        f.fail(key, "must be a string, not " + json_input::kind_of(value));
      continue;
    }
    if (in(kGeographic) || in(kUtm)) {
      if (has_utm && key == "north_deg")
        f.fail(key, "is not allowed with \"utm\": a UTM model's north is the grid's, turned by the meridian convergence");
      continue;
    }
    f.fail(key, "unknown (expected latitude_deg, longitude_deg, elevation_m, north_deg, ground_z_m; or utm, "
                "origin_easting_m, origin_northing_m, elevation_m, ground_z_m)");
  }
  if (has_utm && has_geographic)
    throw Error(name + ": give either latitude_deg/longitude_deg or utm with origin_easting_m/origin_northing_m, not both");
  if (!has_utm && (doc.contains("origin_easting_m") || doc.contains("origin_northing_m")))
    f.fail(doc.contains("origin_easting_m") ? "origin_easting_m" : "origin_northing_m",
           "needs \"utm\": {\"zone\": …, \"northern\": …}");

  const double elevation = f.number("elevation_m", "elevation_m");
  const double ground = f.number("ground_z_m", "ground_z_m", 0.0);
  try {
    if (!has_utm) {
      const double latitude = f.number("latitude_deg", "latitude_deg");
      const double longitude = f.number("longitude_deg", "longitude_deg");
      const double north = f.number("north_deg", "north_deg", 0.0);
      if (!(latitude > -90 && latitude < 90)) f.fail("latitude_deg", fmt::format("{} is not strictly between -90 and 90", latitude));
      if (!(longitude >= -180 && longitude <= 180)) f.fail("longitude_deg", fmt::format("{} is outside [-180, 180]", longitude));
      if (!(north >= -360 && north <= 360)) f.fail("north_deg", fmt::format("{} is outside [-360, 360]", north));
      if (!(elevation >= kMinElevation && elevation <= kMaxElevation))
        f.fail("elevation_m", fmt::format("{} is outside [{}, {}] m", elevation, kMinElevation, kMaxElevation));
      return Site::geographic(latitude, longitude, elevation, north, ground);
    }
    const nlohmann::json& utm = doc["utm"];
    if (!utm.is_object()) f.fail("utm", "must be an object {\"zone\": 1..60, \"northern\": true|false}, not " + json_input::kind_of(utm));
    for (const auto& [key, value] : utm.items())
      if (key != "zone" && key != "northern") f.fail("utm." + key, "unknown (expected zone and northern)");
    const Fields u{utm, name};
    const nlohmann::json* zone = u.find("zone");
    if (!zone) f.fail("utm.zone", "missing (an integer 1..60 is required)");
    if (!zone->is_number_integer() || zone->get<long long>() < 1 || zone->get<long long>() > 60)
      f.fail("utm.zone", "must be an integer from 1 to 60, not " + zone->dump());
    const nlohmann::json* northern = u.find("northern");
    if (!northern) f.fail("utm.northern", "missing (true for the northern hemisphere, false for the southern)");
    if (!northern->is_boolean()) f.fail("utm.northern", "must be true or false, not " + json_input::kind_of(*northern));
    const double easting = f.number("origin_easting_m", "origin_easting_m");
    const double northing = f.number("origin_northing_m", "origin_northing_m");
    if (!(elevation >= kMinElevation && elevation <= kMaxElevation))
      f.fail("elevation_m", fmt::format("{} is outside [{}, {}] m", elevation, kMinElevation, kMaxElevation));
    try {
      return Site::utm(int(zone->get<long long>()), northern->get<bool>(), easting, northing, elevation, ground);
    } catch (const Error& e) {
      f.fail("origin_easting_m/origin_northing_m", e.what());
    }
  } catch (const GeographicLib::GeographicErr& e) {
    throw Error(name + ": " + e.what());
  }
}

}  // namespace

Site parse_site_json(const std::string& text, const std::string& name) {
  return site_from_json(json_input::parse(text, name), name);
}

Site read_site_file(const std::string& path) { return site_from_json(json_input::read_file(path), path); }

}  // namespace daylit
