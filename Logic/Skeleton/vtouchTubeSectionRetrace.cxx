// TubeSectionTracker's phase 2 (vtouchTubeSectionRetracer.h): a path's stretches re-traced along
// the tube, or planned as clutter to cut (the rules in vtouchTubeSectionTracker.h, 2-4). Here:
// PathRetracer's run, and the stretches found and planned in turn (rule 2); the phases it calls
// are listed in vtouchTubeSectionRetracer.h.
#include "vtouchTubeSectionRetracer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace vtouch
{
namespace tube_sections
{

namespace
{
double medianRadius_mm(const SkeletonPath& path)
{
  std::vector<double> x;
  for (const SkeletonPoint& q : path.points)
  {
    x.push_back(q.radius_mm);
  }
  return median(x);
}
} // namespace

PathRetracer::PathRetracer(QSkeleton& skeleton_,
  std::size_t pi_,
  const PathJudgement& judgement,
  const std::vector<std::vector<int>>& realJunctionPoints_,
  const std::vector<Zone>& zones_,
  const SectionSampler& sampler_,
  double largestSpacing_,
  const Settings& s_,
  TubeSectionTracker::Result& result_,
  std::vector<std::vector<std::pair<int, int>>>& clutterCuts_)
  : skeleton(skeleton_)
  , pi(pi_)
  , path(skeleton_.paths[pi_])
  , sec(judgement.sec)
  , arc(judgement.arc)
  , vessel(judgement.vessel)
  , vesselMedian(judgement.vesselMedian)
  , realJunctionPoints(realJunctionPoints_)
  , zones(zones_)
  , sampler(sampler_)
  , largestSpacing(largestSpacing_)
  , s(s_)
  , result(result_)
  , clutterCuts(clutterCuts_)
  , status(result_.sections[pi_])
  , n(static_cast<int>(skeleton_.paths[pi_].points.size()))
  , voxel(sampler_.voxel_mm())
  , pathMedianRadius(medianRadius_mm(skeleton_.paths[pi_]))
{
}

void PathRetracer::run()
{
  status.assign(static_cast<std::size_t>(n), Section::Junction);
  if (n < 3)
  {
    return; // no stretch between two anchors, nor a free end with an anchor before it
  }
  setJudgedSections();
  std::vector<RetracePlan> plans;
  planStretches(plans);
  if (!plans.empty())
  {
    applyPlans(plans);
  }
}

/// Each point's section as phase 1 judged it: in a junction's zone, clean or not.
void PathRetracer::setJudgedSections()
{
  for (int i = 0; i < n; ++i)
  {
    const PointSection& ps = sec[static_cast<std::size_t>(i)];
    status[static_cast<std::size_t>(i)] =
      ps.zone ? Section::Junction : (ps.clean ? Section::Clean : Section::NotClean);
  }
}

// Stretches (rule 2): runs of points between anchors that hold a judged point that is not clean.
// Junction zones inside a run are tracked through: the coder joined paths that run on the
// clutter to this one there; they are re-attached to the track.
int PathRetracer::stretchEnd(int j, bool& judgedNotClean)
{
  int k = j;
  judgedNotClean = false;
  while (k < n && !anchor(k))
  {
    judgedNotClean = judgedNotClean || !sec[static_cast<std::size_t>(k)].zone;
    ++k;
  }
  // Across lone clean points, when a track from the tube before the stretch enters it (lone:
  // project rule, issue 16 item 5).
  while (judgedNotClean && j >= 1 && k < n)
  {
    const double r = tubeRadius(j - 1, k);
    if (!std::isfinite(r) || !lone(k, r))
    {
      break;
    }
    ++result.loneSectionsCrossed;
    ++k;
    while (k < n && !anchor(k))
    {
      ++k;
    }
  }
  return k;
}

/// Each stretch in turn: re-traced by the tube's track (rule 3: between two anchors, or a free
/// end from its anchor), else judged as clutter to cut (rule 4).
void PathRetracer::planStretches(std::vector<RetracePlan>& plans)
{
  int j = 0;
  while (j < n)
  {
    if (anchor(j))
    {
      ++j;
      continue;
    }
    bool judgedNotClean = false;
    const int k = stretchEnd(j, judgedNotClean);
    if (!judgedNotClean)
    {
      j = k;
      continue; // a junction's zone between clean points: the coder's junction stays
    }
    ++result.stretches;
    const std::size_t plansBefore = plans.size();
    StretchTracks tracks; // of a stretch between two anchors
    const bool freeHead = j == 0 && path.head.junction < 0;
    const bool freeTail = k == n && path.tail.junction < 0;
    const double stretchLength_mm = (arc[static_cast<std::size_t>(std::min(k, n - 1))] -
                                      arc[static_cast<std::size_t>(std::max(j - 1, 0))]) *
                                    voxel;
    const double maxLength_mm = s.maximumTrackFactor * stretchLength_mm + 4.0 * voxel;
    if (j >= 1 && k <= n - 1)
    {
      planBetweenAnchors(j, k, maxLength_mm, plans, tracks);
    }
    else if (freeTail && j >= 1)
    {
      planFreeEnd(j - 1, +1, stretchLength_mm, plans);
    }
    else if (freeHead && k <= n - 1)
    {
      planFreeEnd(k, -1, stretchLength_mm, plans);
    }
    if (plans.size() == plansBefore)
    {
      planClutterCut(j, k, tracks, plans);
    }
    j = k;
  }
}

} // namespace tube_sections
} // namespace vtouch
