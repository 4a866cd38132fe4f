// shadowvol render: frames as JSON, the one form every tool and benchmark prints them in.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

#include "raster/raster.h"
#include "render/frame.h"

namespace shadowvol {

// width, height, method, generator, extrusion, split_planes, split_parts, cull, clamp,
// occlusion, slices and light_view_size, by name.
nlohmann::json to_json(const RenderOptions& options);
// The rasterizer's work: triangles, tiles_touched, tiles_skipped, pixels_processed and
// count_updates, each divided by `per` (the frames they were added over).
nlohmann::json to_json(const raster::Counters& counters, std::uint64_t per = 1);
// CC shadow volumes' figures (FrameStats), each divided by `per`: casters_culled_in_shadow,
// casters_culled_unseen, sub_objects_culled, queries (the culling's and the slices'), light_views,
// cull_ms; volumes_clamped, volumes_clamped_away, volume_segments, clamp_pairs, clamp_swaps,
// intervals_merged_by_cost, clamp_ms; with `fill`, fill and stencil_writes (which
// RenderOptions::count_fill must have asked for); v_ms_per_vertex and r_ms_per_pixel where the
// backend measured them.
nlohmann::json cc_json(const FrameStats& stats, int per = 1, bool fill = true);
// Hierarchical occlusion culling's figures, each divided by `per`, as the object under the key
// "occlusion": nodes_visited, queries, queries_waited, objects_culled, volumes_culled,
// objects_drawn, volumes_drawn, bvh_rebuilt, bvh_ms and shadow_queries_ms.
nlohmann::json occlusion_json(const FrameStats& stats, int per = 1);

}  // namespace shadowvol
