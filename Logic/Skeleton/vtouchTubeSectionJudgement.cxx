// TubeSectionTracker's phase 1 (vtouchTubeSectionParts.h): a path's sections and which of them are
// clean (the rules in vtouchTubeSectionTracker.h, 1-2).
#include "vtouchTubeSectionParts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace vtouch
{
namespace tube_sections
{
/// Phase 1 (the header's 1-2): the sections of `path` and which of them are clean; the points
/// judged and not clean are counted into `counts`.
PathJudgement judgePath(const SkeletonPath& path,
  const std::vector<int>& attachedPoints,
  const std::vector<Zone>& zones,
  const SectionSampler& sampler,
  const TubeSectionTracker::Settings& s,
  TubeSectionTracker::Result& counts)
{
  const double voxel = sampler.voxel_mm();
  std::vector<double> rho;
  const int n = static_cast<int>(path.points.size());
  PathJudgement pj;
  auto& sec = pj.sec;
  auto& arc = pj.arc;
  auto& cuts = pj.cuts;
  auto& vessel = pj.vessel;
  auto& vesselMedian = pj.vesselMedian;
  // Sections.
  sec.resize(static_cast<std::size_t>(n));
  arc.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i)
  {
    const SkeletonPoint& q = path.points[static_cast<std::size_t>(i)];
    if (i > 0)
    {
      arc[static_cast<std::size_t>(i)] =
        arc[static_cast<std::size_t>(i - 1)] +
        (q.position_World_mm - path.points[static_cast<std::size_t>(i - 1)].position_World_mm)
            .norm() /
          voxel;
    }
    PointSection& ps = sec[static_cast<std::size_t>(i)];
    for (const Zone& z : zones)
    {
      ps.zone = ps.zone || (q.position_World_mm - z.centre).norm() <= z.radius;
    }
    Vec3 t, u, v;
    SectionSampler::sectionBasis(q.tangent_World, t, u, v);
    const double R = std::max(0.5, q.radius_mm / voxel);
    sectionRays(sampler, q.position_World_mm, u, v, 2.0 * R + 4.0, s, rho);
    ps.s = median(rho);
    const double longest = *std::max_element(rho.begin(), rho.end());
    ps.round =
      ps.s > 0.0 && longest <= ps.s + std::max(s.roundExcess_voxels, s.roundExcessFraction * ps.s);
  }
  // Vessels: the pieces of the path between the points where other paths join it.
  cuts = { 0, std::max(0, n - 1) };
  cuts.insert(cuts.end(), attachedPoints.begin(), attachedPoints.end());
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  vessel.assign(static_cast<std::size_t>(n), 0);
  for (std::size_t c = 0; c + 1 < cuts.size(); ++c)
  {
    for (int i = cuts[c]; i <= cuts[c + 1]; ++i)
    {
      vessel[static_cast<std::size_t>(i)] = static_cast<int>(c);
    }
  }
  // The tube's radius along each vessel: lower quartile of the round sections' s in a window.
  vesselMedian.assign(cuts.size(), 0.0);
  for (std::size_t c = 0; c + 1 < cuts.size(); ++c)
  {
    std::vector<double> x;
    for (int i = cuts[c]; i <= cuts[c + 1]; ++i)
    {
      if (sec[static_cast<std::size_t>(i)].round)
      {
        x.push_back(sec[static_cast<std::size_t>(i)].s);
      }
    }
    vesselMedian[c] = x.empty() ? 0.0 : median(x);
  }
  const auto window = [&](int i)
  {
    const int c = vessel[static_cast<std::size_t>(i)];
    return std::max(s.radiusWindow_voxels, s.radiusWindowRadii * vesselMedian[c]);
  };
  for (int i = 0; i < n; ++i)
  {
    PointSection& ps = sec[static_cast<std::size_t>(i)];
    if (ps.zone)
    {
      continue;
    }
    ++counts.pointsJudged;
    const double w = window(i);
    std::vector<double> x;
    for (int j = 0; j < n; ++j)
    {
      // Across the points where other paths join: the coder joins paths on the clutter to
      // the vessel inside it, and a vessel's piece between two such points is all clutter.
      if (sec[static_cast<std::size_t>(j)].round &&
          std::abs(arc[static_cast<std::size_t>(j)] - arc[static_cast<std::size_t>(i)]) <= w)
      {
        x.push_back(sec[static_cast<std::size_t>(j)].s);
      }
    }
    const double tau = lowerQuartile(x);
    ps.clean = ps.round && std::isfinite(tau) &&
               ps.s <= tau + std::max(s.radiusExcess_voxels, s.radiusExcessFraction * tau);
    counts.pointsNotClean += ps.clean ? 0 : 1;
  }
  for (int i = 0, run = 0; i < n && !pj.tube; ++i)
  {
    run = sec[static_cast<std::size_t>(i)].clean ? run + 1 : 0;
    pj.tube = run >= s.minimumAnchorPoints;
  }
  return pj;
}

} // namespace tube_sections
} // namespace vtouch
