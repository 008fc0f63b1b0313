#include "vtouchCoarseSkeletonRefiner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace vtouch
{

namespace
{
// A closed cross-section larger than this many times the coarse tube's area spans a junction
// (or is cut very obliquely): its centroid would leave the axis, so the coarse centre is kept.
constexpr double kJunctionAreaRatio = 2.0;
// Section samples per radius (the grid step, within 1/2 to 2 voxels).
constexpr double kSamplesPerRadius = 8.0;
// Mean-shift steps that centre a junction's section on the branch's own disc.
constexpr int kMeanShiftIterations = 4;
// The section is searched this many coarse radii (plus one coarse voxel) around the coarse centre.
constexpr double kSearchRadii = 1.5;
// In-plane rays for the radius (the distance to the nearest background voxel centre).
constexpr int kRays = 24;
// Coarse points on each side used for the tangent of the section plane, at least.
constexpr int kTangentPoints = 2;

using P3 = std::array<double, 3>;

P3 normalized(const P3& v)
{
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return n > 0.0 ? P3{ v[0] / n, v[1] / n, v[2] / n } : P3{ 0.0, 0.0, 0.0 };
}

P3 cross(const P3& a, const P3& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
} // namespace

CoarseSkeletonRefiner::CoarseSkeletonRefiner(const SparseVesselMask& fine,
  const std::array<double, 3>& fineSpacing_mm,
  unsigned int factor)
  : Fine(fine)
  , Spacing_mm(fineSpacing_mm)
  , MinSpacing_mm(std::min({ fineSpacing_mm[0], fineSpacing_mm[1], fineSpacing_mm[2] }))
  , MaxSpacing_mm(std::max({ fineSpacing_mm[0], fineSpacing_mm[1], fineSpacing_mm[2] }))
  , Factor(std::max(1U, factor))
{
}

bool CoarseSkeletonRefiner::vesselAt(const P3& p_mm) const
{
  std::uint64_t lin = 0;
  std::uint64_t stride = 1;
  for (int a = 0; a < 3; ++a)
  {
    const double x = p_mm[a] / this->Spacing_mm[a];
    // Negative and out-of-range positions (and NaN) are outside the volume.
    if (!(x > -0.5) || !(x < static_cast<double>(this->Fine.dims()[a]) - 0.5))
    {
      return false;
    }
    lin += stride * static_cast<std::uint64_t>(x + 0.5);
    stride *= static_cast<std::uint64_t>(this->Fine.dims()[a]);
  }
  return this->Fine.test(lin);
}

CoarseSkeletonRefiner::P3 CoarseSkeletonRefiner::voxelCentre(const P3& p_mm) const
{
  P3 c{};
  for (int a = 0; a < 3; ++a)
  {
    // Inside the volume (a vessel sample): the truncation is the floor (std::floor is a libm call).
    c[a] = static_cast<double>(static_cast<std::int64_t>(p_mm[a] / this->Spacing_mm[a] + 0.5)) *
           this->Spacing_mm[a];
  }
  return c;
}

double CoarseSkeletonRefiner::rayToBackground(const P3& p_mm,
  const P3& direction,
  double step_mm,
  double limit_mm) const
{
  for (double s = step_mm; s <= limit_mm; s += step_mm)
  {
    const P3 q{
      p_mm[0] + s * direction[0], p_mm[1] + s * direction[1], p_mm[2] + s * direction[2]
    };
    if (!this->vesselAt(q))
    {
      // The background voxel's centre: BS semantics (as the full-resolution code's radius).
      double d2 = 0.0;
      for (int a = 0; a < 3; ++a)
      {
        const double c = std::round(q[a] / this->Spacing_mm[a]) * this->Spacing_mm[a];
        d2 += (c - p_mm[a]) * (c - p_mm[a]);
      }
      return std::sqrt(d2);
    }
  }
  return limit_mm;
}

CoarseSkeletonRefiner::Section CoarseSkeletonRefiner::crossSection(const P3& p_mm,
  const P3& tangent,
  double coarseRadius_mm)
{
  const P3 t = normalized(tangent);
  if (t[0] == 0.0 && t[1] == 0.0 && t[2] == 0.0)
  {
    return { p_mm, coarseRadius_mm };
  }
  // An in-plane basis (u, w): u across the axis least aligned with the tangent.
  const int axis = std::abs(t[0]) <= std::abs(t[1]) && std::abs(t[0]) <= std::abs(t[2]) ? 0
                   : std::abs(t[1]) <= std::abs(t[2])                                   ? 1
                                                                                        : 2;
  P3 e{ 0.0, 0.0, 0.0 };
  e[axis] = 1.0;
  const P3 u = normalized(cross(t, e));
  const P3 w = cross(t, u);
  const double coarseVoxel_mm = this->Factor * this->MaxSpacing_mm;
  // About 8 samples per radius, between 1/2 and 1 voxel apart. Coarser grids (up to 2 voxels)
  // halve the refinement's time on thick vessels but shift the sections near junctions: 384^3
  // tree mean / p95 0.36 / 1.28 voxel instead of 0.27 / 0.90.
  const double h =
    this->MinSpacing_mm *
    std::clamp(coarseRadius_mm / (kSamplesPerRadius * this->MinSpacing_mm), 0.5, 1.0);
  const double extent_mm = kSearchRadii * coarseRadius_mm + coarseVoxel_mm;
  const int n = static_cast<int>(std::ceil(extent_mm / h));
  const int side = 2 * n + 1;
  const auto sample = [&](int a, int b)
  {
    const double x = (a - n) * h, y = (b - n) * h;
    return P3{
      p_mm[0] + x * u[0] + y * w[0], p_mm[1] + x * u[1] + y * w[1], p_mm[2] + x * u[2] + y * w[2]
    };
  };
  this->Visited.assign(static_cast<std::size_t>(side) * static_cast<std::size_t>(side), 0);
  this->Queue.clear();
  // The section grows from the vessel sample nearest the coarse centre (within one coarse voxel:
  // block maximum puts the coarse centre up to half a block off the fine vessel).
  int start = -1;
  double best = std::numeric_limits<double>::infinity();
  const int reach = static_cast<int>(std::ceil(coarseVoxel_mm / h));
  for (int b = n - reach; b <= n + reach; ++b)
  {
    for (int a = n - reach; a <= n + reach; ++a)
    {
      const double d2 = static_cast<double>((a - n) * (a - n) + (b - n) * (b - n));
      if (d2 < best && this->vesselAt(sample(a, b)))
      {
        best = d2;
        start = b * side + a;
      }
    }
  }
  if (start < 0)
  {
    return { p_mm, coarseRadius_mm };
  }
  this->Visited[static_cast<std::size_t>(start)] = 1;
  this->Queue.push_back(start);
  // Each sample counts at the in-plane position of the voxel centre it hit, not its own: samples
  // at half-voxel positions (a block centre on an axis-aligned section) would otherwise all round
  // the same way and shift the centroid by half a voxel.
  this->SectionPoints.clear();
  double sumA = 0.0, sumB = 0.0;
  bool open = false;
  for (std::size_t q = 0; q < this->Queue.size(); ++q)
  {
    const int a = this->Queue[q] % side, b = this->Queue[q] / side;
    const P3 v = this->voxelCentre(sample(a, b));
    const double x = (v[0] - p_mm[0]) * u[0] + (v[1] - p_mm[1]) * u[1] + (v[2] - p_mm[2]) * u[2];
    const double y = (v[0] - p_mm[0]) * w[0] + (v[1] - p_mm[1]) * w[1] + (v[2] - p_mm[2]) * w[2];
    this->SectionPoints.push_back({ x, y });
    sumA += x;
    sumB += y;
    if (a == 0 || b == 0 || a == side - 1 || b == side - 1)
    {
      open = true; // the section reaches the search border: not one closed tube section
      continue;
    }
    for (const int next :
      { this->Queue[q] - 1, this->Queue[q] + 1, this->Queue[q] - side, this->Queue[q] + side })
    {
      if (!this->Visited[static_cast<std::size_t>(next)])
      {
        this->Visited[static_cast<std::size_t>(next)] = 1;
        if (this->vesselAt(sample(next % side, next / side)))
        {
          this->Queue.push_back(next);
        }
      }
    }
  }
  this->PeakBytes = std::max(this->PeakBytes,
    this->Visited.capacity() + this->Queue.capacity() * sizeof(std::int32_t) +
      this->SectionPoints.capacity() * sizeof(this->SectionPoints[0]));
  const double count = static_cast<double>(this->Queue.size());
  const double area_mm2 = count * h * h;
  constexpr double kPi = 3.14159265358979323846;
  double x = sumA / count, y = sumB / count;
  if (open || area_mm2 > kJunctionAreaRatio * kPi * coarseRadius_mm * coarseRadius_mm)
  {
    // A section through a junction (or cut along a wall): the centroid of the whole would leave
    // the axis. Mean shift with a disc of the coarse radius instead: from the coarse centre, the
    // centroid of the section's samples within one radius, a few times; a sliver of the other
    // branch pulls it far less than the whole merged section would.
    x = 0.0;
    y = 0.0;
    const double r2 = coarseRadius_mm * coarseRadius_mm;
    for (int iteration = 0; iteration < kMeanShiftIterations; ++iteration)
    {
      double sx = 0.0, sy = 0.0, k = 0.0;
      for (const auto& [qx, qy] : this->SectionPoints)
      {
        if ((qx - x) * (qx - x) + (qy - y) * (qy - y) <= r2)
        {
          sx += qx;
          sy += qy;
          k += 1.0;
        }
      }
      if (k == 0.0)
      {
        break;
      }
      x = sx / k;
      y = sy / k;
    }
  }
  const P3 c{
    p_mm[0] + x * u[0] + y * w[0], p_mm[1] + x * u[1] + y * w[1], p_mm[2] + x * u[2] + y * w[2]
  };
  double r = extent_mm;
  for (int k = 0; k < kRays; ++k)
  {
    const double phi = 2.0 * kPi * k / kRays;
    const P3 d{ std::cos(phi) * u[0] + std::sin(phi) * w[0],
      std::cos(phi) * u[1] + std::sin(phi) * w[1],
      std::cos(phi) * u[2] + std::sin(phi) * w[2] };
    r = std::min(r, this->rayToBackground(c, d, 0.5 * h, r));
  }
  return { c, std::max(r, 0.5 * this->MinSpacing_mm) };
}

std::vector<CoarseSkeletonRefiner::Section> CoarseSkeletonRefiner::refinePath(
  const RawSkeletonPath& path)
{
  const int count = static_cast<int>(path.voxels.size());
  // A coarse voxel's centre is the centre of its block of fine voxels.
  const auto fine = [&](int i)
  {
    P3 p = path.center_mm[static_cast<std::size_t>(i)];
    for (int a = 0; a < 3; ++a)
    {
      p[a] += 0.5 * (this->Factor - 1.0) * this->Spacing_mm[a];
    }
    return p;
  };
  std::vector<Section> sections(static_cast<std::size_t>(count));
  const double coarseVoxel_mm = this->Factor * this->MaxSpacing_mm;
  for (int i = 0; i < count; ++i)
  {
    // The section's normal: the chord over about one radius on each side (at least two points).
    const int k = std::max(kTangentPoints,
      static_cast<int>(std::lround(path.radius_mm[static_cast<std::size_t>(i)] / coarseVoxel_mm)));
    const P3 a = fine(std::max(0, i - k));
    const P3 b = fine(std::min(count - 1, i + k));
    sections[static_cast<std::size_t>(i)] = this->crossSection(fine(i),
      P3{ b[0] - a[0], b[1] - a[1], b[2] - a[2] },
      path.radius_mm[static_cast<std::size_t>(i)]);
  }
  return sections;
}

RawSkeleton CoarseSkeletonRefiner::refine(const RawSkeleton& coarse)
{
  const auto t0 = std::chrono::steady_clock::now();
  this->PeakBytes = 0;
  std::vector<std::vector<Section>> sections;
  sections.reserve(coarse.paths.size());
  for (const RawSkeletonPath& path : coarse.paths)
  {
    sections.push_back(this->refinePath(path));
  }
  // An attached end is its parent's point: the two must stay one voxel after the refinement.
  for (const RawJunction& j : coarse.junctions)
  {
    std::vector<Section>& child = sections[static_cast<std::size_t>(j.childPath)];
    child[j.childTail ? child.size() - 1 : 0] =
      sections[static_cast<std::size_t>(j.parentPath)][static_cast<std::size_t>(j.parentPoint)];
  }
  RawSkeleton out;
  out.paths.resize(coarse.paths.size());
  std::vector<std::vector<int>> pointMap(coarse.paths.size());
  for (std::size_t p = 0; p < coarse.paths.size(); ++p)
  {
    RawSkeletonPath& path = out.paths[p];
    path.headJunction = coarse.paths[p].headJunction;
    path.tailJunction = coarse.paths[p].tailJunction;
    for (const Section& s : sections[p])
    {
      std::array<std::int64_t, 3> voxel{};
      for (int a = 0; a < 3; ++a)
      {
        voxel[a] = std::clamp<std::int64_t>(
          std::llround(s.center_mm[a] / this->Spacing_mm[a]), 0, this->Fine.dims()[a] - 1);
      }
      pointMap[p].push_back(appendSkeletonPoint(path, voxel, s.center_mm, s.radius_mm));
    }
  }
  out.junctions = coarse.junctions;
  for (RawJunction& j : out.junctions)
  {
    j.parentPoint =
      pointMap[static_cast<std::size_t>(j.parentPath)][static_cast<std::size_t>(j.parentPoint)];
  }
  out.vesselVoxels = this->Fine.vesselCount();
  out.components = coarse.components;
  out.loops = coarse.loops;
  out.stageSeconds = coarse.stageSeconds;
  out.stageSeconds.emplace_back(
    "refine", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  out.peakBytes = std::max(coarse.peakBytes, this->PeakBytes);
  return out;
}

} // namespace vtouch
