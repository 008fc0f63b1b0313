#include "vtouchSkeletonBenchmarkSupport.h"

#include "vtouchPhantomGenerator.h"

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <vector>

namespace vtouch
{
namespace benchmark
{
namespace
{
/// A "Key:   123 kB" line of /proc/self/status, in kB; -1 when absent.
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
} // namespace

Image::Pointer makePhantom(const std::string& shape,
  int nx,
  int ny,
  int nz,
  double noiseStdDev,
  const std::string& analyticCsvPath,
  double& wall,
  std::string& error)
{
  PhantomSpec spec;
  spec.shape = shape == "Tree" ? PhantomShape::Tree : PhantomShape::Helix;
  spec.dimensions = { nx, ny, nz };
  if (spec.shape == PhantomShape::Tree)
  {
    spec.treeRadiusFractions = { 0.055, 0.045, 0.035 };
  }
  spec.noiseStdDev = noiseStdDev;
  PhantomGenerator generator(spec);
  if (!generator.ok())
  {
    error = generator.error();
    return nullptr;
  }
  auto image = Image::New();
  Image::RegionType region;
  region.SetSize({ { static_cast<itk::SizeValueType>(nx),
    static_cast<itk::SizeValueType>(ny),
    static_cast<itk::SizeValueType>(nz) } });
  image->SetRegions(region);
  image->Allocate();
  generator.fill(image->GetBufferPointer());
  std::ofstream analytic(analyticCsvPath);
  for (const auto& path : generator.centerline().paths)
  {
    for (const auto& q : path.points)
    {
      analytic << q.position_World_mm.x << "," << q.position_World_mm.y << ","
               << q.position_World_mm.z << "," << q.radius_mm << "\n";
    }
  }
  wall = 0.5 * (spec.backgroundIntensity + spec.peakIntensity);
  return image;
}

void writeThresholdMask(const Image* image, double lower, double upper, const std::string& path)
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

void writeSkeletonCsv(const QSkeleton& skeleton, const std::string& path)
{
  std::ofstream csv(path);
  for (const auto& p : skeleton.paths)
  {
    for (const auto& q : p.points)
    {
      csv << q.position_World_mm.x << "," << q.position_World_mm.y << "," << q.position_World_mm.z
          << "," << q.radius_mm << "," << p.id << "\n";
    }
  }
}

void PeakMemoryProbe::start()
{
  this->BaseKb = statusKb("VmRSS:");
  std::ofstream("/proc/self/clear_refs") << "5";
}

long long PeakMemoryProbe::extraBytes() const
{
  return (statusKb("VmHWM:") - this->BaseKb) * 1024;
}

UpdateCost measureUpdate(itk::ProcessObject* filter)
{
  PeakMemoryProbe memory;
  memory.start();
  const auto t0 = std::chrono::steady_clock::now();
  filter->Update();
  UpdateCost cost;
  cost.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  cost.extraBytes = memory.extraBytes();
  return cost;
}

} // namespace benchmark
} // namespace vtouch
