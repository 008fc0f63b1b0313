// vtouch::DistributedGlobalField: the layout and joining both global-field modes share, and the
// two sources of the field (the seed's, the automatic roots').
#include "vtouchDistributedGlobalField.h"

#include "vtouchAutomaticRootDistributedCoding.h"
#include "vtouchSeededDistributedCoding.h"

#include "vtouchCandidateRegionRunner.h"
#include "vtouchControllerCollectives.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"

#include <stdexcept>
#include <utility>

namespace vtouch
{
namespace
{
/// The seeded modes' field (SeededDistributedCoding: the single run's code from the seed).
class SeededSource : public DistributedGlobalField::Source
{
public:
  SeededSource(RankCollectives& c,
    PieceLayout layout,
    const std::array<double, 3>& spacing_mm,
    bool hasSeed,
    const std::array<std::int64_t, 3>& seed_Whole,
    const SeededDistributedCoding::Settings& settings)
    : Coding(c, std::move(layout), spacing_mm, hasSeed, seed_Whole, settings)
  {
  }
  std::vector<float> code(SparseVesselMask& mask) override { return this->Coding.code(mask); }
  void join() override { this->Coding.join(); }
  bool joined() const override { return this->Coding.joined(); }
  void addReport(vtkFieldData* fd) const override
  {
    const SeededDistributedCoding::Report& r = this->Coding.report();
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

private:
  SeededDistributedCoding Coding;
};

/// The unseeded modes' field (AutomaticRootDistributedCoding: the single run's automatic roots).
class AutomaticRootSource : public DistributedGlobalField::Source
{
public:
  AutomaticRootSource(RankCollectives& c,
    PieceLayout layout,
    const std::array<double, 3>& spacing_mm,
    const DistributedRootChoice::Parameters& parameters)
    : Coding(c, std::move(layout), spacing_mm, parameters)
  {
  }
  std::vector<float> code(SparseVesselMask& mask) override { return this->Coding.code(mask); }
  void join() override { this->Coding.join(); }
  bool joined() const override { return this->Coding.joined(); }
  void addReport(vtkFieldData* fd) const override
  {
    const DistributedRootChoice::Result& r = this->Coding.report();
    const auto addInt = [fd](const char* name, int value)
    {
      vtkNew<vtkIntArray> a;
      a->SetName(name);
      a->InsertNextValue(value);
      fd->AddArray(a);
    };
    addInt("RootChoiceRounds", r.rounds);
    addInt("RootChoicePropagations", r.propagations);
    addInt("RootChoiceComponents", static_cast<int>(r.components.size()));
    vtkNew<vtkIntArray> roots;
    roots->SetName("RootChoiceRoots");
    roots->SetNumberOfComponents(3);
    for (const DistributedRootChoice::ComponentRoot& component : r.components)
    {
      for (const std::array<std::int64_t, 3>& v : component.roots_Whole)
      {
        roots->InsertNextTuple3(
          static_cast<double>(v[0]), static_cast<double>(v[1]), static_cast<double>(v[2]));
      }
    }
    fd->AddArray(roots);
  }

private:
  AutomaticRootDistributedCoding Coding;
};

std::array<double, 3> spacingOf(vtkImageData* input)
{
  std::array<double, 3> spacing_mm{ 1.0, 1.0, 1.0 };
  if (input)
  {
    input->GetSpacing(spacing_mm.data());
  }
  return spacing_mm;
}
} // namespace

PieceLayout DistributedGlobalField::gatherLayout(RankCollectives& c,
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

std::array<std::int64_t, 3> DistributedGlobalField::seedVoxel_Whole(vtkImageData* input,
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

DistributedGlobalField::DistributedGlobalField(vtkMultiProcessController* controller,
  const CancellableCollectives::CancelCheck& cancelRequested)
  : Exchanges(std::make_unique<ControllerCollectives>(controller))
  , Collectives(std::make_unique<CancellableCollectives>(*this->Exchanges, cancelRequested))
{
}

DistributedGlobalField::~DistributedGlobalField() = default;

std::unique_ptr<DistributedGlobalField> DistributedGlobalField::seeded(
  vtkMultiProcessController* controller,
  vtkImageData* input,
  const VoxelExtent6& whole,
  bool hasSeed,
  const std::array<std::int64_t, 3>& seed_Whole,
  bool clearOuterLayer,
  const CancellableCollectives::CancelCheck& cancelRequested)
{
  std::unique_ptr<DistributedGlobalField> f(
    new DistributedGlobalField(controller, cancelRequested));
  SeededDistributedCoding::Settings settings;
  settings.clearOuterLayer = clearOuterLayer;
  PieceLayout layout = gatherLayout(*f->Collectives, input, input != nullptr, whole);
  f->FaceTips = std::make_unique<DistributedFaceTips>(*f->Collectives, layout);
  f->FaceTips->setOuterLayerCleared(clearOuterLayer); // the face tips where the coded mask ends
  f->Field = std::make_unique<SeededSource>(*f->Collectives,
    std::move(layout),
    spacingOf(input),
    hasSeed && input != nullptr,
    seed_Whole,
    settings);
  return f;
}

std::unique_ptr<DistributedGlobalField> DistributedGlobalField::automaticRoot(
  vtkMultiProcessController* controller,
  vtkImageData* input,
  const VoxelExtent6& whole,
  const DistributedRootChoice::Parameters& parameters,
  const CancellableCollectives::CancelCheck& cancelRequested)
{
  std::unique_ptr<DistributedGlobalField> f(
    new DistributedGlobalField(controller, cancelRequested));
  PieceLayout layout = gatherLayout(*f->Collectives, input, input != nullptr, whole);
  f->FaceTips = std::make_unique<DistributedFaceTips>(*f->Collectives, layout);
  f->Field = std::make_unique<AutomaticRootSource>(
    *f->Collectives, std::move(layout), spacingOf(input), parameters);
  return f;
}

std::vector<float> DistributedGlobalField::code(SparseVesselMask& mask)
{
  std::vector<float> ss = this->Field->code(mask);
  this->FieldGiven = true;
  return ss;
}

std::vector<std::int64_t> DistributedGlobalField::faceTips(const skeleton::SkeletonTracer& tracer)
{
  return this->FaceTips->answer(tracer);
}

void DistributedGlobalField::finish()
{
  if (!this->Field->joined())
  {
    try
    {
      this->Field->join();
      this->FieldGiven = true;
    }
    catch (const std::runtime_error&)
    {
      // This rank's run failed before its coder: its own message speaks for it (the others
      // report the common verdict).
    }
  }
  // The face tips' rounds follow the field's on every rank that got the field: a rank whose
  // coder stopped before them (an error, a cancel) still takes part, with nothing to tell.
  if (this->FieldGiven && !this->FaceTips->joined())
  {
    try
    {
      this->FaceTips->join();
    }
    catch (const std::runtime_error&)
    {
      // Its own run's message stands.
    }
  }
}

void DistributedGlobalField::addReport(vtkFieldData* fd) const
{
  this->Field->addReport(fd);
}

} // namespace vtouch
