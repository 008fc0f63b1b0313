#include "vtouchSkeletonFragmentCodec.h"

#include <cmath>

namespace vtouch
{

namespace
{
constexpr std::size_t kEnd = 11; // kind, position 3, neighbour piece, parent's neighbours 6
constexpr std::size_t kHeader = 2 + 2 * kEnd; // piece, count, head, tail
constexpr std::size_t kPoint = 10; // position 3, tangent 3, curvature, torsion, radius, label

void putEnd(std::vector<double>& d, const FragmentEnd& e)
{
  d.push_back(static_cast<double>(static_cast<int>(e.kind)));
  d.push_back(e.position_World_mm.x);
  d.push_back(e.position_World_mm.y);
  d.push_back(e.position_World_mm.z);
  d.push_back(static_cast<double>(e.neighbourPiece));
  for (const Vec3& v : { e.parentBefore_World_mm, e.parentAfter_World_mm })
  {
    d.insert(d.end(), { v.x, v.y, v.z });
  }
}

bool getEnd(const double* d, FragmentEnd& e)
{
  const double kind = d[0];
  if (!(kind == 0.0 || kind == 1.0 || kind == 2.0))
  {
    return false;
  }
  e.kind = static_cast<FragmentEnd::Kind>(static_cast<int>(kind));
  e.position_World_mm = { d[1], d[2], d[3] };
  e.neighbourPiece = static_cast<int>(d[4]);
  e.parentBefore_World_mm = { d[5], d[6], d[7] };
  e.parentAfter_World_mm = { d[8], d[9], d[10] };
  return e.position_World_mm.isFinite() || e.kind == FragmentEnd::Kind::Free;
}
} // namespace

std::vector<double> SkeletonFragmentCodec::encode(const std::vector<SkeletonFragment>& fragments)
{
  std::vector<double> d;
  d.push_back(static_cast<double>(fragments.size()));
  for (const SkeletonFragment& f : fragments)
  {
    d.push_back(static_cast<double>(f.piece));
    d.push_back(static_cast<double>(f.points.size()));
    putEnd(d, f.head);
    putEnd(d, f.tail);
    for (const SkeletonPoint& p : f.points)
    {
      d.insert(d.end(),
        { p.position_World_mm.x,
          p.position_World_mm.y,
          p.position_World_mm.z,
          p.tangent_World.x,
          p.tangent_World.y,
          p.tangent_World.z,
          p.curvature_per_mm,
          p.torsion_per_mm,
          p.radius_mm,
          static_cast<double>(static_cast<int>(p.label)) });
    }
  }
  return d;
}

bool SkeletonFragmentCodec::decode(const double* data,
  std::size_t size,
  std::vector<SkeletonFragment>& out,
  std::string& error)
{
  if (size == 0)
  {
    error = "no fragment count";
    return false;
  }
  const double count = data[0];
  if (!(count >= 0.0) || count != std::floor(count))
  {
    error = "bad fragment count";
    return false;
  }
  std::size_t at = 1;
  for (std::size_t f = 0; f < static_cast<std::size_t>(count); ++f)
  {
    if (at + kHeader > size)
    {
      error = "truncated fragment header";
      return false;
    }
    SkeletonFragment fragment;
    fragment.piece = static_cast<int>(data[at]);
    const double points = data[at + 1];
    if (!(points >= 1.0) || points != std::floor(points) ||
        at + kHeader + static_cast<std::size_t>(points) * kPoint > size)
    {
      error = "bad or truncated point count";
      return false;
    }
    if (!getEnd(data + at + 2, fragment.head) || !getEnd(data + at + 2 + kEnd, fragment.tail))
    {
      error = "bad fragment end";
      return false;
    }
    at += kHeader;
    fragment.points.resize(static_cast<std::size_t>(points));
    for (SkeletonPoint& p : fragment.points)
    {
      const double* q = data + at;
      p.position_World_mm = { q[0], q[1], q[2] };
      p.tangent_World = { q[3], q[4], q[5] };
      p.curvature_per_mm = q[6];
      p.torsion_per_mm = q[7];
      p.radius_mm = q[8];
      const int label = static_cast<int>(q[9]);
      if (!p.position_World_mm.isFinite() || label < 0 || label > 2)
      {
        error = "bad point";
        return false;
      }
      p.label = static_cast<PointLabel>(label);
      at += kPoint;
    }
    out.push_back(std::move(fragment));
  }
  if (at != size)
  {
    error = "trailing values after the fragments";
    return false;
  }
  return true;
}

} // namespace vtouch
