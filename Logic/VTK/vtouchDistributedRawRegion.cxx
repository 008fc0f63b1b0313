#include "vtouchDistributedRawRegion.h"

#include "vtouchCandidateRegionRunner.h"
#include "vtouchControllerCollectives.h"
#include "vtouchDistributedCandidateRegion.h"
#include "vtouchDistributedCenterline.h"
#include "vtouchDistributedGlobalField.h"
#include "vtouchSeedComponentSplit.h"
#include "vtouchTypedScalars.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"

#include <stdexcept>

namespace vtouch
{
namespace
{
template<typename T>
DistributedCandidateRegion::Result extractTyped(vtkImageData* piece,
  const T* data,
  const PieceLayout& layout,
  const std::array<std::int64_t, 3>& seed,
  bool useSeed,
  RankCollectives& c)
{
  VolumeView<T> view;
  view.voxels = data;
  if (piece)
  {
    int dims[3];
    piece->GetDimensions(dims);
    view.dims = { dims[0], dims[1], dims[2] };
    piece->GetSpacing(view.spacing_mm.data());
  }
  VesselCandidateRegion::Settings s;
  s.automatic = true;
  s.cutNonTubular = true;
  s.useSeed = useSeed;
  s.seed = seed;
  return DistributedCandidateRegion::extract(view, layout, seed, s, c);
}

std::string outsideText(vtkImageData* piece,
  const VoxelExtent6& whole,
  const double seed_World_mm[3],
  const std::array<std::int64_t, 3>& seed)
{
  double origin[3], spacing[3];
  piece->GetOrigin(origin);
  piece->GetSpacing(spacing);
  double bounds[6];
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = origin[a] + whole[static_cast<std::size_t>(2 * a)] * spacing[a];
    bounds[2 * a + 1] = origin[a] + whole[static_cast<std::size_t>(2 * a + 1)] * spacing[a];
  }
  return seedOutsideVolumeMessage(seed_World_mm, seed, bounds);
}
} // namespace

void DistributedRawRegion::addReport(vtkFieldData* fd, const Report& report)
{
  vtkNew<vtkIntArray> growth;
  growth->SetName("RegionGrowthRounds");
  growth->InsertNextValue(report.growthRounds);
  fd->AddArray(growth);
  vtkNew<vtkIntArray> component;
  component->SetName("RegionComponentRounds");
  component->InsertNextValue(report.componentRounds);
  fd->AddArray(component);
  vtkNew<vtkDoubleArray> sent;
  sent->SetName("RegionVoxelsSent");
  sent->InsertNextValue(report.sentVoxels);
  fd->AddArray(sent);
  if (!report.seeded)
  {
    vtkNew<vtkDoubleArray> adopted;
    adopted->SetName("RegionHeldVoxelsFromOwners");
    adopted->InsertNextValue(report.heldVoxelsFromOwners);
    fd->AddArray(adopted);
  }
}

CandidateRegionOutcome DistributedRawRegion::splitSeedComponent(CandidateRegionOutcome& seeded)
{
  CandidateRegionOutcome rest = seeded;
  rest.ok = false;
  rest.mask = nullptr;
  rest.seedIndex = { -1, -1, -1 };
  rest.stageSeconds.clear();
  if (!seeded.ok || !seeded.mask || seeded.seedIndex[0] < 0)
  {
    return rest;
  }
  SeedComponentSplit::Parts parts = SeedComponentSplit::split(*seeded.mask, seeded.seedIndex);
  if (parts.rest.vesselCount() == 0)
  {
    return rest; // the seed's component is the whole region
  }
  seeded.mask = std::make_shared<const SparseVesselMask>(std::move(parts.seedComponent));
  rest.mask = std::make_shared<const SparseVesselMask>(std::move(parts.rest));
  rest.ok = true;
  return rest;
}

int DistributedRawRegion::minimumMarginVoxels()
{
  return DistributedCandidateRegion::rangeMarginVoxels() + 1;
}

CandidateRegionOutcome DistributedRawRegion::run(vtkMultiProcessController* controller,
  vtkImageData* piece,
  vtkDataArray* scalars,
  const VoxelExtent6& whole,
  const CandidateRegionRequest& request,
  Report& report,
  const CancellableCollectives::CancelCheck& cancelRequested)
{
  // Every exchange a cancel point (issue 19 item 1): a cancel on the first rank stops all.
  ControllerCollectives exchanges(controller);
  CancellableCollectives c(exchanges, cancelRequested);
  CandidateRegionOutcome out;
  out.automatic = true;
  const bool usable = piece && scalars && scalars->GetNumberOfComponents() == 1 &&
                      scalars->GetNumberOfTuples() == piece->GetNumberOfPoints();
  const PieceLayout layout = DistributedGlobalField::gatherLayout(c, piece, usable, whole);
  try
  {
    layout.check(); // the same layout, hence the same verdict, on every rank
  }
  catch (const std::invalid_argument& e)
  {
    out.message = std::string("VesselCenterline (distributed): the ranks' pieces do not cover "
                              "the volume (") +
                  e.what() + "); extract on one rank.";
    return out;
  }
  // The seed's voxel in the whole volume: every rank with a piece computes the same; a rank
  // without one (it owns nothing) takes theirs. (Without a seed every rank skips this exchange:
  // the request is the filter's, the same on every rank.)
  std::vector<std::int64_t> mine;
  if (usable && request.useSeed)
  {
    const std::array<std::int64_t, 3> index = worldToIndex(piece, request.seed_World_mm);
    for (std::size_t a = 0; a < 3; ++a)
    {
      mine.push_back(index[a] - whole[2 * a]);
    }
  }
  std::array<std::int64_t, 3> seed{ -1, -1, -1 };
  if (request.useSeed)
  {
    for (const std::vector<std::int64_t>& theirs : c.allGather(mine))
    {
      if (theirs.size() == 3)
      {
        seed = { theirs[0], theirs[1], theirs[2] };
        break;
      }
    }
  }
  // A rank without a usable piece joins the collectives with no voxels (as float).
  DistributedCandidateRegion::Result r =
    usable
      ? withTypedScalars(scalars,
          [&](const auto* voxels)
          { return extractTyped(piece, voxels, layout, seed, request.useSeed, c); })
      : extractTyped(nullptr, static_cast<const float*>(nullptr), layout, seed, request.useSeed, c);
  report.growthRounds = r.growthRounds;
  report.componentRounds = r.componentRounds;
  report.sentVoxels = static_cast<double>(r.reportedVoxels);
  report.seeded = request.useSeed;
  report.heldVoxelsFromOwners = static_cast<double>(r.heldVoxelsFromOwners);
  out.ok = r.region.ok;
  out.message = r.region.message;
  // Without a seed a two-valued volume is a mask the coder thresholds itself, as the single run
  // (runCandidateRegion's `binary`).
  out.binary = !request.useSeed && r.region.range.binary;
  if (request.useSeed && layout.ownerOf(seed) < 0 && piece)
  {
    out.message = outsideText(piece, whole, request.seed_World_mm, seed);
  }
  out.lower = r.region.range.lower;
  out.upper = r.region.range.upper;
  out.background = r.region.range.background;
  out.backgroundNoise = r.region.range.backgroundNoise;
  out.stageSeconds = r.region.stageSeconds;
  if (r.region.ok)
  {
    if (r.region.mask.vesselCount() == 0 && request.useSeed)
    {
      out.ok = false; // normal: the seed's network does not reach this piece
      out.message = "VesselCenterline (distributed): the seed's network does not reach this piece.";
      return out;
    }
    out.seedIndex = r.seedHere ? r.region.seed : std::array<std::int64_t, 3>{ -1, -1, -1 };
    out.mask = std::make_shared<const SparseVesselMask>(std::move(r.region.mask));
  }
  return out;
}

} // namespace vtouch
