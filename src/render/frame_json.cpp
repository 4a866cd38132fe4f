#include "render/frame_json.h"

#include <string>

namespace shadowvol {

nlohmann::json to_json(const RenderOptions& options) {
  return {{"width", options.width},
          {"height", options.height},
          {"method", std::string(to_string(options.method))},
          {"generator", std::string(to_string(options.generator))},
          {"extrusion", std::string(to_string(options.extrusion))},
          {"split_planes", std::string(to_string(options.split_planes))},
          {"split_parts", std::string(to_string(options.split_parts))},
          {"cull", std::string(to_string(options.cull))},
          {"clamp", std::string(to_string(options.clamp))},
          {"occlusion", std::string(to_string(options.occlusion))},
          {"slices", options.slices},
          {"light_view_size", options.light_view_size}};
}

nlohmann::json cc_json(const FrameStats& s, int per, bool fill) {
  auto each = [per](double total) { return total / per; };
  nlohmann::json out{
      {"casters_culled_in_shadow", each(s.casters_culled_in_shadow)},
      {"casters_culled_unseen", each(s.casters_culled_unseen)},
      {"sub_objects_culled", each(s.sub_objects_culled)},
      {"queries", each(static_cast<double>(s.cull_queries + s.slice_queries))},
      {"light_views", each(s.light_views)},
      {"cull_ms", each(s.ms_cull)},
      {"volumes_clamped", each(s.volumes_clamped)},
      {"volumes_clamped_away", each(s.volumes_clamped_away)},
      {"volume_segments", each(static_cast<double>(s.volume_segments))},
      {"clamp_pairs", each(static_cast<double>(s.clamp_pairs))},
      {"clamp_swaps", each(static_cast<double>(s.clamp_swaps))},
      {"intervals_merged_by_cost", each(static_cast<double>(s.intervals_merged_by_cost))},
      {"clamp_ms", each(s.ms_clamp)}};
  if (fill) {
    out["fill"] = each(static_cast<double>(s.fill));
    out["stencil_writes"] = each(static_cast<double>(s.stencil_writes));
  }
  out["volumes_out_of_range"] = each(s.volumes_out_of_range);
  out["scissor_pixels_saved"] = each(static_cast<double>(s.scissor_pixels_saved));
  if (s.volume_costs.measured()) {
    out["v_ms_per_vertex"] = s.volume_costs.ms_per_vertex;
    out["r_ms_per_pixel"] = s.volume_costs.ms_per_pixel;
  }
  return out;
}

nlohmann::json occlusion_json(const FrameStats& s, int per) {
  auto each = [per](double total) { return total / per; };
  return {"occlusion",
          {{"nodes_visited", each(static_cast<double>(s.nodes_visited))},
           {"queries", each(static_cast<double>(s.queries))},
           {"queries_waited", each(static_cast<double>(s.queries_waited))},
           {"objects_culled", each(s.objects_culled)},
           {"volumes_culled", each(s.volumes_culled)},
           {"objects_drawn", each(s.objects_drawn)},
           {"volumes_drawn", each(s.volumes_drawn)},
           {"bvh_rebuilt", each(s.bvh_rebuilt)},
           {"bvh_ms", each(s.ms_bvh)},
           {"shadow_queries_ms", each(s.ms_occlusion)}}};
}

nlohmann::json to_json(const raster::Counters& c, std::uint64_t per) {
  return {{"triangles", c.triangles_in / per},
          {"block_rows_skipped", c.block_rows_skipped / per},
          {"tiles_touched", c.tiles_touched / per},
          {"tiles_skipped", c.tiles_skipped / per},
          {"pixels_processed", c.pixels_processed / per},
          {"count_updates", c.count_updates / per}};
}

}  // namespace shadowvol
