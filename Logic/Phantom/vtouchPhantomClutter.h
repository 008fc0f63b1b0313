// Clutter of the RawAngiogram phantom: bone-like plates and blobs at vessel intensity, each
// touching a vessel, never part of the ground-truth tree.
#pragma once

#include "vtouchPhantomSpec.h"
#include "vtouchQSkeleton.h"

#include <vector>

namespace vtouch
{

/// Places spec.clutterCount objects (even ranks plates, odd ranks blobs) against the vessels of
/// `tree`: each touches one vessel of radius >= 0.75 voxel at a random point, from a random side,
/// overlapping its wall by half a voxel (so that any threshold that keeps the vessel joins the
/// clutter to it: the extraction must cut it off at the tube). No object reaches a vessel's
/// axis; the touched vessel's wall is entered by at most 0.75 voxel, every other vessel is left
/// at least one voxel clear, and the root's first point (the extraction seed) two voxels.
/// - Plate: a rectangular slab (bone cortex), half thickness 1.5..3 voxels, half sides 6..16
///   voxels (at most 0.15 of the smallest side), lying flat against the vessel.
/// - Blob: an ellipsoid (a lymph node, a calcification, a venous lake), shortest semi-axis
///   2.5..6 voxels toward the vessel, the others 1..1.8 times it.
/// An object that finds no valid place in 200 tries is left out (count() may be below the
/// request in a crowded volume). Same spec and tree -> same clutter.
class PhantomClutter
{
public:
  struct Object
  {
    bool plate = true;
    Vec3 centre_World_mm;
    Vec3 axes[3];            ///< orthonormal; axes[0] points from the object to the vessel
    double halfSize_mm[3]{}; ///< plate: half extents; blob: semi-axes (halfSize_mm[0] smallest)
    int touchedPath = -1;    ///< the tree path it touches
    Vec3 contact_World_mm;   ///< the touched axis point

    bool contains(const Vec3& p) const;
    /// Signed distance bound: positive outside, negative inside, |value| <= true distance to
    /// the surface (exact for plates; (k - 1) * smallest semi-axis for blobs, k the ellipsoid
    /// norm of p, a bound by the support-function argument).
    double signedDistanceBound_mm(const Vec3& p) const;
    /// Axis-aligned bounding box.
    void bounds(Vec3& lo, Vec3& hi) const;
  };

  PhantomClutter(const PhantomSpec& spec, const QSkeleton& tree);

  const std::vector<Object>& objects() const { return this->Objects; }
  bool contains(const Vec3& p) const;

private:
  std::vector<Object> Objects;
};

} // namespace vtouch
