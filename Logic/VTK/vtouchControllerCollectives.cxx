#include "vtouchControllerCollectives.h"

#include "vtkMultiProcessController.h"

namespace vtouch
{
namespace
{
template<typename V>
std::vector<std::vector<V>> gatherAll(vtkMultiProcessController* c, const std::vector<V>& mine)
{
  const int ranks = c->GetNumberOfProcesses();
  const vtkIdType length = static_cast<vtkIdType>(mine.size());
  std::vector<vtkIdType> lengths(static_cast<std::size_t>(ranks), 0);
  c->AllGather(&length, lengths.data(), 1);
  std::vector<vtkIdType> offsets(static_cast<std::size_t>(ranks), 0);
  vtkIdType total = 0;
  for (int r = 0; r < ranks; ++r)
  {
    offsets[static_cast<std::size_t>(r)] = total;
    total += lengths[static_cast<std::size_t>(r)];
  }
  // One element more than needed: a zero-length buffer's data() may be null.
  std::vector<V> received(static_cast<std::size_t>(total) + 1);
  std::vector<V> sent(mine);
  sent.push_back(V{});
  c->AllGatherV(sent.data(), received.data(), length, lengths.data(), offsets.data());
  std::vector<std::vector<V>> out(static_cast<std::size_t>(ranks));
  for (int r = 0; r < ranks; ++r)
  {
    const auto begin = received.begin() + offsets[static_cast<std::size_t>(r)];
    out[static_cast<std::size_t>(r)].assign(begin, begin + lengths[static_cast<std::size_t>(r)]);
  }
  return out;
}

/// `mine` of every rank on `root` (empty lists on the others).
std::vector<std::vector<std::int64_t>> gatherTo(vtkMultiProcessController* c,
  const std::vector<std::int64_t>& mine,
  int root)
{
  const int ranks = c->GetNumberOfProcesses();
  const vtkIdType length = static_cast<vtkIdType>(mine.size());
  std::vector<vtkIdType> lengths(static_cast<std::size_t>(ranks), 0);
  c->Gather(&length, lengths.data(), 1, root);
  std::vector<vtkIdType> offsets(static_cast<std::size_t>(ranks), 0);
  vtkIdType total = 0;
  for (int r = 0; r < ranks; ++r)
  {
    offsets[static_cast<std::size_t>(r)] = total;
    total += lengths[static_cast<std::size_t>(r)];
  }
  // One element more than needed: a zero-length buffer's data() may be null.
  std::vector<std::int64_t> received(static_cast<std::size_t>(total) + 1);
  std::vector<std::int64_t> sent(mine);
  sent.push_back(0);
  c->GatherV(sent.data(), received.data(), length, lengths.data(), offsets.data(), root);
  std::vector<std::vector<std::int64_t>> out(static_cast<std::size_t>(ranks));
  if (c->GetLocalProcessId() != root)
  {
    return out;
  }
  for (int r = 0; r < ranks; ++r)
  {
    const auto begin = received.begin() + offsets[static_cast<std::size_t>(r)];
    out[static_cast<std::size_t>(r)].assign(begin, begin + lengths[static_cast<std::size_t>(r)]);
  }
  return out;
}
} // namespace

int ControllerCollectives::rank() const
{
  return this->Controller->GetLocalProcessId();
}

int ControllerCollectives::ranks() const
{
  return this->Controller->GetNumberOfProcesses();
}

std::vector<std::vector<double>> ControllerCollectives::allGather(const std::vector<double>& mine)
{
  return gatherAll(this->Controller, mine);
}

std::vector<std::vector<std::int64_t>> ControllerCollectives::allGather(
  const std::vector<std::int64_t>& mine)
{
  return gatherAll(this->Controller, mine);
}

} // namespace vtouch

namespace vtouch
{
std::vector<std::vector<std::int64_t>> ControllerCollectives::gather(
  const std::vector<std::int64_t>& mine,
  int root)
{
  return gatherTo(this->Controller, mine, root);
}
} // namespace vtouch
