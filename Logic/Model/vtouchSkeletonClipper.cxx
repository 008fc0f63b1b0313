#include "vtouchSkeletonClipper.h"

namespace vtouch
{

SkeletonClipper::SkeletonClipper(const PieceOwnership& ownership,
  const IndexFrame& frame,
  int piece,
  double band_voxels)
  : ownership_(ownership)
  , frame_(frame)
  , piece_(piece)
  , band_voxels_(band_voxels)
{
}

bool SkeletonClipper::sends(const SkeletonPoint& p) const
{
  const Vec3 index = frame_.toIndex(p.position_World_mm);
  return ownership_.owner(index) == piece_ ||
         (band_voxels_ > 0.0 &&
           ownership_.withinBand(static_cast<std::size_t>(piece_), index, band_voxels_));
}

int SkeletonClipper::ownerOf(const SkeletonPoint& p) const
{
  return ownership_.owner(frame_.toIndex(p.position_World_mm));
}

namespace
{
/// How path `path` ends at its head or tail, in `skeleton`.
FragmentEnd pathEnd(const QSkeleton& skeleton, const PathEnd& end)
{
  FragmentEnd out;
  if (end.junction < 0 || end.junction >= static_cast<int>(skeleton.junctions.size()))
  {
    return out; // free
  }
  const Junction& j = skeleton.junctions[static_cast<std::size_t>(end.junction)];
  const SkeletonPath& parent = skeleton.paths[static_cast<std::size_t>(j.parentPath)];
  out.kind = FragmentEnd::Kind::Attached;
  const auto at = static_cast<std::size_t>(j.parentPoint);
  out.position_World_mm = parent.points[at].position_World_mm;
  if (at > 0)
  {
    out.parentBefore_World_mm = parent.points[at - 1].position_World_mm;
  }
  if (at + 1 < parent.points.size())
  {
    out.parentAfter_World_mm = parent.points[at + 1].position_World_mm;
  }
  return out;
}

FragmentEnd cutEnd(const SkeletonPoint& inside, const SkeletonPoint& beyond, int neighbour)
{
  FragmentEnd out;
  out.kind = FragmentEnd::Kind::Cut;
  out.position_World_mm = (inside.position_World_mm + beyond.position_World_mm) * 0.5;
  out.neighbourPiece = neighbour;
  return out;
}
} // namespace

std::vector<SkeletonFragment> SkeletonClipper::clip(const QSkeleton& skeleton) const
{
  std::vector<SkeletonFragment> fragments;
  for (const SkeletonPath& path : skeleton.paths)
  {
    const std::size_t n = path.points.size();
    std::vector<int> owners(n);
    std::vector<char> sent(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      owners[i] = ownerOf(path.points[i]);
      sent[i] = sends(path.points[i]) ? 1 : 0;
    }
    std::size_t i = 0;
    while (i < n)
    {
      if (!sent[i])
      {
        ++i;
        continue;
      }
      std::size_t j = i;
      while (j + 1 < n && sent[j + 1])
      {
        ++j;
      }
      SkeletonFragment f;
      f.piece = piece_;
      f.points.assign(path.points.begin() + static_cast<std::ptrdiff_t>(i),
        path.points.begin() + static_cast<std::ptrdiff_t>(j + 1));
      f.head = i == 0 ? pathEnd(skeleton, path.head)
                      : cutEnd(path.points[i], path.points[i - 1], owners[i - 1]);
      f.tail = j + 1 == n ? pathEnd(skeleton, path.tail)
                          : cutEnd(path.points[j], path.points[j + 1], owners[j + 1]);
      fragments.push_back(std::move(f));
      i = j + 1;
    }
  }
  return fragments;
}

} // namespace vtouch
