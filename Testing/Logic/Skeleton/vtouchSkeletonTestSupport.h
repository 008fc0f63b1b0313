// Helpers shared by the skeleton tests: phantom volumes as ITK images, accuracy and topology
// measures of a Q-skeleton against the analytic centerline.
#pragma once

#include "vtouchPhantomGenerator.h"
#include "vtouchQSkeleton.h"
#include "vtouchVoxelCoding.h"

#include <itkImage.h>

#include <string>

namespace vtouch
{
namespace test
{

using FloatImage = itk::Image<float, 3>;

/// An image with the grid of `spec` (identity direction) filled by the phantom.
FloatImage::Pointer phantomImage(const PhantomGenerator& generator);

/// Half-maximum threshold of the phantom profile: the vessel wall.
double wallThreshold(const PhantomSpec& spec);

/// Blank image with the given grid.
FloatImage::Pointer blankImage(int nx, int ny, int nz, double spacing = 1.0);

struct Accuracy
{
  double mean_mm = 0.0;  ///< mean distance from output points to the analytic centerline
  double p95_mm = 0.0;   ///< 95th percentile of the same
  double coverage = 0.0; ///< fraction of analytic points within `coverRadius_mm` of the output
  double radiusError_mm = 0.0; ///< mean |radius - analytic radius| away from ends
  std::size_t outputPoints = 0;
};

/// `endMargin_mm`: output points closer than this to a free end are left out of the radius error.
Accuracy measure(const QSkeleton& output, const PhantomGenerator& generator, double coverRadius_mm);

/// Distance from p to the polyline set of `s`.
double distanceToSkeleton(const QSkeleton& s, const Vec3& p);

struct Topology
{
  int endPoints = 0;    ///< free path ends
  int bifurcations = 0; ///< places where three or more branches meet (merged within a distance)
  int loops = 0;        ///< independent cycles: junctions - paths + components
  int components = 0;
};
Topology topology(const QSkeleton& s, double mergeDistance_mm);

/// Empty when every raw path is a 26-connected chain of distinct voxels, else the first problem.
std::string check26Connected(const RawSkeleton& raw, const std::array<double, 3>& spacing);

} // namespace test
} // namespace vtouch
