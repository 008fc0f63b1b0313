#include "vtouchQSkeleton.h"

#include <sstream>

namespace vtouch
{

std::size_t QSkeleton::pointCount() const
{
  std::size_t n = 0;
  for (const SkeletonPath& path : this->paths)
  {
    n += path.points.size();
  }
  return n;
}

namespace
{
std::string checkEnd(const QSkeleton& s,
  const SkeletonPath& path,
  const PathEnd& end,
  Junction::End which)
{
  if (end.junction < 0)
  {
    return {};
  }
  std::ostringstream msg;
  if (end.junction >= static_cast<int>(s.junctions.size()))
  {
    msg << "path " << path.id << " refers to missing junction " << end.junction;
    return msg.str();
  }
  const Junction& j = s.junctions[end.junction];
  if (j.childPath != path.id || j.childEnd != which)
  {
    msg << "junction " << end.junction << " does not point back to path " << path.id;
    return msg.str();
  }
  return {};
}
} // namespace

std::string QSkeleton::validate() const
{
  std::ostringstream msg;
  for (std::size_t i = 0; i < this->paths.size(); ++i)
  {
    const SkeletonPath& path = this->paths[i];
    if (path.id != static_cast<int>(i))
    {
      msg << "path at index " << i << " has id " << path.id;
      return msg.str();
    }
    if (path.points.empty())
    {
      msg << "path " << i << " has no points";
      return msg.str();
    }
    std::string err = checkEnd(*this, path, path.head, Junction::End::Head);
    if (err.empty())
    {
      err = checkEnd(*this, path, path.tail, Junction::End::Tail);
    }
    if (!err.empty())
    {
      return err;
    }
  }
  for (std::size_t k = 0; k < this->junctions.size(); ++k)
  {
    const Junction& j = this->junctions[k];
    const int nPaths = static_cast<int>(this->paths.size());
    if (j.childPath < 0 || j.childPath >= nPaths || j.parentPath < 0 || j.parentPath >= nPaths)
    {
      msg << "junction " << k << " names a missing path";
      return msg.str();
    }
    const int nParent = static_cast<int>(this->paths[j.parentPath].points.size());
    if (j.parentPoint < 0 || j.parentPoint >= nParent)
    {
      msg << "junction " << k << " names point " << j.parentPoint << " outside path "
          << j.parentPath;
      return msg.str();
    }
  }
  return {};
}

} // namespace vtouch
