// TubeSectionTracker's phase 2 on one path (internal to Logic/Skeleton; the rules are in
// vtouchTubeSectionTracker.h, 2-4, and Docs/CENTERLINES.md, "Raw angiograms", step 4): the
// path's stretches found, each re-traced along the tube or planned as clutter to cut, and the
// plans applied to the path. TubeSectionTracker runs one PathRetracer per path.
// The phases, one file each:
//  - the section queries a phase asks (anchors, the tube's radius, a track's heading, wider than
//    the tube, lone clean points, junctions a track reached): vtouchTubeSectionRetracerQueries.cxx;
//  - the stretches found and planned in turn (rule 2): vtouchTubeSectionRetrace.cxx;
//  - a stretch re-traced by the tube's track (rule 3; one function for either direction along
//    the path): vtouchTubeSectionRetracerTracks.cxx;
//  - a stretch no track crossed judged as clutter (rule 4): vtouchTubeSectionRetracerCut.cxx;
//  - the plans applied and the path re-smoothed: vtouchTubeSectionRetracerApply.cxx.
#pragma once

#include "vtouchTubeSectionParts.h"

#include <cstddef>
#include <utility>
#include <vector>

namespace vtouch
{
namespace tube_sections
{

/// A stretch's replacement: the points [first, last] replaced by `positions` (a track), or
/// removed (clutter).
struct RetracePlan
{
  int first; ///< first point replaced
  int last;  ///< last point replaced (inclusive); may be n - 1 (a free tail) or first - 1
  std::vector<Vec3> positions;
  double radiusFrom_mm, radiusTo_mm;
  bool remove = false; ///< clutter: the points go (the path is split there or its end trimmed)
  std::vector<Vec3> before{}; ///< remove: the tube's track kept before the cut
  std::vector<Vec3> after{};  ///< remove: the tube's track kept after the cut
  /// A free end re-traced as far as the tube goes (+1 the tail, -1 the head; 0 not): paths
  /// joined to the stretch farther than `joinReach_mm` from the track are detached.
  int freeEnd = 0;
  double joinReach_mm = 0.0;
};

/// The tracks a stretch between two anchors got (kept beside a cut when it is clutter, rule 4):
/// each the confirmedPart of the track from its side; empty when none was followed.
struct StretchTracks
{
  Track forward;
  Track backward;
  double rBackward_voxels = 0.0; ///< the backward track's tube radius (0: none was followed)
};

/// Phase 2 on path `pi` of `skeleton` (TubeSectionTracker runs one per path); `run` once.
class PathRetracer
{
public:
  using Section = TubeSectionTracker::Section;

  PathRetracer(QSkeleton& skeleton,
    std::size_t pi,
    const PathJudgement& judgement,
    const std::vector<std::vector<int>>& realJunctionPoints,
    const std::vector<Zone>& zones,
    const SectionSampler& sampler,
    double largestSpacing,
    const Settings& s,
    TubeSectionTracker::Result& result,
    std::vector<std::vector<std::pair<int, int>>>& clutterCuts);

  /// Sets the path's sections (Clean / NotClean / Junction), plans its stretches and applies the
  /// plans (the path's points, its sections, the junctions on it and `clutterCuts[pi]`). A path
  /// of fewer than 3 points is left as it is, its sections all Junction (not judged).
  void run();

private:
  // --- Section queries (vtouchTubeSectionRetracerQueries.cxx) ---
  double window(int i) const;
  bool inWindow(int i, int j, double w) const;
  bool anchor(int i) const;
  bool widerThanTube(double sv, double r) const;
  bool lone(int i, double r) const;
  std::pair<int, std::size_t> junctionReached(const Track& tr, int from, int sign, double r) const;
  double tubeRadius(int from, int towards) const;
  Vec3 heading(int from, int sign) const;

  // --- Stretches (vtouchTubeSectionRetrace.cxx) ---
  void setJudgedSections();
  /// The stretch starting at j (not an anchor): its end k (exclusive), across lone clean points;
  /// `judgedNotClean` false when it holds only junction zones.
  int stretchEnd(int j, bool& judgedNotClean);
  void planStretches(std::vector<RetracePlan>& plans);

  // --- Re-tracing (vtouchTubeSectionRetracerTracks.cxx) ---
  void planBetweenAnchors(int j,
    int k,
    double maxLength_mm,
    std::vector<RetracePlan>& plans,
    StretchTracks& tracks);
  bool planTrackAcross(int from,
    int sign,
    int j,
    int k,
    double r,
    double maxLength_mm,
    std::vector<RetracePlan>& plans,
    Track& kept);
  RetracePlan trackPlan(int from, int to, int sign, const Track& tr, std::size_t lastCentre) const;
  void planFreeEnd(int anchorIndex,
    int sign,
    double stretchLength_mm,
    std::vector<RetracePlan>& plans);

  // --- Cutting (vtouchTubeSectionRetracerCut.cxx) ---
  void planClutterCut(int j, int k, const StretchTracks& tracks, std::vector<RetracePlan>& plans);
  bool betweenVessels(int j, int k, double tube_voxels) const;
  int loopChordEnd(int j, int k) const;

  // --- Applying (vtouchTubeSectionRetracerApply.cxx) ---
  void applyPlans(std::vector<RetracePlan>& plans);
  void applyPlan(const RetracePlan& p,
    std::vector<std::pair<int, int>>& changed,
    std::vector<std::pair<int, int>>& clutter);
  void resmoothChanged(const std::vector<std::pair<int, int>>& changed);

  QSkeleton& skeleton;
  const std::size_t pi;
  SkeletonPath& path;
  const std::vector<PointSection>& sec;
  const std::vector<double>& arc; ///< voxels
  const std::vector<int>& vessel;
  const std::vector<double>& vesselMedian;
  const std::vector<std::vector<int>>& realJunctionPoints;
  const std::vector<Zone>& zones;
  const SectionSampler& sampler;
  const double largestSpacing;
  const Settings& s;
  TubeSectionTracker::Result& result;
  std::vector<std::vector<std::pair<int, int>>>& clutterCuts;
  std::vector<Section>& status;
  const int n;                   ///< the path's points before any plan is applied
  const double voxel;            ///< mm
  const double pathMedianRadius; ///< mm, of the points before any plan is applied
};

} // namespace tube_sections
} // namespace vtouch
