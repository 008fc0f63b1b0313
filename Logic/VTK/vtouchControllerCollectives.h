// vtouch::RankCollectives over a vtkMultiProcessController (the pvserver's ranks under MPI): the
// distributed raw seeded mode's exchanges (Logic/Skeleton/vtouchDistributedCandidateRegion.h).
// Not a wrapped class: VesselCenterline's private helper.
#pragma once

#include "vtouchRankCollectives.h"

class vtkMultiProcessController;

namespace vtouch
{

class ControllerCollectives : public RankCollectives
{
public:
  explicit ControllerCollectives(vtkMultiProcessController* controller)
    : Controller(controller)
  {
  }
  int rank() const override;
  int ranks() const override;
  /// The lengths first (AllGather), then the values (AllGatherV).
  std::vector<std::vector<double>> allGather(const std::vector<double>& mine) override;
  std::vector<std::vector<std::int64_t>> allGather(const std::vector<std::int64_t>& mine) override;
  /// The lengths first (Gather), then the values (GatherV), both to `root` only.
  std::vector<std::vector<std::int64_t>> gather(const std::vector<std::int64_t>& mine,
    int root) override;

private:
  vtkMultiProcessController* Controller;
};

} // namespace vtouch
