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
// A part of the volume (one rank's piece in a parallel pipeline) is read with readExtent(): for
// uncompressed NIfTI, NRRD and MetaImage only that part's bytes are read from the file, for a DICOM
// series only the files of its slices; compressed files must be decoded whole (see
// readsExtentsAlone()).
#ifndef vtouchVolumeIO_h
#define vtouchVolumeIO_h

#include <array>
#include <cstddef>
#include <cstdint>
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

/// A box of voxel indices, bounds included on both ends per axis (a VTK extent without the signs).
struct VoxelExtent
{
  std::array<std::size_t, 3> first{ { 0, 0, 0 } };
  std::array<std::size_t, 3> last{ { 0, 0, 0 } };

  /// The whole of a volume of `dimensions` (each > 0).
  static VoxelExtent whole(const std::array<std::size_t, 3>& dimensions);
  std::array<std::size_t, 3> size() const;
  std::size_t voxelCount() const;
  /// first <= last on every axis and last < dimensions.
  bool isWithin(const std::array<std::size_t, 3>& dimensions) const;
};

/// What the last read took from the files, for tests and benchmarks of streamed reads.
struct VolumeReadStatistics
{
  /// Voxel bytes read from disk (uncompressed data), or decoded (compressed data, read whole).
  std::uint64_t bytesRead = 0;
  /// Files opened for voxel data (one per DICOM slice read).
  std::size_t filesRead = 0;
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
  bool read(void* buffer, std::size_t bytes, const VolumeProgress& progress);
  /// Reads the voxels of `extent` into `buffer` (at least extent.voxelCount() voxels, x fastest
  /// then y then z). Returns false when `progress` asked to abort. Throws VolumeIOError on a bad
  /// file or an extent outside the volume.
  virtual bool readExtent(const VoxelExtent& extent,
    void* buffer,
    std::size_t bytes,
    const VolumeProgress& progress) = 0;
  /// True when readExtent() reads no more of the file than the extent needs (uncompressed voxels,
  /// DICOM slices); false when the file must be decoded whole (gzip, NIfTI intensity scaling).
  virtual bool readsExtentsAlone() const = 0;
  /// True when a box narrower than a slice costs less than the whole slices it crosses (raw
  /// voxels read row by row); false when a slice is read whole whatever part is asked for (one
  /// DICOM file per slice). Decides whether a piece grown on its x or y faces is better copied
  /// from memory and topped up box by box, or read again (vtouchExtentReuse.h).
  virtual bool readsPartialSlicesAlone() const { return this->readsExtentsAlone(); }
  /// What the last read took from the files.
  const VolumeReadStatistics& lastReadStatistics() const { return this->LastRead; }

protected:
  /// Throws VolumeIOError unless `extent` lies in the volume and `bytes` can hold it.
  void checkExtentRequest(const VoxelExtent& extent, const void* buffer, std::size_t bytes) const;

  VolumeHeader Header;
  VolumeReadStatistics LastRead;
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
