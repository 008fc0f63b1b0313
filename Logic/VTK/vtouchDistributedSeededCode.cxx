#include "vtouchDistributedSeededCode.h"

#include "vtouchCandidateRegionRunner.h"
#include "vtouchControllerCollectives.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"

namespace vtouch
{

PieceLayout DistributedSeededCode::gatherLayout(RankCollectives& c,
  vtkImageData* piece,
  bool usable,
  const VoxelExtent6& whole)
{
  std::vector<double> mine{ 0, -1, 0, -1, 0, -1 };
  if (usable)
  {
    int e[6];
    piece->GetExtent(e);
    for (int a = 0; a < 3; ++a)
    {
      mine[static_cast<std::size_t>(2 * a)] = e[2 * a] - whole[static_cast<std::size_t>(2 * a)];
      mine[static_cast<std::size_t>(2 * a + 1)] =
        e[2 * a + 1] - whole[static_cast<std::size_t>(2 * a)];
    }
  }
  const std::vector<std::vector<double>> held = c.allGather(mine);
  PieceLayout layout;
  layout.rank = c.rank();
  for (int a = 0; a < 3; ++a)
  {
    layout.wholeDims[static_cast<std::size_t>(a)] =
      whole[static_cast<std::size_t>(2 * a + 1)] - whole[static_cast<std::size_t>(2 * a)] + 1;
  }
  const std::vector<VoxelExtent6> split = DistributedCenterline::pieceExtents(whole, c.ranks());
  for (int r = 0; r < c.ranks(); ++r)
  {
    VoxelBox h, o;
    const VoxelExtent6& e = split[static_cast<std::size_t>(r)];
    for (std::size_t a = 0; a < 3; ++a)
    {
      const std::vector<double>& hr = held[static_cast<std::size_t>(r)];
      h.lo[a] = hr.size() == 6 ? static_cast<std::int64_t>(hr[2 * a]) : 0;
      h.hi[a] = hr.size() == 6 ? static_cast<std::int64_t>(hr[2 * a + 1]) : -1;
      o.lo[a] = e[2 * a] - whole[2 * a];
      o.hi[a] = e[2 * a + 1] - whole[2 * a];
      if (e[2 * a + 1] < whole[2 * a + 1])
      {
        o.hi[a] -= 1; // the shared face layer belongs to the upper piece
      }
    }
    layout.held.push_back(h);
    layout.owned.push_back(o);
  }
  return layout;
}

std::array<std::int64_t, 3> DistributedSeededCode::seedVoxel_Whole(vtkImageData* input,
  const double seed_World_mm[3],
  const VoxelExtent6& whole)
{
  std::array<std::int64_t, 3> index = worldToIndex(input, seed_World_mm);
  for (std::size_t a = 0; a < 3; ++a)
  {
    index[a] -= whole[2 * a];
  }
  return index;
}

DistributedSeededCode::DistributedSeededCode(vtkMultiProcessController* controller,
  vtkImageData* input,
  const VoxelExtent6& whole,
  bool hasSeed,
  const std::array<std::int64_t, 3>& seed_Whole,
  bool clearOuterLayer)
  : Collectives(std::make_unique<ControllerCollectives>(controller))
{
  std::array<double, 3> spacing_mm{ 1.0, 1.0, 1.0 };
  if (input)
  {
    input->GetSpacing(spacing_mm.data());
  }
  SeededDistributedCoding::Settings settings;
  settings.clearOuterLayer = clearOuterLayer;
  this->Coding = std::make_unique<SeededDistributedCoding>(*this->Collectives,
    gatherLayout(*this->Collectives, input, input != nullptr, whole),
    spacing_mm,
    hasSeed && input != nullptr,
    seed_Whole,
    settings);
}

DistributedSeededCode::~DistributedSeededCode() = default;

std::vector<float> DistributedSeededCode::code(SparseVesselMask& mask)
{
  return this->Coding->code(mask);
}

void DistributedSeededCode::finish()
{
  if (this->Coding->joined())
  {
    return;
  }
  try
  {
    this->Coding->join();
  }
  catch (const SeededDistributedCodingError&)
  {
    // This rank's run failed before its coder: its own message speaks for it.
  }
}

void DistributedSeededCode::addReport(vtkFieldData* fd) const
{
  const SeededDistributedCoding::Report& r = this->Coding->report();
  vtkNew<vtkIntArray> rounds;
  rounds->SetName("SeedCodeRounds");
  rounds->InsertNextValue(r.rounds);
  fd->AddArray(rounds);
  vtkNew<vtkDoubleArray> sent;
  sent->SetName("SeedCodeVoxelsSent");
  sent->InsertNextValue(static_cast<double>(r.reportedVoxels));
  fd->AddArray(sent);
  vtkNew<vtkIntArray> root;
  root->SetName("SeedCodeRoot");
  root->SetNumberOfComponents(3);
  root->InsertNextTuple3(static_cast<double>(r.root_Whole[0]),
    static_cast<double>(r.root_Whole[1]),
    static_cast<double>(r.root_Whole[2]));
  fd->AddArray(root);
}

} // namespace vtouch
