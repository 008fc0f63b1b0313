// Whether a pipeline source's first output is a volume VesselTouch can use: 3D image data (at
// least two voxels along each axis) with point scalars. The volume chooser, "Show as MIP" and
// "Extract centerlines" reject anything else with the reason this gives (a PNG or a single slice
// is a 2D image: a MIP of it is meaningless and its "centerlines" are not vessels).
#ifndef pqVesselTouchVolumeCheck_h
#define pqVesselTouchVolumeCheck_h

#include <QString>

class pqPipelineSource;

namespace pqVesselTouchVolumeCheck
{
/// "" when `source` is a usable volume, else why not, in words for the user ("PNG1 is a 2D
/// image (256 x 256 x 1 voxels): VesselTouch needs a 3D volume."). Reads the data information
/// the source has now (a source that never updated has none: "has no data yet").
QString problem(pqPipelineSource* source);
/// True when `source` produces image data at all (a 2D image is image data too).
bool isImage(pqPipelineSource* source);
} // namespace pqVesselTouchVolumeCheck

#endif
