// vesseltouch-whole-volume-vesselness: the cost of multi-scale Hessian vesselness computed over a
// whole raw angiogram (the classic approach the issue 16 extraction avoids by computing tubularity
// only around the candidate vessel), for Utilities/bench beside VesselCenterline's time.
//
//   vesseltouch-whole-volume-vesselness <nx> <ny> <nz> [--seed S] [--noise SD] [--segments K]
//                                       [--scales N]
//
// Builds the RawAngiogram VesselPhantom of that size (seed S = 1, Gaussian noise SD = 20,
// K = 400 target segments), then runs ITK's MultiScaleHessianBasedMeasureImageFilter with
// HessianToObjectnessMeasureImageFilter (Frangi-style objectness for bright tubes, object
// dimension 1: A. F. Frangi et al., MICCAI 1998, eq. 13; ITK's implementation) over N = 4 scales,
// logarithmic from one voxel to the phantom's largest radius (4 voxels): the scales a
// whole-volume approach needs for the vessels of the phantom. Prints one JSON line: seconds (the
// vesselness Update() alone, on ITK's default number of threads), voxels, scales, threads.
#include "vtouchPhantomGenerator.h"

#include <itkHessianToObjectnessMeasureImageFilter.h>
#include <itkImage.h>
#include <itkMultiScaleHessianBasedMeasureImageFilter.h>
#include <itkMultiThreaderBase.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace
{
int usage()
{
  std::fprintf(stderr,
    "usage: vesseltouch-whole-volume-vesselness <nx> <ny> <nz> [--seed S] [--noise SD] "
    "[--segments K] [--scales N]\n");
  return 2;
}
} // namespace

int main(int argc, char** argv)
{
  if (argc < 4)
  {
    return usage();
  }
  vtouch::PhantomSpec spec;
  spec.shape = vtouch::PhantomShape::RawAngiogram;
  spec.noiseStdDev = 20.0;
  spec.angiogramSegments = 400;
  int scales = 4;
  for (int a = 0; a < 3; ++a)
  {
    spec.dimensions[a] = std::atoi(argv[1 + a]);
  }
  for (int i = 4; i < argc; ++i)
  {
    const std::string opt = argv[i];
    if (i + 1 >= argc)
    {
      return usage();
    }
    const double value = std::atof(argv[++i]);
    if (opt == "--seed")
    {
      spec.seed = static_cast<std::uint32_t>(value);
    }
    else if (opt == "--noise")
    {
      spec.noiseStdDev = value;
    }
    else if (opt == "--segments")
    {
      spec.angiogramSegments = static_cast<int>(value);
    }
    else if (opt == "--scales")
    {
      scales = static_cast<int>(value);
    }
    else
    {
      return usage();
    }
  }
  const vtouch::PhantomGenerator generator(spec);
  if (!generator.ok() || scales < 1)
  {
    std::fprintf(stderr,
      "vesseltouch-whole-volume-vesselness: %s\n",
      generator.ok() ? "at least one scale" : generator.error().c_str());
    return 1;
  }
  using Image = itk::Image<float, 3>;
  auto image = Image::New();
  Image::SizeType size;
  for (int a = 0; a < 3; ++a)
  {
    size[a] = static_cast<itk::SizeValueType>(spec.dimensions[a]);
  }
  image->SetRegions(Image::RegionType(size));
  image->Allocate();
  if (!generator.fill(image->GetBufferPointer()))
  {
    std::fprintf(stderr, "vesseltouch-whole-volume-vesselness: the phantom was not filled\n");
    return 1;
  }

  using Hessian = itk::Image<itk::SymmetricSecondRankTensor<double, 3>, 3>;
  using Objectness = itk::HessianToObjectnessMeasureImageFilter<Hessian, Image>;
  using MultiScale = itk::MultiScaleHessianBasedMeasureImageFilter<Image, Hessian, Image>;
  auto objectness = Objectness::New();
  objectness->SetObjectDimension(1);
  objectness->SetBrightObject(true);
  auto multiScale = MultiScale::New();
  multiScale->SetInput(image);
  multiScale->SetHessianToMeasureFilter(objectness);
  multiScale->SetSigmaMinimum(1.0);
  multiScale->SetSigmaMaximum(spec.angiogramLargestRadius_vox);
  multiScale->SetNumberOfSigmaSteps(scales);
  multiScale->SetSigmaStepMethodToLogarithmic();
  multiScale->GenerateScalesOutputOff();
  multiScale->GenerateHessianOutputOff();
  const auto t0 = std::chrono::steady_clock::now();
  multiScale->Update();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("{\"seconds\": %.4f, \"voxels\": %.0f, \"scales\": %d, \"threads\": %u}\n",
    seconds,
    static_cast<double>(size[0]) * size[1] * size[2],
    scales,
    itk::MultiThreaderBase::GetGlobalDefaultNumberOfThreads());
  return 0;
}
