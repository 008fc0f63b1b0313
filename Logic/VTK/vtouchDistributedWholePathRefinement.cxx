#include "vtouchDistributedWholePathRefinement.h"

#include "vtouchControllerCollectives.h"
#include "vtouchDistributedGlobalField.h"
#include "vtouchRangeForeground.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMatrix3x3.h"
#include "vtkNew.h"

#include <vector>

namespace vtouch
{
namespace
{
/// The whole volume's index frame (index 0 at its first voxel) from a piece of it.
SectionGeometry wholeGeometry(vtkImageData* piece, const VoxelExtent6& whole)
{
  SectionGeometry g;
  piece->TransformIndexToPhysicalPoint(whole[0], whole[2], whole[4], g.origin_mm.data());
  piece->GetSpacing(g.spacing_mm.data());
  if (vtkMatrix3x3* m = piece->GetDirectionMatrix())
  {
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        g.direction[static_cast<std::size_t>(3 * r + c)] = m->GetElement(r, c);
      }
    }
  }
  return g;
}

void addValue(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}

void addCount(vtkFieldData* fd, const char* name, int value)
{
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}
} // namespace

std::string DistributedWholePathRefinement::run(vtkMultiProcessController* controller,
  vtkImageData* piece,
  vtkDataArray* scalars,
  const VoxelExtent6& whole,
  QSkeleton* stitched,
  const DistributedRawRefinement::Settings& settings,
  vtkFieldData* report,
  const CancellableCollectives::CancelCheck& cancelRequested)
{
  // Every exchange a cancel point (issue 19 item 1): a cancel on the first rank stops all.
  ControllerCollectives exchanges(controller);
  CancellableCollectives c(exchanges, cancelRequested);
  const bool usable = piece && scalars && scalars->GetNumberOfComponents() == 1 &&
                      scalars->GetNumberOfTuples() == piece->GetNumberOfPoints();
  const PieceLayout layout = DistributedGlobalField::gatherLayout(c, piece, usable, whole);
  // The refinement's arguments are the first rank's; every rank's own (the same range across
  // the ranks, DistributedVolumeRange) must be those numbers.
  const std::vector<std::vector<double>> ranges = c.allGather(std::vector<double>{
    settings.lower, settings.upper, settings.background, settings.backgroundNoise });
  int rangesDiffer = 0;
  for (const std::vector<double>& r : ranges)
  {
    rangesDiffer += r != ranges[0] ? 1 : 0;
  }
  DistributedVolumePages::OwnedIntensity mine;
  if (usable)
  {
    const VoxelBox held = layout.mine();
    const std::array<std::int64_t, 3> d = layout.pieceDims();
    const SectionIntensity voxels = volumeIntensity(scalars, d);
    mine = [voxels, held, d](const std::array<std::int64_t, 3>& w)
    {
      return voxels.value(static_cast<std::uint64_t>(
        (w[0] - held.lo[0]) + d[0] * ((w[1] - held.lo[1]) + d[1] * (w[2] - held.lo[2]))));
    };
  }
  std::string error;
  if (stitched && !usable)
  {
    error = "the first rank holds no piece of the volume: the raw refinement did not run";
    stitched = nullptr;
  }
  const SectionGeometry geometry = usable ? wholeGeometry(piece, whole) : SectionGeometry{};
  const DistributedRawRefinement::Result r =
    DistributedRawRefinement::run(c, layout, mine, stitched, geometry, settings);
  if (!report)
  {
    return std::string();
  }
  error = error.empty() && !r.message.empty()
            ? "the raw refinement over the whole paths stopped: " + r.message
            : error;
  addCount(report, "DistributedRefinementPagesPrefetched", static_cast<int>(r.pagesPrefetched));
  addCount(report, "DistributedRefinementPagesFetched", static_cast<int>(r.pages.pagesFetched));
  addCount(report, "DistributedRefinementRounds", r.pages.rounds);
  addCount(report, "DistributedRefinementRuns", r.pages.runs);
  addValue(
    report, "DistributedRefinementBytesGathered", static_cast<double>(r.pages.bytesGathered));
  addValue(report, "DistributedRefinementSeconds", r.seconds);
  addValue(report, "DistributedRefinementTrackSeconds", r.refinement.trackSeconds);
  addValue(report, "DistributedRefinementPruneSeconds", r.refinement.pruneSeconds);
  addCount(report, "DistributedRefinementRangesDiffer", rangesDiffer);
  if (r.refined)
  {
    addCount(report, "ContactStretchesRetraced", r.refinement.tracked.stretchesTracked);
    addCount(report, "ClutterStretchesCut", r.refinement.tracked.stretchesCut);
    addCount(report, "NonTubularPathsRemoved", r.refinement.pruned.pathsRemoved);
  }
  return error;
}

} // namespace vtouch
