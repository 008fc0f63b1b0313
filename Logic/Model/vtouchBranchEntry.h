// Where a branch's axis enters its parent vessel (issue 16, the raw CTA's iliac bifurcation).
//
// The voxel coder attaches a branch where its SS band merges with the parent's (Yi & Hayward
// section 3.1: a cluster of one band is one cross-section; a bifurcation is where a band falls
// apart). Inside the merged lumen the branch then has no cross-section of its own: its path
// runs on the merged band's centres and crosses the lumen to the parent's point in one or two
// steps, a corner the width of the parent. Where two vessels meet at a shallow angle (the aorta
// flattening into the two iliacs) that corner sits centimetres from the branch's own axis.
//
// The rule (project rule, after the tube definition of a bifurcation that VMTK's branch
// splitting uses, Antiga & Steinman, IEEE TMI 23(6) 2004: a branch's centerline belongs to the
// bifurcation until it leaves the tube of maximal inscribed spheres of the other vessel): the
// branch's stretch inside the parent's tube (its centres closer to the nearest parent centre
// than that centre's radius) is replaced by the branch's own axis carried on straight (the line
// fitted to the branch's centres over one of its radii past the tube, three at least) to the
// parent's axis. Kept as coded when that line does not meet the parent's axis (passes farther
// than half the parent's radius from every parent centre ahead of it, meets it more than four
// parent radii on, or runs within 10 degrees of the parent's axis: a vessel continuing past a
// root or a loop's two fronts, not a branch), when the branch does not leave the parent's tube
// within four parent radii of its end, when it hangs on an end of its parent (the two paths
// join there: that end would become free), and when another path hangs on the stretch that
// would be replaced.
//
// The network's last step, on positions already smoothed and refined (the raw path's tube
// sections judge a junction's zone where the coder put it): the single run's
// `VesselCenterline` after its refinement, a distributed run on the first rank's stitched whole
// network, so both give the same network (issue 19 item 2). The new entry points carry the
// line's geometry (its direction, no curvature). Not applied when the positions are kept as
// coded (a negative SmoothingWindow).
#pragma once

#include "vtouchQSkeleton.h"

#include <cstddef>

namespace vtouch
{

struct BranchEntryReport
{
  std::size_t junctionsMoved = 0; ///< branches whose entry was carried to the parent's axis
  std::size_t pointsReplaced = 0; ///< coded centres inside the parent's tube, replaced
};

/// Applies the rule above to every junction of `skeleton` in junction order (positions, radii,
/// junctions and the labels of the parent points changed; tangents and curvature are the
/// smoothing's). Keeps `skeleton.validate()` true.
BranchEntryReport placeBranchEntries(QSkeleton& skeleton);

} // namespace vtouch
