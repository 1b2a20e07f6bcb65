#pragma once
// Where a model stands on the earth and which way it faces: the model frame against WGS84.
//
// Frames (every conversion is GeographicLib's; none is written here):
// - WGS84 geographic: latitude φ and longitude λ in degrees, height h in metres above the WGS84
//   ellipsoid (ellipsoidal height: about 50 m more than the height above sea level in central
//   Europe; the difference only scales horizontal distances, by h/R ≈ 8e-6 per 50 m).
// - Local east-north-up (ENU): GeographicLib::LocalCartesian at the site's origin; x east, y true
//   north, z up along the ellipsoid's normal at the origin.
// - Model frame: the scene files' metres, z up (= ENU z), origin at the site's origin, turned
//   about z so that TRUE NORTH LIES north_deg DEGREES CLOCKWISE FROM THE MODEL'S +y AXIS, SEEN
//   FROM ABOVE: true north in the model is (sin n, cos n, 0), east (cos n, −sin n, 0). A plan
//   drawn with its north arrow turned 30° to the right of "up" has north_deg = 30.
//
// A model drawn on a UTM grid (+x grid east, +y grid north) has north_deg = −γ, where γ, the
// meridian convergence at the origin, is the bearing of grid north clockwise from true north
// (GeographicLib's convention; γ > 0 east of the zone's central meridian in the northern
// hemisphere, where true north then lies γ anticlockwise from grid north). The model frame is
// still the local one: lengths are ground lengths, the UTM scale factor (0.9996 to 1.0004) is
// not applied.

#include <memory>
#include <optional>
#include <string>

#include "geometry/vec3.hpp"

namespace GeographicLib {
class LocalCartesian;
}

namespace daylit {

struct GeographicPosition {
  double latitude_deg = 0;
  double longitude_deg = 0;
  double height_m = 0;  // above the WGS84 ellipsoid
};

// The UTM grid a site was given in.
struct UtmGrid {
  int zone = 0;  // 1..60
  bool northern = true;
  double origin_easting_m = 0;
  double origin_northing_m = 0;
  double convergence_deg = 0;  // γ at the origin: bearing of grid north, clockwise from true north
  double scale = 1;            // point scale k of the projection at the origin
};

// Immutable; cheap to copy (the GeographicLib projection is shared).
class Site {
 public:
  // Origin at latitude_deg ∈ (−90, 90), longitude_deg ∈ [−180, 180], ellipsoidal height
  // elevation_m; north_deg as in the header comment. ground_z_m: the model z of the ground at the
  // origin, on which context buildings stand. Throws daylit::Error for values out of range.
  static Site geographic(double latitude_deg, double longitude_deg, double elevation_m, double north_deg,
                         double ground_z_m = 0);
  // Origin at (easting, northing) of UTM zone 1..60 in the given hemisphere, for a model whose +x
  // and +y are grid east and north; north_deg = −γ (GeographicLib::UTMUPS::Reverse). Throws
  // daylit::Error for a zone or coordinates outside the UTM ranges (GeographicLib's message).
  static Site utm(int zone, bool northern, double easting_m, double northing_m, double elevation_m,
                  double ground_z_m = 0);

  const GeographicPosition& origin() const noexcept { return origin_; }
  double north_deg() const noexcept { return north_deg_; }
  double ground_z_m() const noexcept { return ground_z_m_; }
  const std::optional<UtmGrid>& utm_grid() const noexcept { return utm_; }

  // Model coordinates of a WGS84 point: LocalCartesian::Forward, then the turn by north_deg.
  // Accurate to GeographicLib's LocalCartesian (nanometres near the origin).
  Vec3 model_from_wgs84(double latitude_deg, double longitude_deg, double height_m) const;
  // The inverse: the turn back, then LocalCartesian::Reverse.
  GeographicPosition wgs84_from_model(const Vec3& model) const;

  // Vectors (not points) between the model frame and ENU at the origin: a rotation about z.
  Vec3 model_from_enu(const Vec3& enu) const noexcept;
  Vec3 enu_from_model(const Vec3& model) const noexcept;

  // Unit vectors of the horizontal directions true north and east at the origin, in the model frame.
  Vec3 true_north_in_model() const noexcept { return north_; }
  Vec3 east_in_model() const noexcept { return east_; }
  // Unit vector towards a point of the sky given by its azimuth (degrees clockwise from true
  // north, as for the sun) and altitude (degrees above the horizontal), in the model frame.
  Vec3 model_direction(double azimuth_deg, double altitude_deg) const noexcept;

  // One line for notices and summaries, e.g. "41.3925° N 2.1640° E, 100 m; true north 45° clockwise from +y".
  std::string description() const;

 private:
  Site() = default;
  void set_north(double north_deg);

  GeographicPosition origin_;
  double north_deg_ = 0;
  double ground_z_m_ = 0;
  Vec3 north_{0, 1, 0}, east_{1, 0, 0};
  std::optional<UtmGrid> utm_;
  std::shared_ptr<const GeographicLib::LocalCartesian> enu_;
};

// A site description in JSON, one of:
//   {"latitude_deg": φ, "longitude_deg": λ, "elevation_m": h, "north_deg": n}      (north_deg optional, 0)
//   {"utm": {"zone": 32, "northern": true}, "origin_easting_m": E, "origin_northing_m": N, "elevation_m": h}
// both with an optional "ground_z_m" (default 0) and optional "name"/"description"/"comment"
// strings. Any other key, a missing or mistyped field, or a value out of range is an error naming
// the file and the field; a JSON syntax error names the file and line.
Site parse_site_json(const std::string& text, const std::string& name);
Site read_site_file(const std::string& path);

}  // namespace daylit
