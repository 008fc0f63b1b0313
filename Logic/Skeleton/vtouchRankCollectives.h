// The collective operations the distributed raw-angiogram stages need (issue 19 item 2, issue 16
// item 1 on a parallel pvserver), as an interface: VesselCenterline implements it with
// vtkMultiProcessController (Logic/VTK/vtouchControllerCollectives.h), the tests with threads in
// one process. Every rank calls every operation in the same order (a collective); each call
// returns only when every rank has made it.
#pragma once

#include <cstdint>
#include <vector>

namespace vtouch
{

class RankCollectives
{
public:
  virtual ~RankCollectives() = default;
  virtual int rank() const = 0;
  virtual int ranks() const = 0;
  /// Every rank's `mine`, indexed by rank (lengths may differ between ranks).
  virtual std::vector<std::vector<double>> allGather(const std::vector<double>& mine) = 0;
  virtual std::vector<std::vector<std::int64_t>> allGather(
    const std::vector<std::int64_t>& mine) = 0;
  /// Every rank's `mine`, indexed by rank, on `root` only (the others get an empty list): what
  /// only one rank needs (DistributedVolumePages' pages) never reaches the others.
  virtual std::vector<std::vector<std::int64_t>> gather(const std::vector<std::int64_t>& mine,
    int root) = 0;

  /// The largest of the ranks' `value`s.
  double maximum(double value)
  {
    double m = value;
    for (const std::vector<double>& v : this->allGather(std::vector<double>{ value }))
    {
      m = v.empty() ? m : (v[0] > m ? v[0] : m);
    }
    return m;
  }
  /// The sum of the ranks' `value`s.
  double sum(double value)
  {
    double s = 0.0;
    for (const std::vector<double>& v : this->allGather(std::vector<double>{ value }))
    {
      s += v.empty() ? 0.0 : v[0];
    }
    return s;
  }
  /// `root`'s `values` on every rank (the others' `values` are ignored).
  std::vector<double> broadcast(const std::vector<double>& values, int root)
  {
    const bool mine = this->rank() == root;
    std::vector<std::vector<double>> all = this->allGather(mine ? values : std::vector<double>{});
    return all[static_cast<std::size_t>(root)];
  }
  /// `root`'s `values` on every rank (the others' `values` are ignored).
  std::vector<std::int64_t> broadcast(const std::vector<std::int64_t>& values, int root)
  {
    const bool mine = this->rank() == root;
    std::vector<std::vector<std::int64_t>> all =
      this->allGather(mine ? values : std::vector<std::int64_t>{});
    return all[static_cast<std::size_t>(root)];
  }
};

} // namespace vtouch
