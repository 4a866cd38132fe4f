#include "accel/continuous_clamping.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace shadowvol {
namespace {

// Sorts `order` by key[order[k]] with local interchanges: O(n + swaps), and an order that was
// sorted for the last frame's keys needs few of them (temporal coherence).
std::uint64_t insertion_sort(std::vector<std::uint32_t>& order, const std::vector<double>& key) {
  std::uint64_t swaps = 0;
  for (std::size_t i = 1; i < order.size(); ++i) {
    const std::uint32_t e = order[i];
    std::size_t j = i;
    for (; j > 0 && key[order[j - 1]] > key[e]; --j) order[j] = order[j - 1];
    swaps += i - j;
    order[j] = e;
  }
  return swaps;
}

}  // namespace

void ContinuousClamping::find_pairs(std::span<const Item> items, double margin, Stats& stats) {
  const std::size_t n = items.size();
  // A different set of sub-objects: sorted afresh, O(n log n); else by insertion from last frame's.
  const bool fresh = by_u_.size() != 2 * n;
  auto sort = [&](std::vector<std::uint32_t>& order, std::size_t size) {
    if (fresh) {
      order.resize(size);
      std::iota(order.begin(), order.end(), 0u);
      std::stable_sort(order.begin(), order.end(),
                       [&](std::uint32_t a, std::uint32_t b) { return key_[a] < key_[b]; });
      return;
    }
    stats.swaps += insertion_sort(order, key_);
  };
  auto box = [&](std::uint32_t e) -> const LightViews::LightBox& {
    return e % 2 ? items[e / 2].receiver : items[e / 2].caster;
  };
  auto in_play = [&](std::uint32_t e) {
    return e % 2 ? items[e / 2].receives : items[e / 2].casts;
  };
  key_.resize(2 * n);
  for (std::uint32_t e = 0; e < 2 * n; ++e) key_[e] = in_play(e) ? box(e).u0 : INFINITY;
  sort(by_u_, 2 * n);
  key_.resize(n);
  for (std::size_t i = 0; i < n; ++i) key_[i] = items[i].receives ? items[i].receiver.z0 : INFINITY;
  sort(by_depth_, n);
  rank_.resize(n);
  for (std::size_t k = 0; k < n; ++k) rank_[by_depth_[k]] = static_cast<std::uint32_t>(k);

  // The sweep along u: each entry meets the open ones whose rectangles it starts within.
  active_.clear();
  pairs_.clear();
  for (const std::uint32_t e : by_u_) {
    if (!in_play(e)) break;  // the rest are out of play too: sorted last
    const LightViews::LightBox& b = box(e);
    for (std::size_t k = 0; k < active_.size();) {
      if (box(active_[k]).u1 < b.u0) {  // closed before this one starts
        active_[k] = active_.back();
        active_.pop_back();
        continue;
      }
      const std::uint32_t a = active_[k++];
      if (a % 2 == e % 2) continue;  // two casters, or two receivers
      const std::uint32_t caster = (e % 2 ? a : e) / 2, receiver = (e % 2 ? e : a) / 2;
      const LightViews::LightBox& t = items[caster].caster;
      const LightViews::LightBox& s = items[receiver].receiver;
      if (t.v0 <= s.v1 && s.v0 <= t.v1 && s.z1 + margin >= t.z0 - margin)
        pairs_.emplace_back(rank_[receiver], caster);
    }
    active_.push_back(e);
  }
  stats.pairs += pairs_.size();
  // By the receiver's place in depth, stably (a counting sort: O(n + pairs)).
  std::vector<std::uint32_t>& starts = active_;  // the sweep is done with it
  starts.assign(n + 1, 0);
  for (const auto& p : pairs_) ++starts[p.first + 1];
  for (std::size_t k = 0; k < n; ++k) starts[k + 1] += starts[k];
  sorted_.resize(pairs_.size());
  for (const auto& p : pairs_) sorted_[starts[p.first]++] = p;
  pairs_.swap(sorted_);
}

}  // namespace shadowvol
