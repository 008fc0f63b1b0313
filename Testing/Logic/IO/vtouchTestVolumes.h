// Tiny volumes with a known geometry written with ITK (ImageFileWriter, ImageSeriesWriter +
// GDCMImageIO) for the reader tests. Voxel (i, j, k) holds testVoxelValue(i, j, k).
#ifndef vtouchTestVolumes_h
#define vtouchTestVolumes_h

#include <array>
#include <string>
#include <vector>

namespace vtouch
{
namespace test
{

struct TestGeometry
{
  std::array<unsigned, 3> size{ { 6, 5, 4 } };
  std::array<double, 3> spacing_mm{ { 0.7, 1.1, 2.5 } };
  std::array<double, 3> origin_LPS_mm{ { -12.5, 30.25, 101.0 } };
  /// Row-major; column a = LPS direction of index axis a.
  std::array<double, 9> direction{ { 1, 0, 0, 0, 1, 0, 0, 0, 1 } };
};

/// An oblique orthonormal direction (rotations of 30 deg about z then 20 deg about x), anisotropic
/// spacing and an off-centre origin.
TestGeometry obliqueGeometry();

/// The value stored at voxel (i, j, k): distinct for every voxel of a test volume.
inline int testVoxelValue(unsigned i, unsigned j, unsigned k)
{
  return static_cast<int>(i + 10 * j + 100 * k) - 50;
}

/// Writes a 3D scalar volume of the given ITK pixel type name ("int8", "uint8", "int16", "uint16",
/// "int32", "uint32", "float", "double", "int64") with the extension-chosen IO (.nrrd, .nhdr,
/// .nii, .nii.gz, .mha, .mhd).
void writeVolume(const std::string& path,
  const TestGeometry& g,
  const std::string& pixel = "int16");

/// Writes an int16 DICOM series (one file per slice, ImagePositionPatient / ImageOrientationPatient
/// per slice) into `directory`. File names run opposite to the slice positions (IM0000 is the last
/// slice) so that sorting by name would be wrong; names are prefix + 4 digits + suffix. names are
/// prefix + 4 digits + suffix. `skipSlice`
/// >= 0 leaves that slice out. Returns the file names written.
std::vector<std::string> writeDicomSeries(const std::string& directory,
  const TestGeometry& g,
  const std::string& seriesUID,
  int skipSlice = -1,
  const std::string& filePrefix = "IM",
  const std::string& fileSuffix = "");

/// Bad inputs: a 2D image, a 4D image (T = 2), a 3-component vector image.
void write2D(const std::string& path);
void write4D(const std::string& path);
void writeVector(const std::string& path);

} // namespace test
} // namespace vtouch

#endif
