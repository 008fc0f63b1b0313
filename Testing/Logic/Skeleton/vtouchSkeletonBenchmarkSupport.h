// What the two centerline benchmark tools share (vtouchSkeletonBenchmark for
// Utilities/skeleton_benchmark.py, vesseltouch-centerline-sweep for Utilities/bench): the
// benchmark phantoms, the files scikit-image and the accuracy scripts read, and the peak-memory
// probe. Not a test.
#ifndef vtouchSkeletonBenchmarkSupport_h
#define vtouchSkeletonBenchmarkSupport_h

#include "vtouchQSkeleton.h"

#include <itkImage.h>
#include <itkProcessObject.h>

#include <string>

namespace vtouch
{
namespace benchmark
{
using Image = itk::Image<float, 3>;

/// The benchmark phantom ("Helix" or "Tree": tree radii 0.055 N / 0.045 N / 0.035 N) of
/// nx × ny × nz voxels with optional Gaussian noise; writes its analytic centerline to
/// `analyticCsvPath` (x,y,z mm, radius mm). `wall` gets the intensity half-way between background
/// and vessel (the threshold that gives the vessel). Null and `error` set on bad parameters.
Image::Pointer makePhantom(const std::string& shape,
  int nx,
  int ny,
  int nz,
  double noiseStdDev,
  const std::string& analyticCsvPath,
  double& wall,
  std::string& error);

/// The threshold mask [lower, upper] as uint8, x fastest (what scikit-image skeletonizes).
void writeThresholdMask(const Image* image, double lower, double upper, const std::string& path);

/// The skeleton's points as x,y,z mm, radius mm, path id.
void writeSkeletonCsv(const QSkeleton& skeleton, const std::string& path);

/// Peak extra resident memory of a stage (Linux /proc): start() before it, extraBytes() after.
class PeakMemoryProbe
{
public:
  /// Records the current RSS and resets the peak (VmHWM) through /proc/self/clear_refs.
  void start();
  /// Peak RSS since start() minus the RSS at start(), bytes.
  long long extraBytes() const;

private:
  long long BaseKb = 0;
};

/// Wall time and peak extra resident memory of one filter->Update().
struct UpdateCost
{
  double seconds = 0.0;
  long long extraBytes = 0;
};
UpdateCost measureUpdate(itk::ProcessObject* filter);

} // namespace benchmark
} // namespace vtouch

#endif
