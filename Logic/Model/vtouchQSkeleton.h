// The Q-skeleton of Yi & Hayward: a network of connected, one-voxel-thick centerline paths.
// Plain C++ (no ITK, no VTK): produced by Logic/Skeleton, read by Logic/Haptics and the VTK facade.
#pragma once

#include "vtouchVector.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vtouch
{

/// Point classification, the `BifurcationLabel` array of the VesselCenterline output.
enum class PointLabel : std::uint8_t
{
  Ordinary = 0,
  Bifurcation = 1, ///< another path joins here (or this path ends on another path)
  EndPoint = 2     ///< a free vessel end (tip or root)
};

struct SkeletonPoint
{
  Vec3 position_World_mm; ///< world frame of the volume (origin + direction * index * spacing)
  Vec3 tangent_World;     ///< unit tangent toward increasing point index
  double curvature_per_mm = 0.0; ///< 1/mm, from the smoothed curve
  double torsion_per_mm = 0.0;   ///< 1/mm, signed, from the smoothed curve
  double radius_mm = 0.0;        ///< local vessel radius
  PointLabel label = PointLabel::Ordinary;
};

/// One end of a path: either free (a vessel end) or attached to a point of another path.
struct PathEnd
{
  int junction = -1; ///< index into QSkeleton::junctions, -1 when the end is free
};

struct SkeletonPath
{
  int id = 0;                        ///< equals the path's index in QSkeleton::paths
  PathEnd head;                      ///< end at point index 0
  PathEnd tail;                      ///< end at the last point
  std::vector<SkeletonPoint> points; ///< ordered head -> tail, 26-connected before smoothing
};

/// Path `childPath`'s end `childEnd` attaches to point `parentPoint` of path `parentPath`.
/// A loop closure is a junction too (two fronts met), so the network may have cycles.
struct Junction
{
  enum class End : std::uint8_t
  {
    Head = 0,
    Tail = 1
  };
  int childPath = -1;
  End childEnd = End::Head;
  int parentPath = -1;
  int parentPoint = -1;
};

class QSkeleton
{
public:
  std::vector<SkeletonPath> paths;
  std::vector<Junction> junctions;

  std::size_t pointCount() const;
  bool empty() const { return paths.empty(); }

  /// Checks indices, ids and head/tail <-> junction back references.
  /// Returns an empty string when consistent, else a description of the first problem.
  std::string validate() const;
};

} // namespace vtouch
