// Medical volume files in, with their orientation: DICOM series, NIfTI (.nii, .nii.gz), NRRD
// (.nrrd, .nhdr) and MetaImage (.mha, .mhd), read with ITK IO.
//
// World convention: LPS (x toward the patient's Left, y toward Posterior, z toward Superior), in
// mm, like ITK and DICOM. ITK converts RAS files on read (NIfTI always; NRRD whose "space" is RAS)
// by negating x and y of the origin and of every axis direction; the geometry below is therefore
// LPS for every format. VolumeGeometry::inFrame(WorldFrame::RAS) gives the RAS view (3D Slicer,
// VMTK).
//
// Reading is two-phase so the caller owns the voxel memory: openVolume() reads the header (cheap),
// the caller allocates header().byteCount() bytes, VolumeSource::read() fills them, x fastest.
#ifndef vtouchVolumeIO_h
#define vtouchVolumeIO_h

#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace vtouch
{

/// Voxel types kept as in the file (no conversion). 64-bit integers, complex and colour pixels are
/// rejected.
enum class VoxelType
{
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Float32,
  Float64
};

std::size_t voxelSize(VoxelType type);
const char* toString(VoxelType type);

/// World frames: LPS (ITK, DICOM; the default everywhere) or RAS (NIfTI, 3D Slicer, VMTK).
enum class WorldFrame
{
  LPS,
  RAS
};

/// Geometry of a 3D volume: voxel (i, j, k) sits at origin + D * diag(spacing) * (i, j, k).
struct VolumeGeometry
{
  std::array<std::size_t, 3> dimensions{ { 0, 0, 0 } };
  /// Voxel size along each index axis, mm (> 0).
  std::array<double, 3> spacing_mm{ { 1.0, 1.0, 1.0 } };
  /// World position of the centre of voxel (0, 0, 0), mm.
  std::array<double, 3> origin_mm{ { 0.0, 0.0, 0.0 } };
  /// Direction matrix D, row-major: column a is the world unit direction of index axis a.
  std::array<double, 9> direction{ { 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0 } };

  std::size_t voxelCount() const;
  /// World position (mm) of the voxel centre (i, j, k); fractional indices allowed.
  std::array<double, 3> worldPosition(double i, double j, double k) const;
  /// This geometry (given in LPS) expressed in `frame`: RAS negates x and y of the origin and of
  /// every axis direction (the rows 0 and 1 of D); LPS returns it unchanged.
  VolumeGeometry inFrame(WorldFrame frame) const;
};

struct VolumeHeader
{
  /// "NIfTI", "NRRD", "MetaImage", "DICOM series" or "DICOM multi-frame".
  std::string format;
  /// Always LPS.
  VolumeGeometry geometry;
  VoxelType voxelType = VoxelType::UInt8;
  /// Things the user should know that do not stop the read (several series in a folder, ...).
  std::vector<std::string> warnings;

  std::size_t byteCount() const;
};

/// Every failure to open or read a volume, with a message meant for the user.
class VolumeIOError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Progress in [0, 1]; return false to abort the read.
using VolumeProgress = std::function<bool(double fraction)>;

/// An opened volume file (header read, voxels not yet).
class VolumeSource
{
public:
  virtual ~VolumeSource() = default;
  const VolumeHeader& header() const { return this->Header; }
  /// Reads every voxel into `buffer` (at least header().byteCount() bytes, x fastest then y then
  /// z). Returns false when `progress` asked to abort. Throws VolumeIOError on a bad file.
  virtual bool read(void* buffer, std::size_t bytes, const VolumeProgress& progress) = 0;

protected:
  VolumeHeader Header;
};

struct VolumeOpenOptions
{
  /// DICOM only: the Series Instance UID to read when a folder holds several series. Empty: the
  /// series of the given file, or (for a folder) the series with the most files.
  std::string seriesInstanceUID;
};

/// Opens `path`: a .nii/.nii.gz/.hdr, .nrrd/.nhdr, .mha/.mhd file, a DICOM file (its series is
/// read from its folder) or a folder of DICOM files. Throws VolumeIOError with a clear reason:
/// missing or unreadable file, corrupt header, 2D image, 4D image, colour/vector pixels,
/// unsupported pixel type, inconsistent or incomplete DICOM series.
std::unique_ptr<VolumeSource> openVolume(const std::string& path,
  const VolumeOpenOptions& options = VolumeOpenOptions());

/// Cheap test for a reader factory: true for the supported extensions (existing files), for a
/// DICOM file and for a folder holding at least one DICOM file among its first entries.
bool canReadVolume(const std::string& path);

struct DicomSeriesSummary
{
  std::string seriesInstanceUID;
  std::size_t fileCount = 0;
};

/// The DICOM series found in `directory` (not recursive), the largest first. Throws VolumeIOError
/// when the folder cannot be scanned.
std::vector<DicomSeriesSummary> listDicomSeries(const std::string& directory);

} // namespace vtouch

#endif
