// shadowvol render: frames as JSON, the one form every tool and benchmark prints them in.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

#include "raster/raster.h"
#include "render/frame.h"

namespace shadowvol {

// width, height, method, generator, extrusion, split_planes, split_parts, cull and
// light_view_size, by name.
nlohmann::json to_json(const RenderOptions& options);
// The rasterizer's work: triangles, tiles_touched, tiles_skipped, pixels_processed and
// count_updates, each divided by `per` (the frames they were added over).
nlohmann::json to_json(const raster::Counters& counters, std::uint64_t per = 1);
// CC culling's figures (FrameStats): casters_culled_in_shadow, casters_culled_unseen, queries,
// light_views and cull_ms, each divided by `per`.
nlohmann::json culling_json(const FrameStats& stats, int per = 1);

}  // namespace shadowvol
