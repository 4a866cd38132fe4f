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
          {"light_view_size", options.light_view_size}};
}

nlohmann::json culling_json(const FrameStats& s, int per) {
  return {{"casters_culled_in_shadow", static_cast<double>(s.casters_culled_in_shadow) / per},
          {"casters_culled_unseen", static_cast<double>(s.casters_culled_unseen) / per},
          {"queries", static_cast<double>(s.cull_queries) / per},
          {"light_views", static_cast<double>(s.light_views) / per},
          {"cull_ms", s.ms_cull / per}};
}

nlohmann::json to_json(const raster::Counters& c, std::uint64_t per) {
  return {{"triangles", c.triangles_in / per},
          {"tiles_touched", c.tiles_touched / per},
          {"tiles_skipped", c.tiles_skipped / per},
          {"pixels_processed", c.pixels_processed / per},
          {"count_updates", c.count_updates / per}};
}

}  // namespace shadowvol
