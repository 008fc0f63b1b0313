// TubeSectionTracker's removal of clutter stretches from a skeleton (vtouchTubeSectionParts.h).
#include "vtouchTubeSectionParts.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace vtouch
{
namespace tube_sections
{

/// Removes the point ranges `cuts[path]` (sorted, disjoint, inclusive) from the paths: each path
/// is split into the pieces between them (the first piece keeps the path's id and head, the last
/// its tail; pieces of fewer than 2 points go); paths joined to a removed point, or to a piece
/// that goes, are detached (that end becomes free). Returns the number of junctions detached.
int cutStretches(QSkeleton& skeleton,
  const std::vector<std::vector<std::pair<int, int>>>& cuts,
  std::vector<std::vector<TubeSectionTracker::Section>>& sections)
{
  using Section = TubeSectionTracker::Section;
  const std::size_t originalPaths = skeleton.paths.size();
  // Where each original point goes: (path, index) or (-1, -1).
  std::vector<std::vector<std::pair<int, int>>> where(originalPaths);
  bool any = false;
  for (std::size_t pi = 0; pi < originalPaths; ++pi)
  {
    const int n = static_cast<int>(skeleton.paths[pi].points.size());
    where[pi].resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i)
    {
      where[pi][static_cast<std::size_t>(i)] = { static_cast<int>(pi), i };
    }
    any = any || !cuts[pi].empty();
  }
  if (!any)
  {
    return 0;
  }
  for (std::size_t pi = 0; pi < originalPaths; ++pi)
  {
    if (cuts[pi].empty())
    {
      continue;
    }
    SkeletonPath original = std::move(skeleton.paths[pi]);
    std::vector<Section> originalSections = std::move(sections[pi]);
    const int n = static_cast<int>(original.points.size());
    std::vector<char> removed(static_cast<std::size_t>(n), 0);
    for (const auto& [first, last] : cuts[pi])
    {
      for (int i = std::max(0, first); i <= std::min(n - 1, last); ++i)
      {
        removed[static_cast<std::size_t>(i)] = 1;
      }
    }
    // Pieces of consecutive kept points.
    std::vector<std::pair<int, int>> pieces;
    for (int i = 0; i < n;)
    {
      if (removed[static_cast<std::size_t>(i)])
      {
        ++i;
        continue;
      }
      int e = i;
      while (e + 1 < n && !removed[static_cast<std::size_t>(e + 1)])
      {
        ++e;
      }
      if (e - i + 1 >= 2)
      {
        pieces.emplace_back(i, e);
      }
      i = e + 1;
    }
    for (auto& w : where[pi])
    {
      w = { -1, -1 };
    }
    skeleton.paths[pi] = SkeletonPath{};
    skeleton.paths[pi].id = static_cast<int>(pi);
    sections[pi].clear();
    for (std::size_t c = 0; c < pieces.size(); ++c)
    {
      const auto [first, last] = pieces[c];
      const int id = c == 0 ? static_cast<int>(pi) : static_cast<int>(skeleton.paths.size());
      SkeletonPath piece;
      piece.id = id;
      piece.head.junction = first == 0 ? original.head.junction : -1;
      piece.tail.junction = last == n - 1 ? original.tail.junction : -1;
      piece.points.assign(original.points.begin() + first, original.points.begin() + last + 1);
      std::vector<Section> st(
        originalSections.begin() + first, originalSections.begin() + last + 1);
      for (int i = first; i <= last; ++i)
      {
        where[pi][static_cast<std::size_t>(i)] = { id, i - first };
      }
      if (c == 0)
      {
        skeleton.paths[pi] = std::move(piece);
        sections[pi] = std::move(st);
      }
      else
      {
        skeleton.paths.push_back(std::move(piece));
        sections.push_back(std::move(st));
      }
    }
    if (pieces.empty())
    {
      // Nothing of the path stays: an empty placeholder, dropped below.
      skeleton.paths[pi].head.junction = skeleton.paths[pi].tail.junction = -1;
    }
  }
  // Junctions: re-point parents and children; detach those whose parent point or child end went.
  std::vector<Junction> kept;
  std::vector<int> newIndex(skeleton.junctions.size(), -1);
  int detached = 0;
  for (std::size_t ji = 0; ji < skeleton.junctions.size(); ++ji)
  {
    Junction jn = skeleton.junctions[ji];
    const auto parent =
      where[static_cast<std::size_t>(jn.parentPath)][static_cast<std::size_t>(jn.parentPoint)];
    // The child's end: its head (index 0) or its tail (last index) of the original path.
    const std::size_t childPath = static_cast<std::size_t>(jn.childPath);
    const int childIndex =
      jn.childEnd == Junction::End::Head ? 0 : static_cast<int>(where[childPath].size()) - 1;
    const auto child = childIndex >= 0 ? where[childPath][static_cast<std::size_t>(childIndex)]
                                       : std::pair<int, int>{ -1, -1 };
    if (parent.first < 0 || child.first < 0)
    {
      ++detached;
      continue;
    }
    jn.parentPath = parent.first;
    jn.parentPoint = parent.second;
    jn.childPath = child.first;
    newIndex[ji] = static_cast<int>(kept.size());
    kept.push_back(jn);
  }
  for (SkeletonPath& path : skeleton.paths)
  {
    for (PathEnd* end : { &path.head, &path.tail })
    {
      end->junction = end->junction >= 0 ? newIndex[static_cast<std::size_t>(end->junction)] : -1;
    }
  }
  skeleton.junctions = std::move(kept);
  // A child whose junction stayed: its end refers to the junction's new index (set above). Drop
  // paths that lost every point, and pieces left on the clutter: joined to nothing (both ends
  // free, no path joins them) and without a run of 3 clean or re-traced sections (renumbering
  // ids and references).
  std::vector<char> carries(skeleton.paths.size(), 0);
  for (const Junction& jn : skeleton.junctions)
  {
    carries[static_cast<std::size_t>(jn.parentPath)] = 1;
  }
  const auto orphan = [&](std::size_t pi)
  {
    const SkeletonPath& path = skeleton.paths[pi];
    if (path.head.junction >= 0 || path.tail.junction >= 0 || carries[pi])
    {
      return false;
    }
    int run = 0;
    for (const Section x : sections[pi])
    {
      run = x == Section::Clean || x == Section::Retraced ? run + 1 : 0;
      if (run >= 3)
      {
        return false;
      }
    }
    return true;
  };
  std::vector<int> newPath(skeleton.paths.size(), -1);
  std::vector<SkeletonPath> paths;
  std::vector<std::vector<Section>> newSections;
  for (std::size_t pi = 0; pi < skeleton.paths.size(); ++pi)
  {
    if (skeleton.paths[pi].points.size() >= 2 &&
        !(pi < originalPaths ? !cuts[pi].empty() && orphan(pi) : orphan(pi)))
    {
      newPath[pi] = static_cast<int>(paths.size());
      paths.push_back(std::move(skeleton.paths[pi]));
      paths.back().id = newPath[pi];
      newSections.push_back(std::move(sections[pi]));
    }
  }
  for (Junction& jn : skeleton.junctions)
  {
    jn.parentPath = newPath[static_cast<std::size_t>(jn.parentPath)];
    jn.childPath = newPath[static_cast<std::size_t>(jn.childPath)];
  }
  skeleton.paths = std::move(paths);
  sections = std::move(newSections);
  // Labels: free ends, and junction points (only where a junction still is).
  for (SkeletonPath& path : skeleton.paths)
  {
    for (SkeletonPoint& q : path.points)
    {
      if (q.label == PointLabel::Bifurcation)
      {
        q.label = PointLabel::Ordinary;
      }
    }
    path.points.front().label =
      path.head.junction >= 0 ? PointLabel::Bifurcation : PointLabel::EndPoint;
    path.points.back().label =
      path.tail.junction >= 0 ? PointLabel::Bifurcation : PointLabel::EndPoint;
  }
  for (const Junction& jn : skeleton.junctions)
  {
    skeleton.paths[static_cast<std::size_t>(jn.parentPath)]
      .points[static_cast<std::size_t>(jn.parentPoint)]
      .label = PointLabel::Bifurcation;
  }
  return detached;
}

} // namespace tube_sections
} // namespace vtouch
