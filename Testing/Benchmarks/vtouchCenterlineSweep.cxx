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
//            --downsample F          DownsampleFactor (when the filter has it; exit 3 otherwise).
//            --no-mask               do not write mask.raw (no scikit-image comparison needed).
// Writes <outdir>/voxelcoding.csv (x,y,z mm, radius mm, path id), <outdir>/mask.raw (uint8, the
// threshold mask, x fastest), for phantoms <outdir>/analytic.csv (x,y,z mm, radius mm), and one
// JSON line on stdout: seconds of Update(), extra_rss_bytes (peak RSS during Update() minus RSS
// before it), vessel voxels, paths and points.
#include "vtouchVoxelCodingSkeletonFilter.h"

#include "vtouchPhantomGenerator.h"

#include <itkImageFileReader.h>
#include <itkMetaImageIOFactory.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace
{
using Image = itk::Image<float, 3>;
using Filter = vtouch::VoxelCodingSkeletonFilter<Image>;

/// True when the filter has SetDownsampleFactor (added by the skeleton speed work; this tool
/// builds with or without it).
template<typename F, typename = void>
struct HasDownsampleFactor : std::false_type
{
};
template<typename F>
struct HasDownsampleFactor<F, std::void_t<decltype(std::declval<F&>().SetDownsampleFactor(1u))>>
  : std::true_type
{
};

template<typename F>
bool setDownsampleFactor(F& filter, unsigned int factor)
{
  if constexpr (HasDownsampleFactor<F>::value)
  {
    filter.SetDownsampleFactor(factor);
    return true;
  }
  else
  {
    (void)filter;
    return factor == 1;
  }
}

struct Options
{
  unsigned int downsample = 1;
  double smoothing_mm = 0.0;
  double minBranch = 2.5;
  bool vesselness = false;
  double noise = 0.0;
  bool writeMask = true;
};

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

int run(Image* image, double lower, double upper, const std::string& outdir, const Options& o)
{
  if (o.writeMask)
  {
    writeMask(image, lower, upper, outdir + "/mask.raw");
  }
  auto filter = Filter::New();
  filter->SetInput(image);
  filter->SetLowerThreshold(lower);
  filter->SetUpperThreshold(upper);
  filter->SetSmoothingWindow(o.smoothing_mm);
  filter->SetMinimumBranchLength(o.minBranch);
  filter->SetUseVesselness(o.vesselness);
  if (!setDownsampleFactor(*filter, o.downsample))
  {
    std::cerr << "this filter has no DownsampleFactor parameter\n";
    return 3;
  }
  const long long baseKb = statusKb("VmRSS:");
  std::ofstream("/proc/self/clear_refs") << "5";
  const auto t0 = std::chrono::steady_clock::now();
  filter->Update();
  const auto t1 = std::chrono::steady_clock::now();
  const long long peakKb = statusKb("VmHWM:");
  const vtouch::QSkeleton& s = filter->GetSkeleton();
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
  std::printf("{\"nx\": %lu, \"ny\": %lu, \"nz\": %lu, \"vessel_voxels\": %llu, \"seconds\": %.5f, "
              "\"extra_rss_bytes\": %lld, \"paths\": %zu, \"points\": %zu, \"downsample\": %u}\n",
    size[0],
    size[1],
    size[2],
    filter->GetNumberOfVesselVoxels(),
    std::chrono::duration<double>(t1 - t0).count(),
    (peakKb - baseKb) * 1024,
    s.paths.size(),
    s.pointCount(),
    o.downsample);
  return 0;
}

int phantom(char** a, const Options& o)
{
  vtouch::PhantomSpec spec;
  const std::string shape = a[0];
  spec.shape = shape == "Tree" ? vtouch::PhantomShape::Tree : vtouch::PhantomShape::Helix;
  spec.dimensions = { std::atoi(a[1]), std::atoi(a[2]), std::atoi(a[3]) };
  if (spec.shape == vtouch::PhantomShape::Tree)
  {
    spec.treeRadiusFractions = { 0.055, 0.045, 0.035 };
  }
  spec.noiseStdDev = o.noise;
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
  const std::string outdir = a[4];
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
      o.downsample = static_cast<unsigned int>(std::max(1, std::atoi(argv[++i])));
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
