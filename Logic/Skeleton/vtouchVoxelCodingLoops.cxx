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

void VoxelCoder::Impl::pruneStubEnds(std::size_t firstPath)
{
  for (std::size_t p = firstPath; p < out.paths.size(); ++p)
  {
    RawSkeletonPath& path = out.paths[p];
    const int n = static_cast<int>(path.center_mm.size());
    int first = n, last = -1; // the outermost points other paths attach to
    for (const RawJunction& j : out.junctions)
    {
      if (j.parentPath == static_cast<int>(p))
      {
        first = std::min(first, j.parentPoint);
        last = std::max(last, j.parentPoint);
      }
    }
    if (last < 0)
    {
      continue;
    }
    const auto stubLength = [&](int from, int to)
    {
      double length = 0.0;
      for (int i = std::min(from, to); i < std::max(from, to); ++i)
      {
        length += distance(path.center_mm[i], path.center_mm[i + 1]);
      }
      return length;
    };
    const auto isStub = [&](int junctionPoint, int end)
    {
      return junctionPoint != end &&
             stubLength(junctionPoint, end) <
               std::max(par.minimumBranchLength * nearbyRadius(static_cast<int>(p), junctionPoint),
                 2.0 * bandWidth);
    };
    if (path.tailJunction < 0 && isStub(last, n - 1))
    {
      path.voxels.resize(static_cast<std::size_t>(last) + 1);
      path.center_mm.resize(static_cast<std::size_t>(last) + 1);
      path.radius_mm.resize(static_cast<std::size_t>(last) + 1);
    }
    if (path.headJunction < 0 && first < static_cast<int>(path.center_mm.size()) - 1 &&
        isStub(first, 0))
    {
      path.voxels.erase(path.voxels.begin(), path.voxels.begin() + first);
      path.center_mm.erase(path.center_mm.begin(), path.center_mm.begin() + first);
      path.radius_mm.erase(path.radius_mm.begin(), path.radius_mm.begin() + first);
      for (RawJunction& j : out.junctions)
      {
        if (j.parentPath == static_cast<int>(p))
        {
          j.parentPoint -= first;
        }
      }
    }
  }
}

} // namespace vtouch
