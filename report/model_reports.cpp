#include "report/model_reports.hpp"

namespace daylit::cli {

nlohmann::json site_json(const Site& site, const std::string& path) {
  const GeographicPosition& o = site.origin();
  nlohmann::json j = {{"path", path},
                      {"latitude_deg", o.latitude_deg},
                      {"longitude_deg", o.longitude_deg},
                      {"elevation_m", o.height_m},
                      {"north_deg", site.north_deg()},
                      {"ground_z_m", site.ground_z_m()}};
  if (const auto& utm = site.utm_grid())
    j["utm"] = {{"zone", utm->zone},
                {"northern", utm->northern},
                {"origin_easting_m", utm->origin_easting_m},
                {"origin_northing_m", utm->origin_northing_m},
                {"meridian_convergence_deg", utm->convergence_deg}};
  return j;
}

nlohmann::json context_json(const ContextPlacement& context, const std::string& path) {
  nlohmann::json j = {{"path", path},
                      {"buildings_read", context.read},
                      {"placed", context.placed},
                      {"faces", context.faces},
                      {"left_out",
                       {{"holding_the_model", context.enclosing_model},
                        {"below_the_horizon", context.below_horizon},
                        {"behind_the_apertures", context.behind_apertures},
                        {"smaller_than_min_angle", context.too_small}}},
                      {"min_angle_deg", context.min_angular_size_deg},
                      {"sc_change_bound_percent", context.sc_change_bound_percent},
                      {"rule", context.rule}};
  if (context.sun_beam_kept) j["kept_in_sun_beam"] = context.kept_in_sun_beam;
  return j;
}

nlohmann::json scene_json(const Scene& scene, const VisibilityEngine& engine) {
  return {{"occluders", scene.occluders.size()},
          {"occluder_pieces", engine.occluder_piece_count()},
          {"apertures", scene.apertures.size()},
          {"aperture_pieces", engine.aperture_piece_count()},
          {"notices", scene.notices}};
}

nlohmann::json counters_json(const VisibilityCounters& c) {
  return {
      {"sensor_aperture_pairs", c.pairs},
      {"pairs_not_facing", c.pairs_not_facing},
      {"pairs_without_clipping", c.pairs_unobstructed + c.pairs_not_facing + c.pairs_covered},
      {"pairs_unobstructed", c.pairs_unobstructed},
      {"pairs_covered", c.pairs_covered},
      {"pairs_clipped", c.pairs_clipped},
      {"pairs_clipped_in_certified_intervals", c.pairs_clipped - c.pairs_rational},
      {"pairs_needing_exact_rationals", c.pairs_rational},
      {"occluder_pieces_culled_by_boxes", c.occluders_box_culled},
      {"occluder_pieces_tested_exactly", c.occluders_tested},
      {"occluder_pieces_clipped", c.occluders_clipped},
      {"other_panes_beyond_the_aperture", c.panes_beyond},
      {"other_panes_in_front_of_the_aperture", c.panes_in_front},
      {"panes_crossing_the_aperture_plane", c.panes_crossing},
  };
}


nlohmann::json en17037_json(const En17037Assessment& a) {
  nlohmann::json levels = nlohmann::json::array();
  for (const auto& l : a.levels)
    levels.push_back({{"level", l.name},
                      {"target_lux", l.target_lux},
                      {"minimum_target_lux", l.minimum_target_lux},
                      {"target_df_percent", l.target_df},
                      {"minimum_target_df_percent", l.minimum_target_df},
                      {"share_at_target", l.share_at_target},
                      {"share_at_minimum_target", l.share_at_minimum_target},
                      {"met", l.met}});
  return {{"source",
           "EN 17037:2018 Table A.1 (openings in vertical and inclined surfaces): target over 50 % and minimum target "
           "over 95 % of the reference plane; daylight-factor targets 100 E / E_v,d,med (A.3); shares of sensors "
           "(equal cells); the sky component only unless reflections are computed"},
          {"median_diffuse_lux", a.median_diffuse_lux},
          {"levels", levels},
          {"level_met", a.level_met}};
}

nlohmann::json breeam_json(const BreeamHea01& b, const std::string& df_is) {
  const auto value = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  return {{"source",
           "BREEAM UK New Construction 2018 Hea 01 with CIBSE LG10: average daylight factor, minimum point daylight "
           "factor and uniformity (minimum over average) over the sensors outside the perimeter band (closer than "
           "perimeter_band_m in plan to a wall, or to anything else cut at the grid's height); BREEAM's criteria per "
           "building type are read against these; null where every sensor is in the band"},
          {"df_percent_is", df_is},
          {"perimeter_band_m", b.band},
          {"sensors", b.sensors},
          {"sensors_in_perimeter_band", b.sensors_in_band},
          {"average_df_percent", value(b.average_df)},
          {"minimum_df_percent", value(b.minimum_df)},
          {"uniformity_min_over_average", value(b.uniformity)}};
}

}  // namespace daylit::cli
