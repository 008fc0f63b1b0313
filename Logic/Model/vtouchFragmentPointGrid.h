// A uniform grid over the points of skeleton fragments, for the stitcher's neighbour queries
// (issue 19, item 2). Plain C++.
#pragma once

#include "vtouchSkeletonFragment.h"

#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

namespace vtouch
{

/// Buckets the points of a list of fragments (or paths) by cells of `cell_mm`; `visit` calls a
/// function with every point within `reach_mm` (<= cell_mm) of a position.
class FragmentPointGrid
{
public:
  /// A point: fragment `fragment`'s point `point`.
  struct Item
  {
    std::size_t fragment;
    std::size_t point;
  };
  explicit FragmentPointGrid(double cell_mm);
  void add(const Vec3& position_World_mm, Item item);
  /// Calls `f(item)` for every item whose cell is within one cell of `position_World_mm`'s (the
  /// caller measures the distance).
  void visitNear(const Vec3& position_World_mm, const std::function<void(const Item&)>& f) const;

private:
  std::int64_t key(long i, long j, long k) const;
  long cellOf(double v) const;
  double cell_mm_;
  std::unordered_map<std::int64_t, std::vector<Item>> cells_;
};

} // namespace vtouch
