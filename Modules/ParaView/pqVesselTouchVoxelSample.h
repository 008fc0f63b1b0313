// Statistics of a volume's voxels for the panel's Centerlines section (read in this process:
// nothing when the data is on a remote server): the seed's value and neighbourhood, and an evenly
// strided sample of the volume for the range fields' default and the background test.
#ifndef pqVesselTouchVoxelSample_h
#define pqVesselTouchVoxelSample_h

class pqPipelineSource;

namespace pqVesselTouchVoxelSample
{
/// Order statistics of an evenly strided sample of the volume's voxels: the upper tail's start
/// and the background (the median: vessels fill far less than half an angiogram) with its noise
/// (P50 - P15.87, one Gaussian sigma from the lower half, which the vessels do not reach).
struct VoxelSample
{
  bool ok = false;
  double tail = 0.0;
  double background = 0.0;
  double noise = 0.0;
};

/// The sample of `volume` (ok false with remote or no data).
VoxelSample sampleVoxels(pqPipelineSource* volume);
/// Median of the 3x3x3 voxels around the world point `point_mm` (the seed): a vessel's lumen
/// around its brightest voxel, or background around a noise spike. False outside the volume.
bool neighbourhoodMedian(pqPipelineSource* volume, const double point_mm[3], double& median);
/// The voxel value nearest the world point `point_mm`; false outside the volume.
bool voxelValue(pqPipelineSource* volume, const double point_mm[3], double& value);
} // namespace pqVesselTouchVoxelSample

#endif
