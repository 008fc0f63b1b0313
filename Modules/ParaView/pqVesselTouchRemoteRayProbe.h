// The brightest voxel along a click's ray, resolved where the voxels are: on the pvserver
// (issue 19, item 1). Built in, pqVesselTouchSeedPicker walks the voxels of the volume in this
// process (vtouch::RayMaximum). Connected to a pvserver the volume is split across the ranks and
// none of it is here, so the ray is probed on the server instead: ParaView's ProbeLine
// (vtkPProbeLineFilter: every rank probes its piece, rank 0 composites the valid samples) samples
// the segment of the ray inside the volume's bounds every half of the smallest voxel spacing, and
// only those samples (a few hundred points) are moved to the client (ClientServerMoveData).
//
// Departure from the built-in walk: the samples are trilinear (ProbeLine interpolates), so the
// seed is the voxel nearest to the brightest sample and its value the sample's. At half a voxel
// per step every voxel the ray crosses is sampled within half a voxel of its centre. The volume's
// geometry comes from its data information (bounds and extent), so the voxel snap assumes an
// axis-aligned image (identity direction matrix); the sample itself is right either way.
#ifndef pqVesselTouchRemoteRayProbe_h
#define pqVesselTouchRemoteRayProbe_h

#include <QString>

class pqPipelineSource;

class pqVesselTouchRemoteRayProbe
{
public:
  struct Result
  {
    bool found = false;
    double seed_mm[3] = { 0.0, 0.0, 0.0 }; ///< the voxel nearest to the brightest sample
    double value = 0.0;                    ///< the brightest sample's value
    int samples = 0;                       ///< valid samples the server returned
    QString error;                         ///< why nothing was found ("" when found)
  };

  /// Probes output 0 of `volume` (image data on the active server) along the segment
  /// near_mm -> far_mm (world mm, the click's ray between the near and far planes).
  static Result find(pqPipelineSource* volume, const double near_mm[3], const double far_mm[3]);

  /// The part of near_mm -> far_mm inside `bounds` (xmin, xmax, ...): false when it misses.
  static bool clipToBounds(const double bounds[6],
    const double near_mm[3],
    const double far_mm[3],
    double p0[3],
    double p1[3]);
};

#endif
