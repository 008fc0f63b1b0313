// The random bifurcating vascular tree of the RawAngiogram phantom (the ground truth, port 1).
#pragma once

#include "vtouchPhantomSpec.h"
#include "vtouchQSkeleton.h"

#include <vector>

namespace vtouch
{

class PhantomRandom;

/// Grows a seeded random arterial tree inside the phantom volume.
///
/// - Radii follow Murray's law at every bifurcation, r_parent^3 = r_1^3 + r_2^3 (C. D. Murray,
///   "The physiological principle of minimum work. I.", PNAS 12:207, 1926, eq. for the cube law);
///   the asymmetry r_2/r_1 is drawn in [0.25, 1]; a child below the smallest radius is set to it
///   and its sibling takes the rest of the cube sum, so the law holds exactly everywhere.
/// - Branching angles are Murray's minimum-work angles (C. D. Murray, J Gen Physiol 9:835, 1926):
///   cos t1 = (r0^4 + r1^4 - r2^4) / (2 r0^2 r1^2), and symmetrically for t2, in a plane rolled
///   at random about the parent's end tangent: segments run in all orientations.
/// - Segments are cubic Hermite curves whose end tangent turns up to 35 deg from the start tangent
///   (curved, tangent-continuous from the parent); length max(10..20 voxels, 8..16 radii), at
///   most a quarter of the smallest side, shortened by up to 60 % on later placement attempts;
///   a segment heading for a face within 0.3 of the smallest side bends back toward the centre.
/// - Growth is breadth first and stops at the target segment count, when every leaf is too thin to
///   split, or when no child fits: every segment stays inside the volume (its radius + 3 voxels
///   from the faces) and clear of all other segments (the radii + 2 voxels apart, beyond the
///   bifurcation it starts from), so vessels touch only at their bifurcations.
/// - The root (path 0) starts near the centre of one face, pointing inward; its first point is
///   where a user would seed an extraction.
/// Same spec (seed included) -> same tree.
class VascularTreeGenerator
{
public:
  /// `spec` must be valid; `step_mm` is the sampling step of the returned centerline.
  VascularTreeGenerator(const PhantomSpec& spec, double step_mm);

  /// The tree: one path per segment (constant radius along it), each child's head joined to its
  /// parent's last point.
  QSkeleton build();

private:
  struct Segment
  {
    int parent = -1;
    Vec3 p0;
    Vec3 p1;
    Vec3 m0; ///< Hermite start tangent (direction * length)
    Vec3 m1; ///< Hermite end tangent
    double radius_mm = 0.0;
    std::vector<Vec3> samples; ///< about one per voxel, for the clearance tests
  };

  Segment makeSegment(int parent,
    const Vec3& start,
    const Vec3& direction,
    double radius_mm,
    double lengthScale,
    PhantomRandom& random) const;
  bool fits(const Segment& s, int parent, int sibling) const;
  void addToGrid(int index);

  const PhantomSpec& Spec;
  double Step_mm;
  double Voxel_mm;
  Vec3 Lo;
  Vec3 Hi;
  std::vector<Segment> Segments;

  /// Uniform hash grid of segment samples (cell = the largest clearance distance).
  double Cell_mm = 1.0;
  int GridDims[3] = { 1, 1, 1 };
  std::vector<std::vector<std::pair<int, int>>> Grid; ///< (segment, sample)
};

} // namespace vtouch
