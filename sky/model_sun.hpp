#pragma once
// The sun's direction in the model frame: from an instant and the site (NREL SPA, topocentric,
// refraction included), or from a given zenith and azimuth; turned into the model frame by the
// site's north angle, or with +y north where there is no site.

#include <optional>
#include <string>

#include "geometry/vec3.hpp"
#include "sky/site.hpp"

namespace daylit {

struct ModelSun {
  std::string source = "none";  // "spa" (from an instant), "given", or "none"
  double zenith_deg = 0, azimuth_deg = 0;  // azimuth clockwise from true north
  Vec3 direction{0, 0, 1};                 // unit, model frame, towards the sun
  double distance_au = 1;                  // Earth–sun distance (SPA's R; 1 AU when given)
};

// SPA at the site's origin for an ISO 8601 instant with a UTC offset (parse_iso8601_time);
// throws daylit::Error for a malformed instant.
ModelSun sun_at_instant(const std::string& iso8601, const Site& site, double pressure_hpa, double temperature_c);

// A given position; `site` turns it by the site's north (model_direction), else +y is north.
ModelSun sun_given(double zenith_deg, double azimuth_deg, const std::optional<Site>& site);

}  // namespace daylit
