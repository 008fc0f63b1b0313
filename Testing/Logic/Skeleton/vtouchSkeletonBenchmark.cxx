// Speed and memory of the voxel-coding skeleton, for Utilities/skeleton_benchmark.py (which runs
// scikit-image on the same volumes and prints the side-by-side table). Not a test.
//
//   vtouchSkeletonBenchmark phantom <Helix|Tree> <nx> <ny> <nz> <outdir> [downsample]
//       writes <outdir>/mask.raw (uint8, x fastest), <outdir>/analytic.csv (x,y,z mm) and runs the
//       filter, writing <outdir>/voxelcoding.csv (x,y,z mm, radius mm, path id) and one JSON line
//       on stdout.
//   vtouchSkeletonBenchmark image <file.mha> <lower> <upper> <outdir> [downsample]
//       same for an image file (mask.raw, voxelcoding.csv; no analytic centerline).
//   [downsample]: the filter's DownsampleFactor (default: the filter's default, 0 = automatic);
//   mask.raw stays at full resolution. The JSON line reports the factor used ("factor") and the
//   voxels coded at it ("coded_voxels").
#include "vtouchVoxelCodingSkeletonFilter.h"

#include "vtouchSkeletonBenchmarkSupport.h"

#include <itkImageFileReader.h>
#include <itkMetaImageIOFactory.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
using vtouch::benchmark::Image;
using Filter = vtouch::VoxelCodingSkeletonFilter<Image>;

constexpr unsigned int kFilterDefault = ~0U;

unsigned int downsampleArg(const char* text)
{
  return static_cast<unsigned int>(std::max(0, std::atoi(text))); // 0 = automatic
}

int run(Image* image,
  double lower,
  double upper,
  const std::string& outdir,
  const std::string& name,
  unsigned int downsample)
{
  vtouch::benchmark::writeThresholdMask(image, lower, upper, outdir + "/mask.raw");
  auto filter = Filter::New();
  filter->SetInput(image);
  filter->SetLowerThreshold(lower);
  filter->SetUpperThreshold(upper);
  if (downsample != kFilterDefault)
  {
    filter->SetDownsampleFactor(downsample);
  }
  const vtouch::benchmark::UpdateCost cost = vtouch::benchmark::measureUpdate(filter);
  const vtouch::QSkeleton& s = filter->GetSkeleton();
  // Stage profile on stderr (the JSON line on stdout stays one line).
  for (const auto& stage : filter->GetRawSkeleton().stageSeconds)
  {
    std::fprintf(stderr, "stage %-12s %.4f s\n", stage.first.c_str(), stage.second);
  }
  vtouch::benchmark::writeSkeletonCsv(s, outdir + "/voxelcoding.csv");
  const auto size = image->GetLargestPossibleRegion().GetSize();
  std::printf("{\"case\": \"%s\", \"nx\": %lu, \"ny\": %lu, \"nz\": %lu, \"vessel_voxels\": %llu, "
              "\"seconds\": %.4f, \"extra_rss_bytes\": %lld, \"code_bytes\": %llu, \"paths\": %zu, "
              "\"points\": %zu, \"junctions\": %zu, \"factor\": %u, \"coded_voxels\": %llu}\n",
    name.c_str(),
    size[0],
    size[1],
    size[2],
    filter->GetNumberOfVesselVoxels(),
    cost.seconds,
    cost.extraBytes,
    filter->GetCodeMemoryBytes(),
    s.paths.size(),
    s.pointCount(),
    s.junctions.size(),
    filter->GetEffectiveDownsampleFactor(),
    filter->GetNumberOfCodedVoxels());
  return 0;
}
} // namespace

int main(int argc, char** argv)
{
  try
  {
    if ((argc == 7 || argc == 8) && std::string(argv[1]) == "phantom")
    {
      const std::string shape = argv[2];
      const std::string outdir = argv[6];
      double wall = 0.0;
      std::string error;
      Image::Pointer image = vtouch::benchmark::makePhantom(shape,
        std::atoi(argv[3]),
        std::atoi(argv[4]),
        std::atoi(argv[5]),
        0.0,
        outdir + "/analytic.csv",
        wall,
        error);
      if (!image)
      {
        std::cerr << error << "\n";
        return 1;
      }
      return run(
        image, wall, 1e30, outdir, shape, argc == 8 ? downsampleArg(argv[7]) : kFilterDefault);
    }
    if ((argc == 6 || argc == 7) && std::string(argv[1]) == "image")
    {
      itk::MetaImageIOFactory::RegisterOneFactory();
      auto reader = itk::ImageFileReader<Image>::New();
      reader->SetFileName(argv[2]);
      reader->Update();
      Image::Pointer image = reader->GetOutput();
      return run(image,
        std::atof(argv[3]),
        std::atof(argv[4]),
        argv[5],
        "image",
        argc == 7 ? downsampleArg(argv[6]) : kFilterDefault);
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << e.what() << "\n";
    return 1;
  }
  std::cerr << "usage: vtouchSkeletonBenchmark phantom <Helix|Tree> nx ny nz outdir [downsample]\n"
               "       vtouchSkeletonBenchmark image file.mha lower upper outdir [downsample]\n";
  return 2;
}
