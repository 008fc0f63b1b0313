// Voxel coding stage 7: loop closing where two SS fronts meet.
#include "vtouchVoxelCodingImpl.h"

namespace vtouch
{

double VoxelCoder::Impl::distanceToSkeleton(const std::array<double, 3>& q) const
{
  double best = std::numeric_limits<double>::infinity();
  for (const RawSkeletonPath& p : out.paths)
  {
    for (const auto& c : p.center_mm)
    {
      best = std::min(best, distance(c, q));
    }
  }
  return best;
}

void VoxelCoder::Impl::closeLoops()
{
  const StageTimer timer{ *this, "loops" };
  const std::size_t clusterCount = clusters.size();
  for (std::uint32_t c = 0; c < clusterCount; ++c)
  {
    if (clusters[c].lower.size() < 2)
    {
      continue;
    }
    const std::vector<std::uint32_t> lower = clusters[c].lower;
    for (std::uint32_t p : lower)
    {
      if (clusters[p].path >= 0)
      {
        continue;
      }
      // Side A: the cluster itself when it is on the skeleton, else another lower neighbour
      // already on it, else a trace down through another lower neighbour.
      Trace a;
      if (clusters[c].path >= 0)
      {
        a.path = clusters[c].path;
        a.point = clusters[c].point;
      }
      else
      {
        for (std::uint32_t q : lower)
        {
          if (q != p && clusters[q].path >= 0 && a.path < 0)
          {
            a.path = clusters[q].path;
            a.point = clusters[q].point;
            a.voxels.push_back(clusters[c].bestVoxel);
          }
        }
        for (std::uint32_t q : lower)
        {
          if (q != p && a.path < 0)
          {
            a = descend(clusters[q].bestVoxel, kInf, patienceFor(clusters[q]));
            a.voxels.insert(a.voxels.begin(), clusters[c].bestVoxel);
          }
        }
        if (a.path < 0)
        {
          continue;
        }
      }
      const P3 aEnd =
        a.voxels.empty() ? out.paths[a.path].center_mm[a.point] : centerOf(a.voxels.front());
      const double radius =
        std::max(out.paths[a.path].radius_mm[a.point], static_cast<double>(clusters[c].maxBs));
      const std::uint32_t start = clusters[p].bestVoxel;
      const double margin = 2.0 * radius + 2.0 * bandWidth;
      const float ignoreAbove = ss[mask.rank(start)] - static_cast<float>(margin);
      const Trace b = descend(start, ignoreAbove, patienceFor(clusters[p]));
      if (b.path < 0 || b.voxels.empty())
      {
        continue;
      }
      const double drop = ss[mask.rank(start)] - ss[mask.rank(b.voxels.back())];
      const double length = a.length + b.length + distance(aEnd, centerOf(start));
      // Both sides arriving at one place of the skeleton are one front too.
      const double apart =
        distance(out.paths[a.path].center_mm[a.point], out.paths[b.path].center_mm[b.point]);
      if (drop < margin + std::max(3.0 * bandWidth, radius) || apart < margin ||
          length < par.minimumBranchLength * radius)
      {
        continue;
      }
      // The other side of a real loop runs away from the skeleton; a trace alongside it (inside
      // a thick vessel) is the same lumen.
      const std::uint32_t middle = b.voxels[b.voxels.size() / 2];
      if (distanceToSkeleton(centerOf(middle)) <= radiusAt(middle) + bandWidth)
      {
        continue;
      }
      Trace joined;
      joined.path = a.path;
      joined.point = a.point;
      joined.voxels.assign(b.voxels.rbegin(), b.voxels.rend());
      joined.voxels.insert(joined.voxels.end(), a.voxels.begin(), a.voxels.end());
      emitPath(joined, false, b.path, b.point);
      ++out.loops;
    }
  }
}

} // namespace vtouch
