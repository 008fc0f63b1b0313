// The analytic centerlines of the phantom shapes, in the world frame of the phantom volume.
#pragma once

#include "vtouchPhantomSpec.h"
#include "vtouchQSkeleton.h"

namespace vtouch
{

/// Samples every vessel of `spec` about every `step_mm` along its arc, with analytic tangent,
/// curvature, torsion and radius, and links the paths with junctions (loops included).
/// `spec` must be valid (PhantomSpec::validate() empty).
QSkeleton buildPhantomCenterline(const PhantomSpec& spec, double step_mm);

} // namespace vtouch
