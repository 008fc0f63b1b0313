// vesseltouch-centerline-sweep: one run of the voxel-coding skeleton filter with its parameters
// on the command line, for Utilities/bench (speed against accuracy). Like
// Testing/Logic/Skeleton/vtouchSkeletonBenchmark (same files, same JSON line) plus parameters.
//
//   vesseltouch-centerline-sweep [options] phantom <Helix|Tree> <nx> <ny> <nz> <outdir>
//   vesseltouch-centerline-sweep [options] image <file.mha> <lower> <upper> <outdir>
//   options: --smoothing-mm W        SmoothingWindow (0 automatic, < 0 off). Default 0.
//            --min-branch L          MinimumBranchLength, local radii. Default 2.5.
//            --vesselness            UseVesselness on (Hessian test on the raw intensities).
//            --noise SD              phantom: additive Gaussian noise (intensity units). Default 0.
//            --downsample F          DownsampleFactor (0 automatic, 1 full resolution; default:
//                                    the filter's). The JSON "downsample" is the factor used.
//            --no-mask               do not write mask.raw (no scikit-image comparison needed).
// Writes <outdir>/voxelcoding.csv (x,y,z mm, radius mm, path id), <outdir>/mask.raw (uint8, the
// threshold mask, x fastest), for phantoms <outdir>/analytic.csv (x,y,z mm, radius mm), and one
// JSON line on stdout: seconds of Update(), extra_rss_bytes (peak RSS during Update() minus RSS
// before it), vessel voxels, paths and points.
#include "vtouchVoxelCodingSkeletonFilter.h"

#include "vtouchSkeletonBenchmarkSupport.h"

#include <itkImageFileReader.h>
#include <itkMetaImageIOFactory.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace
{
using vtouch::benchmark::Image;
using Filter = vtouch::VoxelCodingSkeletonFilter<Image>;

struct Options
{
  int downsample = -1; // -1: the filter's default (0 = automatic)
  double smoothing_mm = 0.0;
  double minBranch = 2.5;
  bool vesselness = false;
  double noise = 0.0;
  bool writeMask = true;
};

int run(Image* image, double lower, double upper, const std::string& outdir, const Options& o)
{
  if (o.writeMask)
  {
    vtouch::benchmark::writeThresholdMask(image, lower, upper, outdir + "/mask.raw");
  }
  auto filter = Filter::New();
  filter->SetInput(image);
  filter->SetLowerThreshold(lower);
  filter->SetUpperThreshold(upper);
  filter->SetSmoothingWindow(o.smoothing_mm);
  filter->SetMinimumBranchLength(o.minBranch);
  filter->SetUseVesselness(o.vesselness);
  if (o.downsample >= 0)
  {
    filter->SetDownsampleFactor(static_cast<unsigned int>(o.downsample));
  }
  const vtouch::benchmark::UpdateCost cost = vtouch::benchmark::measureUpdate(filter);
  const vtouch::QSkeleton& s = filter->GetSkeleton();
  vtouch::benchmark::writeSkeletonCsv(s, outdir + "/voxelcoding.csv");
  const auto size = image->GetLargestPossibleRegion().GetSize();
  std::printf("{\"nx\": %lu, \"ny\": %lu, \"nz\": %lu, \"vessel_voxels\": %llu, \"seconds\": %.5f, "
              "\"extra_rss_bytes\": %lld, \"paths\": %zu, \"points\": %zu, \"downsample\": %u, "
              "\"coded_voxels\": %llu}\n",
    size[0],
    size[1],
    size[2],
    filter->GetNumberOfVesselVoxels(),
    cost.seconds,
    cost.extraBytes,
    s.paths.size(),
    s.pointCount(),
    filter->GetEffectiveDownsampleFactor(),
    filter->GetNumberOfCodedVoxels());
  return 0;
}

int phantom(char** a, const Options& o)
{
  const std::string outdir = a[4];
  double wall = 0.0;
  std::string error;
  Image::Pointer image = vtouch::benchmark::makePhantom(a[0],
    std::atoi(a[1]),
    std::atoi(a[2]),
    std::atoi(a[3]),
    o.noise,
    outdir + "/analytic.csv",
    wall,
    error);
  if (!image)
  {
    std::cerr << error << "\n";
    return 1;
  }
  return run(image, wall, 1e30, outdir, o);
}
} // namespace

int main(int argc, char** argv)
{
  Options o;
  int i = 1;
  for (; i < argc && argv[i][0] == '-' && argv[i][1] == '-'; ++i)
  {
    const std::string opt = argv[i];
    if (opt == "--smoothing-mm" && i + 1 < argc)
    {
      o.smoothing_mm = std::atof(argv[++i]);
    }
    else if (opt == "--min-branch" && i + 1 < argc)
    {
      o.minBranch = std::atof(argv[++i]);
    }
    else if (opt == "--vesselness")
    {
      o.vesselness = true;
    }
    else if (opt == "--noise" && i + 1 < argc)
    {
      o.noise = std::atof(argv[++i]);
    }
    else if (opt == "--downsample" && i + 1 < argc)
    {
      o.downsample = std::max(0, std::atoi(argv[++i]));
    }
    else if (opt == "--no-mask")
    {
      o.writeMask = false;
    }
    else
    {
      break;
    }
  }
  try
  {
    if (argc - i == 6 && std::string(argv[i]) == "phantom")
    {
      return phantom(argv + i + 1, o);
    }
    if (argc - i == 5 && std::string(argv[i]) == "image")
    {
      itk::MetaImageIOFactory::RegisterOneFactory();
      auto reader = itk::ImageFileReader<Image>::New();
      reader->SetFileName(argv[i + 1]);
      reader->Update();
      Image::Pointer image = reader->GetOutput();
      return run(image, std::atof(argv[i + 2]), std::atof(argv[i + 3]), argv[i + 4], o);
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << e.what() << "\n";
    return 1;
  }
  std::cerr << "usage: vesseltouch-centerline-sweep [--smoothing-mm W] [--min-branch L] "
               "[--vesselness] [--noise SD] [--downsample F] [--no-mask] phantom <Helix|Tree> nx "
               "ny nz outdir\n"
               "       vesseltouch-centerline-sweep [options] image file.mha lower upper outdir\n";
  return 2;
}
