// vesseltouch-centerline-survey: the voxel-coding skeleton filter, with its defaults, over a family
// of phantoms that the accuracy tests do not pin one by one: every shape at several grid sizes
// (odd sizes put the analytic line off the voxel centres), vessel radii from ~3 to ~7 voxels,
// tapered vessels, flat (contrast-filled) profiles, rough walls over several wall seeds, noise,
// and anisotropic voxels. For each case it prints the topology found against the analytic one
// and the accuracy measures in voxels (of the longest voxel side), and says which target
// a case misses. Not a test: a case outside the list may legitimately miss (a vessel
// thinner than three voxels, a ring whose hole is narrower than the tube); the summary counts them.
//
//   vesseltouch-centerline-survey [--quick] [--only SUBSTRING] [--json FILE]
//     --quick       one grid size and one wall seed (about 30 cases, ~20 s on 2 cores)
//     --only S      the cases whose name contains S
//     --json FILE   one record per case (name, topology found and expected, mean/p95/coverage in
//                   voxels, radius error in voxels, seconds, passed, missed)
//     --dump DIR    per case DIR/<case>.output.csv (x,y,z mm, radius mm, path id, distance to the
//                   analytic line mm) and DIR/<case>.analytic.csv (x,y,z mm, radius mm, path id,
//                   distance to the output mm): where a case misses
#include "vtouchVoxelCodingSkeletonFilter.h"

#include "vtouchSkeletonTestSupport.h"

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using vtouch::PhantomShape;
using vtouch::PhantomSpec;
using Filter = vtouch::VoxelCodingSkeletonFilter<vtouch::test::FloatImage>;

struct SurveyCase
{
  std::string name;
  PhantomSpec spec;
  int downsample = -1; ///< the filter's DownsampleFactor; -1: its default (automatic)
};

struct SurveyResult
{
  vtouch::test::Topology got, want;
  vtouch::test::Accuracy accuracy; // in voxels of the longest side
  double seconds = 0.0;
  std::string missed; // empty when every target is met
  std::string error;  // the filter's exception, if any
};

std::string caseName(const PhantomSpec& s, const char* variant)
{
  std::ostringstream name;
  name << vtouch::toString(s.shape) << " " << s.dimensions[0] << "x" << s.dimensions[1] << "x"
       << s.dimensions[2] << " r" << s.radiusFraction;
  if (*variant)
  {
    name << " " << variant;
  }
  return name.str();
}

/// The survey's cases. Radii are fractions of the smallest side, as in the phantom source.
std::vector<SurveyCase> surveyCases(bool quick)
{
  const PhantomShape shapes[] = { PhantomShape::StraightTube,
    PhantomShape::Helix,
    PhantomShape::YBifurcation,
    PhantomShape::Tree,
    PhantomShape::LoopNetwork,
    PhantomShape::Circle };
  const std::vector<int> sizes = quick ? std::vector<int>{ 97 } : std::vector<int>{ 96, 97, 128 };
  const std::vector<double> radii{ 0.035, 0.05, 0.07 };
  const int wallSeeds = quick ? 2 : 6;
  std::vector<SurveyCase> cases;
  for (PhantomShape shape : shapes)
  {
    for (int n : sizes)
    {
      for (double r : radii)
      {
        PhantomSpec s;
        s.shape = shape;
        s.dimensions = { n, n, n };
        s.radiusFraction = r;
        cases.push_back({ caseName(s, ""), s });
      }
      PhantomSpec flat;
      flat.shape = shape;
      flat.dimensions = { n, n, n };
      flat.profile = PhantomSpec::Profile::Flat;
      cases.push_back({ caseName(flat, "flat"), flat });
      if (shape != PhantomShape::Circle && shape != PhantomShape::LoopNetwork)
      {
        PhantomSpec taper = flat;
        taper.profile = PhantomSpec::Profile::Gaussian;
        taper.taperRatio = 0.5;
        cases.push_back({ caseName(taper, "taper 0.5"), taper });
      }
    }
    for (int seed = 1; seed <= wallSeeds; ++seed)
    {
      PhantomSpec rough;
      rough.shape = shape;
      rough.dimensions = { 96, 96, 96 };
      rough.wallRoughness = 0.2;
      rough.seed = static_cast<std::uint32_t>(seed);
      cases.push_back({ caseName(rough, ("rough seed " + std::to_string(seed)).c_str()), rough });
    }
    PhantomSpec aniso;
    aniso.shape = shape;
    aniso.dimensions = { 97, 97, 49 };
    aniso.spacing_mm = { 1.0, 1.0, 2.0 };
    cases.push_back({ caseName(aniso, "spacing 1x1x2"), aniso });
    if (!quick)
    {
      PhantomSpec anisoX = aniso;
      anisoX.dimensions = { 65, 97, 97 };
      anisoX.spacing_mm = { 1.5, 1.0, 1.0 };
      cases.push_back({ caseName(anisoX, "spacing 1.5x1x1"), anisoX });
      PhantomSpec noisy;
      noisy.shape = shape;
      noisy.dimensions = { 96, 96, 96 };
      noisy.noiseStdDev = 30.0;
      noisy.seed = 2;
      cases.push_back({ caseName(noisy, "noise 30"), noisy });
    }
  }
  // The thick benchmark vessels, large enough for the automatic scale to code them on
  // 2x2x2 blocks: at that scale (the default) and at full resolution.
  PhantomSpec thickTree;
  thickTree.shape = PhantomShape::Tree;
  thickTree.dimensions = { 352, 352, 352 };
  thickTree.treeRadiusFractions = { 0.055, 0.045, 0.035 };
  PhantomSpec thickHelix;
  thickHelix.shape = PhantomShape::Helix;
  thickHelix.dimensions = { 256, 256, 256 };
  for (const PhantomSpec& thick : { thickTree, thickHelix })
  {
    cases.push_back({ caseName(thick, "automatic scale"), thick });
    if (!quick)
    {
      cases.push_back({ caseName(thick, "full resolution"), thick, 1 });
    }
  }
  return cases;
}

void addMiss(std::string& missed, const std::string& what)
{
  missed += (missed.empty() ? "" : ", ") + what;
}

std::string fileName(const std::string& name)
{
  std::string f = name;
  std::replace_if(
    f.begin(),
    f.end(),
    [](char ch) { return !std::isalnum(static_cast<unsigned char>(ch)) && ch != '.'; },
    '_');
  return f;
}

void dumpCase(const std::string& dir,
  const SurveyCase& c,
  const vtouch::QSkeleton& output,
  const vtouch::PhantomGenerator& generator)
{
  const std::string base = dir + "/" + fileName(c.name);
  std::ofstream out(base + ".output.csv");
  for (const vtouch::SkeletonPath& path : output.paths)
  {
    for (const vtouch::SkeletonPoint& q : path.points)
    {
      const vtouch::Vec3& x = q.position_World_mm;
      out << x.x << "," << x.y << "," << x.z << "," << q.radius_mm << "," << path.id << ","
          << generator.distanceToCenterline_mm(x) << "\n";
    }
  }
  std::ofstream analytic(base + ".analytic.csv");
  for (const vtouch::SkeletonPath& path : generator.centerline().paths)
  {
    for (const vtouch::SkeletonPoint& q : path.points)
    {
      const vtouch::Vec3& x = q.position_World_mm;
      analytic << x.x << "," << x.y << "," << x.z << "," << q.radius_mm << "," << path.id << ","
               << vtouch::test::distanceToSkeleton(output, x) << "\n";
    }
  }
}

SurveyResult runCase(const SurveyCase& c, const std::string& dumpDir)
{
  SurveyResult result;
  vtouch::PhantomGenerator generator(c.spec);
  if (!generator.ok())
  {
    result.error = generator.error();
    result.missed = "phantom";
    return result;
  }
  auto image = vtouch::test::phantomImage(generator);
  auto filter = Filter::New();
  filter->SetInput(image);
  filter->SetLowerThreshold(vtouch::test::wallThreshold(c.spec));
  if (c.downsample >= 0)
  {
    filter->SetDownsampleFactor(static_cast<unsigned int>(c.downsample));
  }
  const auto t0 = std::chrono::steady_clock::now();
  try
  {
    filter->Update();
  }
  catch (const itk::ExceptionObject& e)
  {
    result.error = e.GetDescription();
    result.missed = "no output";
    return result;
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double voxel_mm =
    std::max({ c.spec.spacing_mm[0], c.spec.spacing_mm[1], c.spec.spacing_mm[2] });
  // Junction points closer than this are one bifurcation (an output may split one in two).
  const double merge_mm = 1.5 * c.spec.radiusFraction * c.spec.referenceLength_mm();
  if (!dumpDir.empty())
  {
    dumpCase(dumpDir, c, filter->GetSkeleton(), generator);
  }
  result.got = vtouch::test::topology(filter->GetSkeleton(), merge_mm);
  result.want = vtouch::test::topology(generator.centerline(), merge_mm);
  vtouch::test::Accuracy a =
    vtouch::test::measure(filter->GetSkeleton(), generator, 1.5 * voxel_mm);
  a.mean_mm /= voxel_mm;
  a.p95_mm /= voxel_mm;
  a.radiusError_mm /= voxel_mm;
  result.accuracy = a;
  if (result.got.endPoints != result.want.endPoints ||
      result.got.bifurcations != result.want.bifurcations || result.got.loops != result.want.loops)
  {
    addMiss(result.missed, "topology");
  }
  if (a.mean_mm > 0.35)
  {
    addMiss(result.missed, "mean");
  }
  if (a.p95_mm > 1.0)
  {
    addMiss(result.missed, "p95");
  }
  if (a.coverage < 0.99)
  {
    addMiss(result.missed, "coverage");
  }
  if (a.radiusError_mm > 1.0)
  {
    addMiss(result.missed, "radius");
  }
  const std::string gaps = vtouch::test::check26Connected(filter->GetRawSkeleton(), {});
  if (!gaps.empty())
  {
    addMiss(result.missed, "26-connectivity");
  }
  return result;
}

std::string topologyText(const vtouch::test::Topology& t)
{
  return std::to_string(t.endPoints) + "/" + std::to_string(t.bifurcations) + "/" +
         std::to_string(t.loops);
}

void writeJson(std::ostream& out, const SurveyCase& c, const SurveyResult& r, bool last)
{
  out << "  {\"name\": \"" << c.name << "\", \"got\": \"" << topologyText(r.got)
      << "\", \"want\": \"" << topologyText(r.want) << "\", \"mean_vox\": " << r.accuracy.mean_mm
      << ", \"p95_vox\": " << r.accuracy.p95_mm << ", \"coverage\": " << r.accuracy.coverage
      << ", \"radius_error_vox\": " << r.accuracy.radiusError_mm << ", \"seconds\": " << r.seconds
      << ", \"passed\": " << (r.missed.empty() ? "true" : "false") << ", \"missed\": \"" << r.missed
      << "\"}" << (last ? "\n" : ",\n");
}

int usage()
{
  std::fprintf(stderr,
    "usage: vesseltouch-centerline-survey [--quick] [--only S] [--json FILE] [--dump DIR]\n");
  return 2;
}

} // namespace

int main(int argc, char** argv)
{
  bool quick = false;
  std::string only, jsonPath, dumpDir;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--quick"))
    {
      quick = true;
    }
    else if (!std::strcmp(argv[i], "--only") && i + 1 < argc)
    {
      only = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--json") && i + 1 < argc)
    {
      jsonPath = argv[++i];
    }
    else if (!std::strcmp(argv[i], "--dump") && i + 1 < argc)
    {
      dumpDir = argv[++i];
    }
    else
    {
      return usage();
    }
  }
  std::vector<SurveyCase> cases;
  for (const SurveyCase& c : surveyCases(quick))
  {
    if (only.empty() || c.name.find(only) != std::string::npos)
    {
      cases.push_back(c);
    }
  }
  std::printf("| case | ends/bifurcations/loops (want) | mean | p95 | coverage | radius err | s | "
              "missed |\n|---|---|---|---|---|---|---|---|\n");
  std::vector<SurveyResult> results;
  int passed = 0;
  for (const SurveyCase& c : cases)
  {
    const SurveyResult r = runCase(c, dumpDir);
    results.push_back(r);
    passed += r.missed.empty() ? 1 : 0;
    std::printf("| %s | %s (%s) | %.3f | %.3f | %.3f | %.2f | %.2f | %s%s%s |\n",
      c.name.c_str(),
      topologyText(r.got).c_str(),
      topologyText(r.want).c_str(),
      r.accuracy.mean_mm,
      r.accuracy.p95_mm,
      r.accuracy.coverage,
      r.accuracy.radiusError_mm,
      r.seconds,
      r.missed.c_str(),
      r.error.empty() ? "" : ": ",
      r.error.c_str());
    std::fflush(stdout);
  }
  std::printf("\n%d of %zu cases meet every target (topology, mean <= 0.35, p95 <= 1.0, coverage "
              ">= 0.99, radius within 1 voxel, 26-connected)\n",
    passed,
    cases.size());
  if (!jsonPath.empty())
  {
    std::ofstream json(jsonPath);
    json << "[\n";
    for (std::size_t i = 0; i < cases.size(); ++i)
    {
      writeJson(json, cases[i], results[i], i + 1 == cases.size());
    }
    json << "]\n";
  }
  return 0;
}
