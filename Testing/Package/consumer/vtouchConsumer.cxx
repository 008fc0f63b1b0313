// Uses each exported library once, through installed headers only: a phantom tube is coded into
// a Q-skeleton (Phantom, Skeleton), the force zones k(P) of the haptic logic and of the widget
// agree (Haptics, Widgets), and a SeqLock publishes a vector (Core). Exits non-zero on any
// mismatch, with the reason on stderr.
#include "qVesselTouchForceZonesWidget.h"
#include "vtouchForceZones.h"
#include "vtouchPhantomGenerator.h"
#include "vtouchSeqLock.h"
#include "vtouchVector.h"
#include "vtouchVoxelCodingSkeletonFilter.h"

#include <itkImage.h>

#include <cmath>
#include <cstdio>
#include <vector>

namespace
{
int fail(const char* what)
{
  std::fprintf(stderr, "vtouchConsumer: %s\n", what);
  return 1;
}
} // namespace

int main()
{
  vtouch::PhantomSpec spec;
  spec.shape = vtouch::PhantomShape::StraightTube;
  spec.dimensions = { 48, 32, 32 };
  vtouch::PhantomGenerator phantom(spec);
  if (!phantom.ok())
  {
    return fail(phantom.error().c_str());
  }
  using Image = itk::Image<float, 3>;
  auto image = Image::New();
  Image::SizeType size;
  for (unsigned int a = 0; a < 3; ++a)
  {
    size[a] = static_cast<Image::SizeValueType>(spec.dimensions[a]);
  }
  image->SetRegions(Image::RegionType(size));
  image->Allocate();
  if (!phantom.fill(image->GetBufferPointer()))
  {
    return fail("the phantom did not fill");
  }
  auto filter = vtouch::VoxelCodingSkeletonFilter<Image>::New();
  filter->SetInput(image);
  // Half way between background and peak: the Gaussian profile's wall.
  filter->SetLowerThreshold(0.5 * (spec.backgroundIntensity + spec.peakIntensity));
  filter->SetUpperThreshold(2.0 * spec.peakIntensity);
  filter->Update();
  const vtouch::QSkeleton& skeleton = filter->GetSkeleton();
  if (skeleton.paths.size() != 1 || skeleton.paths[0].points.size() < 10)
  {
    return fail("a straight tube must give one path");
  }

  vtouch::ForceZones zones;
  for (double pressure : { 0.0, 0.1, 0.3, 0.6, 1.0 })
  {
    const double widget = qVesselTouchForceZonesWidget::zoneGain(
      pressure, zones.zeroBelow, zones.saturateAbove, zones.gain_N);
    if (std::abs(widget - zones.gain(pressure)) > 1e-12)
    {
      return fail("the widget's k(P) differs from the haptic logic's");
    }
  }

  vtouch::SeqLock<vtouch::Vec3> published;
  published.store(vtouch::Vec3{ 1.0, 2.0, 3.0 });
  if (published.load().z != 3.0)
  {
    return fail("SeqLock did not publish");
  }
  std::printf("vtouchConsumer: one path of %zu points\n", skeleton.paths[0].points.size());
  return 0;
}
