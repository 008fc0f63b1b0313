// DICOM series: grouping by Series Instance UID, geometry from the per-slice
// ImagePositionPatient / ImageOrientationPatient (gdcm::Scanner, headers only), slices
// ordered by their position along the slice normal, gaps and duplicates reported. Internal to
// VesselTouchIO.
#ifndef vtouchDicomSeries_h
#define vtouchDicomSeries_h

#include "vtouchVolumeIO.h"

namespace vtouch
{

/// `path` is a DICOM file or a folder. See openVolume().
std::unique_ptr<VolumeSource> openDicomSeries(const std::string& path,
  const VolumeOpenOptions& options);

/// True when GDCM recognises `path` as a DICOM file.
bool isDicomFile(const std::string& path);

} // namespace vtouch

#endif
