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
//     --lumen-floor for rough-walled cases, also the mean distance from the analytic line of the
//                   thresholded lumen's own cross-section centroids (normal to the analytic line,
//                   away from junctions and ends), raw and averaged along the path over the
//                   filter's position window (+-4 radii): what an ideal centroid-and-smoothing
//                   estimator scores, i.e. how much of a rough case's error is the phantom's
//                   lopsided lumen rather than the method
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

/// Mean distances (voxels) of the lumen's own centroids from the analytic line (--lumen-floor).
struct LumenFloor
{
  double raw = -1.0;
  double smoothed = -1.0;
};

struct SurveyResult
{
  LumenFloor floor;
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
  if (s.shape == PhantomShape::WindingLine && s.windingPeriods == 1.0)
  {
    name << " sinuous";
  }
  if (*variant)
  {
    name << " " << variant;
  }
  return name.str();
}

/// A phantom of `shape` with the phantom source's defaults, except the winding line: amplitude 0.1
/// N over one period, a sinuous vessel (the defaults fold the tube at every crest; that case is
/// surveyed once, apart).
PhantomSpec baseSpec(PhantomShape shape)
{
  PhantomSpec s;
  s.shape = shape;
  if (shape == PhantomShape::WindingLine)
  {
    s.windingAmplitudeFraction = 0.1;
    s.windingPeriods = 1.0;
  }
  return s;
}

/// The survey's cases. Radii are fractions of the smallest side, as in the phantom source.
std::vector<SurveyCase> surveyCases(bool quick)
{
  const PhantomShape shapes[] = { PhantomShape::StraightTube,
    PhantomShape::Helix,
    PhantomShape::YBifurcation,
    PhantomShape::Tree,
    PhantomShape::LoopNetwork,
    PhantomShape::Circle,
    PhantomShape::WindingLine };
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
        PhantomSpec s = baseSpec(shape);
        s.dimensions = { n, n, n };
        s.radiusFraction = r;
        cases.push_back({ caseName(s, ""), s });
      }
      PhantomSpec flat = baseSpec(shape);
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
      PhantomSpec rough = baseSpec(shape);
      rough.dimensions = { 96, 96, 96 };
      rough.wallRoughness = 0.2;
      rough.seed = static_cast<std::uint32_t>(seed);
      cases.push_back({ caseName(rough, ("rough seed " + std::to_string(seed)).c_str()), rough });
    }
    PhantomSpec aniso = baseSpec(shape);
    aniso.dimensions = { 97, 97, 49 };
    aniso.spacing_mm = { 1.0, 1.0, 2.0 };
    cases.push_back({ caseName(aniso, "spacing 1x1x2"), aniso });
    if (!quick)
    {
      PhantomSpec anisoX = aniso;
      anisoX.dimensions = { 65, 97, 97 };
      anisoX.spacing_mm = { 1.5, 1.0, 1.0 };
      cases.push_back({ caseName(anisoX, "spacing 1.5x1x1"), anisoX });
      PhantomSpec noisy = baseSpec(shape);
      noisy.dimensions = { 96, 96, 96 };
      noisy.noiseStdDev = 30.0;
      noisy.seed = 2;
      cases.push_back({ caseName(noisy, "noise 30"), noisy });
    }
  }
  // Yi & Hayward's winding line as the phantom source makes it by default: its crests bend with a
  // radius of 0.02 N, tighter than the vessel (0.05 N), so the tube folds onto itself there and
  // the mask has no single medial axis; it misses by construction.
  PhantomSpec folded;
  folded.shape = PhantomShape::WindingLine;
  cases.push_back({ caseName(folded, "default amplitude 0.2, 2 periods (folds)"), folded });
  // The 4x4-voxel column (the failure case of Lee-style thinning) through the volume.
  PhantomSpec column;
  column.shape = PhantomShape::Column;
  column.dimensions = { 40, 40, 100 };
  cases.push_back({ caseName(column, ""), column });
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

LumenFloor lumenFloor(const vtouch::PhantomGenerator& generator,
  const vtouch::test::FloatImage* image,
  double threshold)
{
  using vtouch::Vec3;
  const PhantomSpec& spec = generator.spec();
  const auto size = image->GetLargestPossibleRegion().GetSize();
  const float* v = image->GetBufferPointer();
  const auto vessel = [&](const Vec3& p)
  {
    std::int64_t i[3];
    const double xyz[3] = { p.x, p.y, p.z };
    for (int a = 0; a < 3; ++a)
    {
      i[a] = std::llround((xyz[a] - spec.origin_mm[a]) / spec.spacing_mm[a]);
      if (i[a] < 0 || i[a] >= static_cast<std::int64_t>(size[a]))
      {
        return false;
      }
    }
    return v[i[0] + size[0] * (i[1] + size[1] * i[2])] >= threshold;
  };
  const vtouch::QSkeleton& line = generator.centerline();
  std::vector<Vec3> junctionPoints;
  for (const vtouch::Junction& j : line.junctions)
  {
    junctionPoints.push_back(line.paths[j.parentPath].points[j.parentPoint].position_World_mm);
  }
  const double voxel = std::min({ spec.spacing_mm[0], spec.spacing_mm[1], spec.spacing_mm[2] });
  double rawSum = 0.0, smoothSum = 0.0;
  int count = 0;
  for (const vtouch::SkeletonPath& path : line.paths)
  {
    const auto& pts = path.points;
    std::vector<Vec3> offset(pts.size());
    std::vector<char> valid(pts.size(), 0);
    for (std::size_t k = 0; k < pts.size(); ++k)
    {
      const Vec3 q = pts[k].position_World_mm;
      const double r = pts[k].radius_mm;
      bool nearJunction = false;
      for (const Vec3& j : junctionPoints)
      {
        nearJunction = nearJunction || (q - j).norm() < 3.0 * r;
      }
      const bool nearEnd = (q - pts.front().position_World_mm).norm() < 2.0 * r ||
                           (q - pts.back().position_World_mm).norm() < 2.0 * r;
      if (nearJunction || nearEnd)
      {
        continue;
      }
      const Vec3 t = pts[k].tangent_World;
      const Vec3 helper = std::abs(t.x) < 0.9 ? Vec3{ 1, 0, 0 } : Vec3{ 0, 1, 0 };
      Vec3 u = t.cross(helper);
      u = u * (1.0 / u.norm());
      const Vec3 w = t.cross(u);
      Vec3 sum{ 0, 0, 0 };
      int n = 0;
      const double step = 0.2 * voxel;
      const double extent = 1.6 * r;
      for (double a = -extent; a <= extent; a += step)
      {
        for (double b = -extent; b <= extent; b += step)
        {
          const Vec3 p = q + u * a + w * b;
          if (a * a + b * b <= extent * extent && vessel(p))
          {
            sum = sum + (u * a + w * b);
            ++n;
          }
        }
      }
      if (n > 0)
      {
        offset[k] = sum * (1.0 / n);
        valid[k] = 1;
      }
    }
    // Average the offsets along the path over the filter's position window (+-4 radii).
    std::vector<double> arc(pts.size(), 0.0);
    for (std::size_t k = 1; k < pts.size(); ++k)
    {
      arc[k] = arc[k - 1] + (pts[k].position_World_mm - pts[k - 1].position_World_mm).norm();
    }
    for (std::size_t k = 0; k < pts.size(); ++k)
    {
      if (!valid[k])
      {
        continue;
      }
      const double window = 4.0 * std::max(voxel, pts[k].radius_mm);
      Vec3 mean{ 0, 0, 0 };
      int n = 0;
      for (std::size_t j = 0; j < pts.size(); ++j)
      {
        if (valid[j] && std::abs(arc[j] - arc[k]) <= window)
        {
          mean = mean + offset[j];
          ++n;
        }
      }
      rawSum += offset[k].norm();
      smoothSum += (mean * (1.0 / n)).norm();
      ++count;
    }
  }
  const double maxSpacing =
    std::max({ spec.spacing_mm[0], spec.spacing_mm[1], spec.spacing_mm[2] });
  return count ? LumenFloor{ rawSum / count / maxSpacing, smoothSum / count / maxSpacing }
               : LumenFloor{};
}

SurveyResult runCase(const SurveyCase& c, const std::string& dumpDir, bool floor)
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
  if (floor && c.spec.wallRoughness > 0.0)
  {
    result.floor = lumenFloor(generator, image, vtouch::test::wallThreshold(c.spec));
  }
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
      << ", \"radius_error_vox\": " << r.accuracy.radiusError_mm
      << ", \"lumen_centroid_raw_vox\": " << r.floor.raw
      << ", \"lumen_centroid_averaged_vox\": " << r.floor.smoothed << ", \"seconds\": " << r.seconds
      << ", \"passed\": " << (r.missed.empty() ? "true" : "false") << ", \"missed\": \"" << r.missed
      << "\"}" << (last ? "\n" : ",\n");
}

int usage()
{
  std::fprintf(stderr,
    "usage: vesseltouch-centerline-survey [--quick] [--only S] [--json FILE] [--dump DIR] "
    "[--lumen-floor]\n");
  return 2;
}

} // namespace

int main(int argc, char** argv)
{
  bool quick = false;
  std::string only, jsonPath, dumpDir;
  bool floor = false;
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
    else if (!std::strcmp(argv[i], "--lumen-floor"))
    {
      floor = true;
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
    const SurveyResult r = runCase(c, dumpDir, floor);
    results.push_back(r);
    passed += r.missed.empty() ? 1 : 0;
    std::string name = c.name;
    if (r.floor.raw >= 0.0)
    {
      char text[96];
      std::snprintf(text,
        sizeof text,
        " (lumen centroids: raw %.3f, averaged %.3f)",
        r.floor.raw,
        r.floor.smoothed);
      name += text;
    }
    std::printf("| %s | %s (%s) | %.3f | %.3f | %.3f | %.2f | %.2f | %s%s%s |\n",
      name.c_str(),
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
