// The brightest voxel along a ray through a volume, in index space (plain C++, no VTK, no Qt): what
// a click on a maximum-intensity projection points at. The seed picker unprojects the click into
// a segment, transforms its ends into continuous voxel indices (voxel centres at integers) and
// asks this class for the voxel of maximum intensity on that segment.
#ifndef vtouchRayMaximum_h
#define vtouchRayMaximum_h

#include <array>
#include <functional>

namespace vtouch
{

/// The voxel found by RayMaximum::find.
struct RayMaximumResult
{
  /// The segment crossed the volume and at least one voxel was sampled.
  bool found = false;
  /// Index of the brightest voxel, 0-based in each axis; -1 when not found.
  std::array<int, 3> index{ { -1, -1, -1 } };
  /// Its value (the sampler's units). 0 when not found.
  double value = 0.0;
  /// Voxels visited along the segment (each counted once).
  int visited = 0;
};

class RayMaximum
{
public:
  /// Value of voxel (i, j, k), 0-based indices inside the dimensions.
  using Sampler = std::function<double(int i, int j, int k)>;

  /// Marches the segment start_Index -> end_Index (continuous voxel indices) through a volume of
  /// `dimensions` voxels (each > 0), clipped to the volume's box [-0.5, n - 0.5] per axis, with a
  /// step of `step_voxels` (default 0.25, at most 1; values <= 0 or non-finite use the default),
  /// sampling the nearest voxel. The first voxel reached (from start) wins ties, so the seed is
  /// the front-most of equally bright voxels. Non-finite ends or a segment missing the volume give
  /// found = false.
  static RayMaximumResult find(const std::array<int, 3>& dimensions,
    const std::array<double, 3>& start_Index,
    const std::array<double, 3>& end_Index,
    const Sampler& sample,
    double step_voxels = 0.25);

  /// Clips the segment start + t (end - start), t in [0, 1], to the axis-aligned box [low, high]
  /// (slab method; any frame, the box and the segment in the same one). True and the parameter
  /// range [t0, t1] when they intersect; false for a miss or a non-finite coordinate.
  static bool clipSegmentToBox(const std::array<double, 3>& low,
    const std::array<double, 3>& high,
    const std::array<double, 3>& start,
    const std::array<double, 3>& end,
    double& t0,
    double& t1);

  /// Clips the segment start + t (end - start), t in [0, 1], to the box [-0.5, n - 0.5] per axis
  /// (clipSegmentToBox in the index frame). True and the parameter range [t0, t1] when they
  /// intersect.
  static bool clipToVolume(const std::array<int, 3>& dimensions,
    const std::array<double, 3>& start_Index,
    const std::array<double, 3>& end_Index,
    double& t0,
    double& t1);
};

} // namespace vtouch

#endif
