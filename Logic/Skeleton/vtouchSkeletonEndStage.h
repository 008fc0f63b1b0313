// Private to Logic/Skeleton: stage 6 of vtouch::VoxelCoder, the paths' free ends.
#pragma once

#include "vtouchSkeletonDraft.h"
#include "vtouchSkeletonVoxelGrid.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace vtouch
{
namespace skeleton
{

/// Where the component's paths end (back-tracing starts at the apex of each tip; Yi & Hayward §3.1
/// want the line that connects the two ends of each branch, whose centre ends short of the apex;
/// the rules are the project's, Docs/CENTERLINES.md): stubs beyond the last junction are cut, and a
/// vessel that ends inside the volume ends at its cap's centre.
///
/// Input: the grid (its mask) and the draft's paths from `firstPath`, with their closedEnd flags.
/// Output: the same paths, shortened at their free ends (junction points renumbered).
class EndStage
{
public:
  /// `ss_mm`: the SS code (VoxelCodes::ss, by the mask's rank), for the root's own end (see
  /// pruneStubEnds); null: every end is judged alike.
  EndStage(const VoxelGrid& grid,
    double minimumBranchLength,
    SkeletonDraft& draft,
    std::size_t firstPath,
    const std::vector<float>* ss_mm = nullptr);

  /// pruneStubEnds(), then trimClosedEnds().
  void run();

  /// A free path end that goes on less than a spur's length (minimumBranchLength local radii)
  /// beyond the outermost point another path attaches to is a spur of its own: cut at that point.
  /// Where the second front of a ring is attached next to the first trace's start, the start's
  /// last voxels would otherwise stick out as an end point of a vessel that has none.
  /// The root's own end (its voxel in the SS code's first band: the seed the user picked, or the
  /// automatic root's end cap) is cut only when it goes on less than one local radius (it lies
  /// inside the junction's lumen): the network reaches the point it was grown from, where a
  /// branch (a blob, a side vessel) joins the root's vessel within a spur's length of it (128^3
  /// seed 28, session 19: the root's first 9.4 voxels, radius 4, were cut). The field is the
  /// single run's on every rank (globalSs_mm), so a distributed run keeps the same ends.
  void pruneStubEnds();

  /// A vessel that ends inside the volume ends in a cap; its centerline ends at the cap's centre,
  /// one radius back from the apex, where the medial axis would go on to the apex. Points that
  /// other paths attach to are kept.
  void trimClosedEnds();

  struct EndCap
  {
    std::size_t trim = 0; ///< points to drop at the end
    /// Where the new end point goes (on the axis, at the cap's centre), when the cap was measured.
    std::optional<Point_mm> centre_mm;
  };
  /// The cap at one free end of `path` (its tail when `fromTail`); `pinned` marks the path's
  /// points that other paths attach to. See trimClosedEnds().
  EndCap measureEndCap(const RawSkeletonPath& path,
    bool fromTail,
    const std::vector<char>& pinned) const;

  /// The vessel mask (1 vessel, 0 background) interpolated trilinearly at `p_mm` (scaled index
  /// frame); -1 where the interpolation needs a voxel outside the volume.
  double maskValueAt(const Point_mm& p_mm) const;
  /// Distance (mm) from `from` along the unit direction `dir` to the wall, where maskValueAt()
  /// falls below one half (steps of a quarter of the smallest voxel side, interpolated between
  /// them); < 0 when `from` is not inside, or the march leaves the volume or goes beyond
  /// `limit_mm` first.
  double distanceToWall(const Point_mm& from, const Point_mm& dir, double limit_mm) const;

private:
  const VoxelGrid& grid;
  double minimumBranchLength; // in local radii
  SkeletonDraft& draft;
  std::size_t firstPath;           // the component's first path
  const std::vector<float>* ss_mm; // the SS code by mask rank, or null
};

} // namespace skeleton
} // namespace vtouch
