#include "sky/model_sun.hpp"

#include "sky/cie_sky.hpp"
#include "sky/solar_position.hpp"

namespace daylit {

ModelSun sun_at_instant(const std::string& iso8601, const Site& site, double pressure_hpa, double temperature_c) {
  SolarPositionInput in;
  in.time = parse_iso8601_time(iso8601);
  in.latitude_deg = site.origin().latitude_deg;
  in.longitude_deg = site.origin().longitude_deg;
  in.elevation_m = site.origin().height_m;
  in.pressure_hpa = pressure_hpa;
  in.temperature_c = temperature_c;
  const SolarPosition p = solar_position(in);
  return {"spa", p.zenith_deg, p.azimuth_deg, site.model_direction(p.azimuth_deg, 90 - p.zenith_deg), p.distance_au};
}

ModelSun sun_given(double zenith_deg, double azimuth_deg, const std::optional<Site>& site) {
  const Vec3 direction = site ? site->model_direction(azimuth_deg, 90 - zenith_deg) : sun_direction(zenith_deg, azimuth_deg);
  return {"given", zenith_deg, azimuth_deg, direction};
}

}  // namespace daylit
