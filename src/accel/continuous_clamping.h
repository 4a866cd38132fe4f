// shadowvol accel: continuous shadow clamping (Lloyd, Wendt, Govindaraju and Manocha 2004, "CC
// Shadow Volumes", §3.2.1): per caster, the intervals of depth along the light's view that hold
// receivers, from boxes in light space.
//
// Owns: the overlap tests and the occupied intervals of one light view, and what it keeps from
// frame to frame (temporal coherence: the sweep-and-prune order).
//   - Overlap: a receiver S may lie in the volume of a caster T when their rectangles on the
//     light's image plane overlap and S's farthest depth lies beyond T's nearest. The rectangles'
//     starts along u are kept sorted by insertion sort with local interchanges (sweep and prune,
//     Cohen, Lin, Manocha and Ponamgi 1995), so a frame whose boxes moved a little sorts in
//     O(n + swaps); a sweep along that order finds the pairs overlapping in u, then v and depth.
//   - Intervals: each caster starts with its own depths (self-shadowing); the receivers are
//     taken by their nearest depth, kept sorted the same way, so only a caster's last interval
//     changes: it holds the receiver (case 1), is extended to it (case 2), or a new interval
//     starts at it (case 3), unless the new interval would cost more to draw than the gap it
//     skips (V > R: V = (2C + 2S) v, the caps' and silhouette's vertices at the measured cost per
//     vertex; R = A r, the gap's area on screen at the measured cost per pixel), when it is
//     merged as in case 2.
// Every depth is widened by `margin` on both sides, so that a receiver lies strictly inside its
// interval, with room for the float planes the segments are cut by (core/volume.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "accel/light_views.h"

namespace shadowvol {

// An interval of depth in double; begin -inf: from the caster itself.
struct Interval {
  double begin = 0.0, end = 0.0;
};

class ContinuousClamping {
 public:
  // One sub-object in the view: the box of what it casts (where `casts`: its volume is clamped
  // here) and of what it receives (where `receives`: a potential receiver touching the view).
  struct Item {
    LightViews::LightBox caster{}, receiver{};
    bool casts = false, receives = false;
    // V's vertices for this caster, 2C + 2S (the caps' and the silhouette's).
    double interval_vertices = 0.0;
  };
  struct Stats {
    std::uint64_t pairs = 0;           // caster-receiver pairs whose boxes overlap
    std::uint64_t swaps = 0;           // interchanges of the insertion sorts (temporal coherence)
    std::uint64_t merged_by_cost = 0;  // new intervals not made because V > R
  };

  // The occupied intervals of every casting item into intervals[offsets[i] .. offsets[i + 1])
  // (none for the others), sorted. `gap_cost(i, from, to)`: R for caster i's gap between depths
  // `from` and `to`; `vertex_cost`: v. Items must keep their order from frame to frame (the same
  // sub-object at the same index) for the sort to stay coherent; a different count starts anew.
  template <class GapCost>
  void clamp(std::span<const Item> items, double margin, double vertex_cost, GapCost&& gap_cost,
             std::vector<std::uint32_t>& offsets, std::vector<Interval>& intervals, Stats& stats) {
    find_pairs(items, margin, stats);
    clamp_pairs(items, margin, offsets, intervals, stats, [&](std::size_t i, const Interval& gap) {
      return items[i].interval_vertices * vertex_cost > gap_cost(i, gap.begin, gap.end);
    });
  }

 private:
  void find_pairs(std::span<const Item> items, double margin, Stats& stats);
  template <class TooCostly>
  void clamp_pairs(std::span<const Item> items, double margin, std::vector<std::uint32_t>& offsets,
                   std::vector<Interval>& intervals, Stats& stats, TooCostly&& too_costly);

  // Entries 2i (caster i) and 2i + 1 (receiver i), sorted by the start of their rectangle in u;
  // the receivers sorted by nearest depth. Kept between frames.
  std::vector<std::uint32_t> by_u_, by_depth_;
  std::vector<double> key_;            // scratch: each entry's sort key
  std::vector<std::uint32_t> active_;  // the sweep's open entries
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs_, sorted_;  // (receiver rank, caster)
  std::vector<std::uint32_t> rank_;          // per receiver: its place by depth
  std::vector<std::vector<Interval>> open_;  // per caster: its intervals so far
};

template <class TooCostly>
void ContinuousClamping::clamp_pairs(std::span<const Item> items, double margin,
                                     std::vector<std::uint32_t>& offsets,
                                     std::vector<Interval>& intervals, Stats& stats,
                                     TooCostly&& too_costly) {
  open_.resize(items.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    open_[i].clear();
    // Its own depths: the first interval starts at the caster.
    if (items[i].casts) open_[i].push_back({-INFINITY, items[i].caster.z1 + margin});
  }
  // Receivers nearest first, so that only the last interval of a caster ever changes.
  for (const auto& [rank, caster] : pairs_) {
    const LightViews::LightBox& s = items[by_depth_[rank]].receiver;
    std::vector<Interval>& open = open_[caster];
    Interval& last = open.back();
    const double begin = s.z0 - margin, end = s.z1 + margin;
    if (begin <= last.end) {  // cases 1 and 2: holds it, or extended to it
      last.end = std::max(last.end, end);
    } else if (too_costly(caster, Interval{last.end, begin})) {  // V > R: merged as in case 2
      last.end = end;
      ++stats.merged_by_cost;
    } else {  // case 3: a new interval
      open.push_back({begin, end});
    }
  }
  offsets.assign(items.size() + 1, 0);
  intervals.clear();
  for (std::size_t i = 0; i < items.size(); ++i) {
    intervals.insert(intervals.end(), open_[i].begin(), open_[i].end());
    offsets[i + 1] = static_cast<std::uint32_t>(intervals.size());
  }
}

}  // namespace shadowvol
