// Private to Logic/Skeleton: the rule that moves the automatic root to the thickest end of a tree
// (ClusterStage::thickerRoot), written once so that the single run and the distributed run
// (vtouch::DistributedRootChoice, issue 19 item 2) read the same cluster graph the same way.
#pragma once

#include "vtouchSkeletonClusterGraph.h"
#include "vtouchSparseVesselMask.h"

#include <cstdint>
#include <optional>
#include <vector>

namespace vtouch
{
namespace skeleton
{

/// Each cluster's place in the *key order*: by the SS code of its voxel of smallest linear index
/// (Cluster::firstVoxel), ties by that index. `ss` is indexed by `mask` rank.
///
/// Project rule (issue 19 item 2): the rule below used to read the clusters' numbers, which
/// follow the SS queue's visiting order (last in first out inside a bucket): an order no
/// distributed run reproduces. The key order is that order up to the ties inside one bucket, and
/// is the order a coder given a global SS field numbers its clusters in (VoxelCoder's
/// codeGlobalField sorts by SS, ties by index). It only decides ties (of voxel count, of
/// thickness); the six outputs of hash_builtin_centerlines.py are unchanged by it.
std::vector<std::uint32_t> clusterKeyOrder(const std::vector<Cluster>& clusters,
  const std::vector<float>& ss,
  const SparseVesselMask& mask);

/// The end cluster to move the root to, or none (Yi & Hayward §3.1 root the SS code at an
/// extremity; any extremity gives a valid code, but back-tracing toward a thin end cuts the
/// corners of the bifurcations, so the code is rooted at the thickest end, the inflow trunk).
/// `clusters`: a component's cluster graph (band, count, maxBs, lower, higher read);
/// `position`: each cluster's place in the key order (clusterKeyOrder); the root's cluster is
/// the first (the only cluster of band 0: every other voxel is at least one band from the root).
///
/// Thickness of an end: the largest BS code over it and kBands clusters walked down from it
/// (each step to the lower neighbour of most voxels, ties to the first in key order: the end
/// cluster itself is a cap whose BS is small). The root's end is measured walking up the same
/// way (a ball around a rounded cap's apex would see only the cap, and a vessel of one calibre
/// would then always be re-rooted). The chosen end: of band > kBands, no higher neighbour, the
/// thickest (ties to the first in key order), when it is more than kFactor times the root's
/// (project rule: 20 %, "clearly thicker", so that a tree of one calibre keeps its root).
std::optional<std::uint32_t> thickerEnd(const std::vector<Cluster>& clusters,
  const std::vector<std::uint32_t>& position);

/// The walk length of the thickness, bands.
constexpr std::uint32_t kThickerEndBands = 8;
/// How much thicker an end must be to move the root there.
constexpr float kThickerEndFactor = 1.2F;

} // namespace skeleton
} // namespace vtouch
