// Generates a synthetic angiogram and its analytic centerline (the ground truth of the tests).
#pragma once

#include "vtouchPhantomSpec.h"
#include "vtouchQSkeleton.h"

#include <cstdint>
#include <functional>

namespace vtouch
{

class PhantomGenerator
{
public:
  /// Builds the analytic centerline of `spec`. Check ok() / error() before use.
  explicit PhantomGenerator(const PhantomSpec& spec);

  bool ok() const { return this->Error.empty(); }
  const std::string& error() const { return this->Error; }
  const PhantomSpec& spec() const { return this->Spec; }

  /// The analytic centerline sampled every ~0.25 of the smallest voxel side, world frame, with
  /// analytic tangent, curvature, torsion and radius. Paths joined by junctions like a Q-skeleton.
  const QSkeleton& centerline() const { return this->Centerline; }

  /// Total analytic length of all vessels, millimetres.
  double totalLength_mm() const;

  /// Distance (mm) from a world point to the nearest vessel centerline and the radius there.
  /// Computed on the fine sampling (chord error well below 1e-2 voxel). Brute force: for tests.
  double distanceToCenterline_mm(const Vec3& p_World_mm, double* radius_mm = nullptr) const;

  /// Fills a buffer of dimensions[0]*dimensions[1]*dimensions[2] voxels, x fastest.
  /// `progress` (may be empty) is called on the calling thread with 0 first, then with the
  /// fraction done while worker threads fill, and 1 at the end; returning false aborts (the call
  /// then returns false and the buffer is partly filled).
  bool fill(float* voxels, const std::function<bool(double)>& progress = {}) const;
  bool fill(std::uint16_t* voxels, const std::function<bool(double)>& progress = {}) const;

  /// Intensity at one world point without noise and roughness: the brightest vessel profile
  /// there (brute force over the fine sampling; for tests). RawAngiogram: the peak intensity
  /// inside a vessel of the tree, the tissue intensity elsewhere (no clutter, bias or texture).
  double intensityAt(const Vec3& p_World_mm) const;

private:
  PhantomSpec Spec;
  std::string Error;
  QSkeleton Centerline;
  template<typename T>
  bool fillT(T* voxels, const std::function<bool(double)>& progress) const;
};

} // namespace vtouch
