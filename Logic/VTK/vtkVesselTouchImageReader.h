// VesselTouch image reader: DICOM series, NIfTI (.nii, .nii.gz), NRRD (.nrrd, .nhdr) and
// MetaImage (.mha, .mhd) through ITK IO, with origin, spacing and direction matrix kept.
//
// The output vtkImageData is in LPS millimetres (like ITK and DICOM) unless OutputFrame is RAS:
// voxel (i, j, k) sits at Origin + DirectionMatrix * diag(Spacing) * (i, j, k). RAS files (NIfTI,
// NRRD in a RAS space) are converted to LPS on read by negating x and y. Voxels are read straight
// into the output array (no intermediate copy, except inside ITK's NIfTI library). Bad input
// (missing or corrupt file, 2D or 4D image, colour pixels, unsupported pixel type, a DICOM series
// with gaps, duplicates or mixed orientations) gives a vtkErrorMacro and an empty output.
//
// Streaming: the reader produces sub-extents (CAN_PRODUCE_SUB_EXTENT), so in a parallel pipeline
// (pvserver under MPI) each rank asks for its piece and reads only that: the piece's bytes of an
// uncompressed NIfTI, NRRD or MetaImage file, the files of its slices of a DICOM series. A
// compressed file (.nii.gz, gzip NRRD, compressed MetaImage) is decoded whole by each rank and cut
// (a warning says so once per file); GetReadsPiecesAlone() tells which case a file is.
// A piece asked for again with a larger extent (a distributed VesselCenterline's piece grown by
// its ghost margin, after the view showed the piece) copies the voxels it holds and reads only the
// rest, when the piece it holds is also held elsewhere (a view's representation): then it stays
// in memory anyway and copying from it adds nothing to the peak. Held only by this reader's
// output, it is released first and the new extent read whole, as before.
#ifndef vtkVesselTouchImageReader_h
#define vtkVesselTouchImageReader_h

#include "vtkImageAlgorithm.h"
#include "vtkNew.h"                    // for vtkNew
#include "vtkTimeStamp.h"              // for vtkTimeStamp
#include "vtkWeakPointer.h"            // for vtkWeakPointer
#include "vtkVesselTouchLogicModule.h" // for export macro

#include <memory> // for std::unique_ptr
#include <string> // for std::string

class vtkDataArray;
class vtkImageData;
class vtkStringArray;

namespace vtouch
{
class VolumeSource;
enum class VoxelType;
}

class VTKVESSELTOUCHLOGIC_EXPORT vtkVesselTouchImageReader : public vtkImageAlgorithm
{
public:
  static vtkVesselTouchImageReader* New();
  vtkTypeMacro(vtkVesselTouchImageReader, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// A volume file, a DICOM file (its whole series is read) or a folder of DICOM files.
  vtkSetStringMacro(FileName);
  vtkGetStringMacro(FileName);

  /// DICOM only: the Series Instance UID to read when the folder holds several series. Empty
  /// (default): the series of the chosen file, or the series with the most files for a folder.
  vtkSetStringMacro(SeriesInstanceUID);
  vtkGetStringMacro(SeriesInstanceUID);

  enum WorldFrame
  {
    LPS = 0,
    RAS = 1
  };
  /// World frame of the output: LPS (default; ITK, DICOM) or RAS (3D Slicer, VMTK, NIfTI's own
  /// frame): RAS negates x and y of the origin and of the direction matrix rows.
  vtkSetClampMacro(OutputFrame, int, LPS, RAS);
  vtkGetMacro(OutputFrame, int);

  /// 1 when the file looks readable (extension or DICOM preamble; a folder with a DICOM file).
  int CanReadFile(const char* path);

  /// After UpdateInformation: the DICOM series found in the folder (largest first), as UIDs and
  /// as "UID (N files)" lines; empty for other formats.
  vtkStringArray* GetSeriesInstanceUIDs();
  vtkStringArray* GetSeriesSummaries();

  /// After UpdateInformation: the format read ("NIfTI", "NRRD", "MetaImage", "DICOM series", ...)
  /// and the voxel type, or empty when the file could not be opened.
  const char* GetFileFormat() { return this->FileFormat.c_str(); }

  /// After UpdateInformation: 1 when a piece of this file is read without reading the rest
  /// (uncompressed voxels, DICOM slices), 0 when every piece decodes the whole file.
  int GetReadsPiecesAlone();

  /// After an update: voxel bytes the last update read from disk (or decoded, for a compressed
  /// file), and the number of files it opened for voxels. For tests and benchmarks of streaming.
  double GetLastReadBytes();
  int GetLastReadFiles();
  /// After an update: voxel bytes the last update copied from the piece it had read before
  /// instead of reading them again (see "Streaming" above: a grown piece after the piece).
  double GetLastReusedBytes();

protected:
  vtkVesselTouchImageReader();
  ~vtkVesselTouchImageReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

private:
  vtkVesselTouchImageReader(const vtkVesselTouchImageReader&) = delete;
  void operator=(const vtkVesselTouchImageReader&) = delete;

  /// Marks the ghost layers a downstream filter asked for (vtkGhostType) when the piece carries
  /// them.
  void MarkGhostLayers(vtkInformation* outInfo, vtkImageData* output);
  /// Computes the read voxels' range and finite range and stores them in VTK's range cache of
  /// `scalars` (vtouchVoxelValueRange.h).
  void CacheValueRange(vtkDataArray* scalars, vtouch::VoxelType type);
  /// The last read's statistics as field data: ReaderVoxelBytesRead, ReaderVoxelBytesReused,
  /// ReaderFilesRead, ReaderReadsPiecesAlone (one value each).
  void AddReadStatistics(vtkImageData* output);
  /// The voxels of this reader's last read, when they may be copied into the next one (same
  /// file, untouched; whether something else holds them is decided in RequestData once the
  /// output let go of them: see "Streaming" above), else null; `extent` gets their extent.
  vtkDataArray* ReusablePiece(int extent[6]) const;
  /// Remembers what `output` now holds, for ReusablePiece.
  void RememberPiece(vtkImageData* output);
  /// Opens the file (header only); empty on success, else the reason.
  std::string Open();
  void UpdateSeriesList();

  char* FileName = nullptr;
  char* SeriesInstanceUID = nullptr;
  int OutputFrame = LPS;
  std::string FileFormat;
  std::string OpenError;
  vtkTimeStamp OpenTime;          // when Open() last ran; reopened only after a property change
  bool WarnedWholeDecode = false; // the compressed-file warning, once per opened file
  std::unique_ptr<vtouch::VolumeSource> Source;
  // The last read: what it took from the file and from the piece before.
  double LastBytesRead = 0.0;
  double LastBytesReused = 0.0;
  int LastFilesRead = 0;
  // The voxels the last read left in the output. Weak: this reader never keeps them alive
  // itself (the output, a view's representation or a downstream filter may).
  vtkWeakPointer<vtkDataArray> LastPieceArray;
  vtkMTimeType LastPieceArrayTime = 0;
  vtkMTimeType LastPieceOpenTime = 0;
  int LastPieceExtent[6] = { 0, -1, 0, -1, 0, -1 };
  vtkNew<vtkStringArray> SeriesUIDs;
  vtkNew<vtkStringArray> SeriesLines;
};

#endif
