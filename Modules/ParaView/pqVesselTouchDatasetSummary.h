// One line describing a pipeline source's first output for the panel's info widget, e.g.
// "Image (Uniform Rectilinear Grid), 128 x 128 x 128 voxels, Intensity in [0, 1100]".
#ifndef pqVesselTouchDatasetSummary_h
#define pqVesselTouchDatasetSummary_h

#include <QString>

class pqPipelineSource;

class pqVesselTouchDatasetSummary
{
public:
  /// Data type, size (voxels for images, points otherwise) and the scalars' range; "" when the
  /// source is null or has no data yet.
  static QString describe(pqPipelineSource* source);
};

#endif
