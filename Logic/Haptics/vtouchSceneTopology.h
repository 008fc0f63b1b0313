// The camera-independent part of the haptic scene model: how the Q-skeleton's points connect.
// Built once per skeleton (off the haptic thread); shared by every view model of that skeleton.
#pragma once

#include "vtouchQSkeleton.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace vtouch
{

/// Points are numbered globally: point `i` of path `p` is `pathOffset[p] + i`.
/// The graph has an edge between consecutive points of a path and one per junction (child end point
/// <-> parent point); loop closures are junctions, so the graph may have cycles.
class SceneTopology
{
public:
  /// `slopeWindow_mm`: 3D arc length of the centred stencil used for dz/dl (see ViewModelBuilder).
  static std::shared_ptr<const SceneTopology> build(const QSkeleton& skeleton,
    double slopeWindow_mm);

  int pointCount() const { return static_cast<int>(this->PathOf.size()); }
  int pathCount() const { return static_cast<int>(this->PathOffset.size()) - 1; }
  int globalIndex(int path, int point) const { return this->PathOffset[path] + point; }
  int pathOf(int g) const { return this->PathOf[g]; }
  int pointOf(int g) const { return g - this->PathOffset[this->PathOf[g]]; }
  int pathBegin(int path) const { return this->PathOffset[path]; }
  int pathEnd(int path) const { return this->PathOffset[path + 1]; }

  /// Graph neighbours of global point g: writes up to `capacity` indices, returns how many.
  /// Never allocates (safe in the haptic tick).
  int neighbours(int g, int* out, int capacity) const;
  /// Largest number of neighbours any point has.
  int maxDegree() const { return this->MaxDegree; }

  /// Centred stencils for the tangent estimate used by dz/dl: the inner one reaches about half the
  /// window on each side along the path (wrapping around closed loops), the outer one twice as far.
  /// The unit tangent estimate is
  ///   D = innerWeight * (P[hiInner] - P[loInner]) - outerWeight * (P[hiOuter] - P[loOuter]),
  /// a Richardson extrapolation of the two central differences (error O(h^4) instead of O(h^2),
  /// which keeps tight bends within 2 %); near free path ends it falls back to one difference.
  /// The extrapolation assumes a smooth curve. On one, the turn between the backward and forward
  /// half-chords grows in proportion to the chord (exactly so on a circle): the outer stencil's
  /// turn is twice the inner one's. Where it is not, a corner lies inside the stencil (a flat
  /// vessel meeting a steep rise) and the extrapolation overshoots: on the flat side it gave a
  /// depth change of the wrong sign, on the rise side a projected tangent pointing backwards, i.e.
  /// a slope force of the wrong sign (+2.5 N for -2.6 N next to an 89 degree rise). So the
  /// correction is faded out with m = |turn_outer - 2 turn_inner| (full below 2 degrees, none
  /// above 4): near a corner D is the plain central difference of the inner chord, whose depth
  /// change has the sign of the path's.
  static constexpr double kRichardsonFullBelow_rad = 2.0 * 3.14159265358979323846 / 180.0;
  static constexpr double kRichardsonNoneAbove_rad = 4.0 * 3.14159265358979323846 / 180.0;
  int stencilLow(int g) const { return this->Stencil[g].loInner; }
  int stencilHigh(int g) const { return this->Stencil[g].hiInner; }
  const Vec3& tangentEstimate(int g) const { return this->TangentEstimate[g]; }
  /// Positions as float arrays (structure of arrays) for the vectorized projection of a rebuild.
  const float* positionsX() const { return this->PackedX.data(); }
  const float* positionsY() const { return this->PackedY.data(); }
  const float* positionsZ() const { return this->PackedZ.data(); }
  /// The stencil window, mm: dz and dl are reported per window (ViewModel).
  double slopeWindow_mm() const { return this->Window_mm; }

  const Vec3& position_World_mm(int g) const { return this->Position[g]; }
  const Vec3& tangent_World(int g) const { return this->Tangent[g]; }
  double torsion_per_mm(int g) const { return this->Torsion[g]; }
  double radius_mm(int g) const { return this->Radius[g]; }
  /// 3D arc length from the start of g's path to g, mm (increases with the point index).
  double pathArc_mm(int g) const { return this->PathArc[g]; }
  /// True when g is a bifurcation: a branch joins its path there (a junction's parent point or
  /// the child's end point); a loop closing on its own end is not one.
  bool isBifurcation(int g) const { return this->Bifurcation[g] != 0; }
  /// pathArc_mm of the bifurcation on g's path nearest to g (by arc), NaN when the path has none.
  /// Ikits et al.'s tick-mark texture marks bifurcations with it (ConstraintProxyForceLaw).
  double nearestBifurcationArc_mm(int g) const { return this->NearestBifurcationArc[g]; }
  /// Signed 3D arc distance from an agent at `location` (from, to, t) to the nearest bifurcation
  /// of its path, mm, positive when the agent lies beyond it toward increasing index; 0 on a
  /// junction edge between two paths (the agent is at the bifurcation); NaN when there is none.
  /// Never allocates.
  double bifurcationOffset_mm(int from, int to, double t) const;
  /// Identifies the skeleton (changes each build) so agent state knows when indices are stale.
  std::uint64_t id() const { return this->Id; }

private:
  std::vector<int> PathOffset;
  std::vector<int> PathOf;
  struct StencilEntry
  {
    int loInner = 0, hiInner = 0, loOuter = 0, hiOuter = 0;
    double innerWeight = 0.0, outerWeight = 0.0;
    double plainWeight = 0.0; // 1 / inner chord length: the central difference alone
  };
  std::vector<StencilEntry> Stencil;
  std::vector<Vec3> TangentEstimate;
  std::vector<float> PackedX, PackedY, PackedZ;
  double Window_mm = 1.0;
  std::vector<Vec3> Position;
  std::vector<Vec3> Tangent;
  std::vector<double> Torsion;
  std::vector<double> Radius;
  std::vector<double> PathArc;
  std::vector<unsigned char> Bifurcation;
  std::vector<double> NearestBifurcationArc;
  // Junction edges in CSR form (most points have none).
  std::vector<int> JunctionBegin;
  std::vector<int> JunctionTarget;
  int MaxDegree = 2;
  std::uint64_t Id = 0;
};

} // namespace vtouch
