#include "soft/split_sampler.h"

#include <algorithm>
#include <cmath>

namespace shadowvol::soft {

std::size_t SplitPlaneSampler::cheapest(const Target& target, std::span<const glm::vec4> always,
                                        std::span<const glm::vec4> zfail_only, DepthBounds bounds,
                                        std::span<const glm::vec4> planes, Counters& counters) {
  if (planes.size() < 2) return 0;
  constexpr int s = kSampleStride, offset = kSampleStride / 2;  // the sampled tile of a block
  const int cols = (target.tiles_x + s - 1) / s, rows = (target.tiles_y + s - 1) / s;
  if (samples_.width != cols || samples_.height != rows) samples_ = Target(cols, rows);
  const std::size_t n = static_cast<std::size_t>(cols) * rows;
  tile_.assign(n, -1);
  middle_.assign(n, 0.0f);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int tx = s * c + offset, ty = s * r + offset;
      if (tx >= target.tiles_x || ty >= target.tiles_y) continue;
      const std::size_t t = static_cast<std::size_t>(ty) * target.tiles_x + tx;
      const TileDepth& depth = target.tile_depth[t];
      if (depth.zmax < bounds.zmin || depth.zmin > bounds.zmax) continue;  // free either way
      tile_[static_cast<std::size_t>(r) * cols + c] = static_cast<std::int64_t>(t);
      // Where split_rule tests the tile.
      middle_[static_cast<std::size_t>(r) * cols + c] = 0.5f * (depth.zmin + depth.zmax);
    }

  // Map clip space so that sample pixel (c, r)'s centre lands where the centre of tile
  // (s c + offset, s r + offset) is in the frame: in window units, frame x = 8 (s c + offset) + 4
  // at sample x = c + 1/2; an affine map of NDC, so linear in clip space (x' = a x + b w).
  const double k = double(kTileSize) * s, lead = double(kTileSize) * offset + kTileSize / 2.0;
  const double w = target.width, h = target.height;
  const float ax = float(w / (k * cols)), bx = float(((w - 2.0 * lead) / k + 1.0) / cols - 1.0);
  const float ay = float(h / (k * rows)), by = float(1.0 - ((h - 2.0 * lead) / k + 1.0) / rows);
  triangles_.assign(always.begin(), always.end());
  triangles_.insert(triangles_.end(), zfail_only.begin(), zfail_only.end());
  for (glm::vec4& v : triangles_) {
    v.x = ax * v.x + bx * v.w;
    v.y = ay * v.y + by * v.w;
  }
  ones_.assign(triangles_.size() / 3, 1);
  const std::span<const glm::vec4> mapped(triangles_);
  // z-pass counts the sides in front of a tile's surfaces; z-fail the sides and caps behind.
  // A sample set aside lies in front of every fragment for the first, behind every one for the
  // second, so that the rasterizer culls it.
  count_layers(mapped.first(always.size()), CountRule::cover, 2.0f, zpass_layers_, counters);
  count_layers(mapped, CountRule::behind, -1.0f, zfail_layers_, counters);

  // A plane costs the z-fail layers of every sample plus, where it picks z-pass, the difference:
  // only the samples where the two rules differ tell the planes apart (a small part's volume
  // leaves most at 0 and 0).
  telling_.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (tile_[i] >= 0 && zpass_layers_[i] != zfail_layers_[i]) telling_.push_back(i);
  std::size_t best = 0;
  std::int64_t best_cost = 0;
  for (std::size_t p = 0; p < planes.size(); ++p) {
    std::int64_t cost = 0;  // over z-fail everywhere
    for (const std::size_t i : telling_) {
      const int tx = static_cast<int>(tile_[i] % target.tiles_x);
      const int ty = static_cast<int>(tile_[i] / target.tiles_x);
      if (split_rule(target, tx, ty, planes[p]) == CountRule::zpass)
        cost += zpass_layers_[i] - zfail_layers_[i];
    }
    if (p == 0 || cost < best_cost) best_cost = cost, best = p;
  }
  return best;
}

void SplitPlaneSampler::count_layers(std::span<const glm::vec4> triangles, CountRule rule,
                                     float set_aside, std::vector<std::int32_t>& layers,
                                     Counters& counters) {
  for (std::size_t i = 0; i < tile_.size(); ++i)
    samples_.depth[i] = tile_[i] < 0 ? set_aside : middle_[i];
  samples_.update_tile_depth();
  // Depth bounds wider than any depth: the samples set aside are left to the depth test.
  draw_counts(samples_, triangles, std::span(ones_).first(triangles.size() / 3), rule, counters,
              {-2.0f, 2.0f});
  layers.assign(samples_.count.begin(), samples_.count.end());
  std::fill(samples_.count.begin(), samples_.count.end(), 0);
}

}  // namespace shadowvol::soft
