// Private to Logic/Skeleton: the clusters of a voxel-coding run and their graph.
#pragma once

#include "vtouchSkeletonVoxelGrid.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace vtouch
{
namespace skeleton
{

/// A connected part of one SS band (Zhou & Toga's cluster; Yi & Hayward §3.1: a slab of the vessel
/// across its axis). Written by ClusterStage, except `path` / `point`, which SkeletonTracer sets
/// when a trace first passes through the cluster.
struct Cluster
{
  std::uint32_t band = 0;
  std::uint32_t count = 0;
  double sum[3] = { 0.0, 0.0, 0.0 }; // of the voxel centres, mm
  float maxBs = 0.0F;                // mm
  std::vector<std::uint32_t> lower;  // adjacent clusters of lower bands
  std::vector<std::uint32_t> higher; // adjacent clusters of higher bands
  int path = -1;                     // path and point that represent this cluster
  int point = -1;
  std::uint32_t bestVoxel = 0;  // voxel of largest BS code
  bool onBorder = false;        // touches the volume border (an end cut by the field of view)
  std::uint32_t firstVoxel = 0; // its voxel of smallest linear index
  std::int64_t indexSum[3] = { 0, 0, 0 }; // of the voxel indices (exact, any order)
  Point_mm centroid() const { return { sum[0] / count, sum[1] / count, sum[2] / count }; }
};

/// The clusters, numbered in SS order, and each vessel voxel's cluster.
struct ClusterGraph
{
  static constexpr std::uint32_t kLabelled = 0x80000000U;

  std::vector<Cluster> clusters;
  /// Per vessel voxel (rank): union-find parents while ClusterStage builds, then
  /// kLabelled | cluster.
  std::vector<std::uint32_t> label;

  std::uint32_t clusterOfRank(std::uint32_t r) const { return label[r] & ~kLabelled; }

  static void addUnique(std::vector<std::uint32_t>& v, std::uint32_t c)
  {
    if (std::find(v.begin(), v.end(), c) == v.end())
    {
      v.push_back(c);
    }
  }
};

} // namespace skeleton
} // namespace vtouch
