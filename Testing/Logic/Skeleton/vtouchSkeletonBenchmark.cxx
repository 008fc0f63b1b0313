// Speed and memory of the voxel-coding skeleton, for Utilities/skeleton_benchmark.py (which runs
// scikit-image on the same volumes and prints the side-by-side table). Not a test.
//
//   vtouchSkeletonBenchmark phantom <Helix|Tree> <nx> <ny> <nz> <outdir> [downsample]
//       writes <outdir>/mask.raw (uint8, x fastest), <outdir>/analytic.csv (x,y,z mm) and runs the
//       filter, writing <outdir>/voxelcoding.csv (x,y,z mm, radius mm, path id) and one JSON line
//       on stdout.
//   vtouchSkeletonBenchmark image <file.mha> <lower> <upper> <outdir> [downsample]
//       same for an image file (mask.raw, voxelcoding.csv; no analytic centerline).
//   [downsample]: the filter's DownsampleFactor (default 1); mask.raw stays at full resolution.
#include "vtouchVoxelCodingSkeletonFilter.h"

#include "vtouchPhantomGenerator.h"

#include <itkImageFileReader.h>
#include <itkMetaImageIOFactory.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
using Image = itk::Image<float, 3>;
using Filter = vtouch::VoxelCodingSkeletonFilter<Image>;

/// Peak resident memory since the last reset, bytes (Linux /proc).
long long statusKb(const char* key)
{
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
  {
    if (line.rfind(key, 0) == 0)
    {
      return std::atoll(line.c_str() + std::strlen(key));
    }
  }
  return -1;
}

unsigned int downsampleArg(const char* text)
{
  return static_cast<unsigned int>(std::max(0, std::atoi(text))); // 0 is rejected by the filter
}

void resetPeak()
{
  std::ofstream("/proc/self/clear_refs") << "5";
}

void writeMask(const Image* image, double lower, double upper, const std::string& path)
{
  const auto n = image->GetLargestPossibleRegion().GetNumberOfPixels();
  std::vector<unsigned char> mask(n);
  const float* v = image->GetBufferPointer();
  for (std::size_t i = 0; i < n; ++i)
  {
    mask[i] = v[i] >= lower && v[i] <= upper ? 1 : 0;
  }
  std::ofstream(path, std::ios::binary)
    .write(reinterpret_cast<const char*>(mask.data()), static_cast<std::streamsize>(n));
}

int run(Image* image,
  double lower,
  double upper,
  const std::string& outdir,
  const std::string& name,
  unsigned int downsample)
{
  writeMask(image, lower, upper, outdir + "/mask.raw");
  auto filter = Filter::New();
  filter->SetInput(image);
  filter->SetLowerThreshold(lower);
  filter->SetUpperThreshold(upper);
  filter->SetDownsampleFactor(downsample);
  const long long baseKb = statusKb("VmRSS:");
  resetPeak();
  const auto t0 = std::chrono::steady_clock::now();
  filter->Update();
  const auto t1 = std::chrono::steady_clock::now();
  const long long peakKb = statusKb("VmHWM:");
  const vtouch::QSkeleton& s = filter->GetSkeleton();
  // Stage profile on stderr (the JSON line on stdout stays one line).
  for (const auto& stage : filter->GetRawSkeleton().stageSeconds)
  {
    std::fprintf(stderr, "stage %-12s %.4f s\n", stage.first.c_str(), stage.second);
  }
  std::ofstream csv(outdir + "/voxelcoding.csv");
  for (const auto& path : s.paths)
  {
    for (const auto& q : path.points)
    {
      csv << q.position_World_mm.x << "," << q.position_World_mm.y << "," << q.position_World_mm.z
          << "," << q.radius_mm << "," << path.id << "\n";
    }
  }
  const auto size = image->GetLargestPossibleRegion().GetSize();
  std::printf("{\"case\": \"%s\", \"nx\": %lu, \"ny\": %lu, \"nz\": %lu, \"vessel_voxels\": %llu, "
              "\"seconds\": %.4f, \"extra_rss_bytes\": %lld, \"code_bytes\": %llu, \"paths\": %zu, "
              "\"points\": %zu, \"junctions\": %zu}\n",
    name.c_str(),
    size[0],
    size[1],
    size[2],
    filter->GetNumberOfVesselVoxels(),
    std::chrono::duration<double>(t1 - t0).count(),
    (peakKb - baseKb) * 1024,
    filter->GetCodeMemoryBytes(),
    s.paths.size(),
    s.pointCount(),
    s.junctions.size());
  return 0;
}
} // namespace

int main(int argc, char** argv)
{
  try
  {
    if ((argc == 7 || argc == 8) && std::string(argv[1]) == "phantom")
    {
      vtouch::PhantomSpec spec;
      const std::string shape = argv[2];
      spec.shape = shape == "Tree" ? vtouch::PhantomShape::Tree : vtouch::PhantomShape::Helix;
      spec.dimensions = { std::atoi(argv[3]), std::atoi(argv[4]), std::atoi(argv[5]) };
      if (spec.shape == vtouch::PhantomShape::Tree)
      {
        spec.treeRadiusFractions = { 0.055, 0.045, 0.035 };
      }
      vtouch::PhantomGenerator generator(spec);
      if (!generator.ok())
      {
        std::cerr << generator.error() << "\n";
        return 1;
      }
      auto image = Image::New();
      Image::RegionType region;
      region.SetSize({ { static_cast<itk::SizeValueType>(spec.dimensions[0]),
        static_cast<itk::SizeValueType>(spec.dimensions[1]),
        static_cast<itk::SizeValueType>(spec.dimensions[2]) } });
      image->SetRegions(region);
      image->Allocate();
      generator.fill(image->GetBufferPointer());
      const std::string outdir = argv[6];
      std::ofstream analytic(outdir + "/analytic.csv");
      for (const auto& path : generator.centerline().paths)
      {
        for (const auto& q : path.points)
        {
          analytic << q.position_World_mm.x << "," << q.position_World_mm.y << ","
                   << q.position_World_mm.z << "," << q.radius_mm << "\n";
        }
      }
      const double wall = 0.5 * (spec.backgroundIntensity + spec.peakIntensity);
      return run(image, wall, 1e30, outdir, shape, argc == 8 ? downsampleArg(argv[7]) : 1U);
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
        argc == 7 ? downsampleArg(argv[6]) : 1U);
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
