// Voxel coding stage 1: the BS code, as an exact separable Euclidean distance transform
// restricted to the vessel voxels.
//
// Why separable: the vector propagation it replaces visited every vessel voxel's 26 neighbours
// once per improvement (about 40 % of the coder's time). Here each vessel voxel is touched a few
// times per axis, in runs, and the result is exact (the propagation was not, by a few per cent
// at some voxels).
//
// Why restricted to runs: along one axis, the squared distance of a vessel voxel is the lower
// envelope of parabolas f(s) + (x - s)^2 over all voxels s of its line. The background voxel
// just before and just after the voxel's vessel run (f = 0) is closer than anything beyond it, so
// only the run and its two bounding background voxels matter: the work is linear in the vessel
// voxels, and nothing is allocated per volume voxel (columns are gathered plane by plane with a
// counting sort on x: scratch for the largest plane only).
#include "vtouchSkeletonBoundaryCodeStage.h"

#include "vtouchProgress.h"
#include "vtouchSkeletonVoxelCodes.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <system_error>

namespace vtouch
{
namespace skeleton
{
namespace
{
constexpr float kInf = VoxelCodes::kInf;
} // namespace

BoundaryCodeStage::BoundaryCodeStage(const VoxelGrid& g, RunMeter& m, std::vector<float>& codes)
  : grid(g)
  , meter(m)
  , bs(codes)
{
}

void BoundaryCodeStage::boundaryCheckpoint() const
{
  if (boundaryQuiet && meter.stopRequested.load(std::memory_order_relaxed))
  {
    throw Cancelled();
  }
}

void BoundaryCodeStage::rowPass()
{
  // Along x, runs are consecutive ranks: the distance to the nearest background voxel of the row
  // is the distance to the run's ends. Outside the volume is not background.
  std::uint32_t runStart = 0;
  std::int64_t runFirstI = 0, previousI = -2;
  std::uint64_t previousLin = 0;
  std::uint32_t r = 0;
  const auto closeRun = [&](std::uint32_t end, std::int64_t lastI)
  {
    for (std::uint32_t q = runStart; q < end; ++q)
    {
      const std::int64_t i = runFirstI + static_cast<std::int64_t>(q - runStart);
      const double left = runFirstI > 0 ? static_cast<double>(i - runFirstI + 1) : kInf;
      const double right = lastI < grid.nx - 1 ? static_cast<double>(lastI - i + 1) : kInf;
      const double d = std::min(left, right) * grid.sp[0];
      bs[q] = static_cast<float>(d * d);
    }
  };
  grid.mask.forEach(
    [&](std::uint64_t lin)
    {
      std::int64_t c[3];
      grid.coords(lin, c);
      if (!(r > 0 && lin == previousLin + 1 && c[0] == previousI + 1))
      {
        if (r > 0)
        {
          closeRun(r, previousI);
        }
        runStart = r;
        runFirstI = c[0];
      }
      previousLin = lin;
      previousI = c[0];
      ++r;
      if (!boundaryQuiet)
      {
        meter.tick();
      }
      else if ((r & 0xFFFF) == 0)
      {
        boundaryCheckpoint();
      }
    });
  if (r > 0)
  {
    closeRun(r, previousI);
  }
}

void BoundaryCodeStage::linePass(int axis)
{
  // Plane by plane (z slices for the pass along y, y slabs for the pass along z): gather the
  // plane's vessel voxels row by row (a row is a run of consecutive ranks), sort them by x with a
  // counting sort (stable: each column comes out sorted along the axis) and solve each column's
  // vessel runs. Scratch: the largest plane's vessel voxels and one counter per x, never a
  // per-vessel-voxel or per-volume-line array.
  const std::int64_t len = axis == 1 ? grid.ny : grid.nz;
  const std::int64_t planes = axis == 1 ? grid.nz : grid.ny;
  const double s = grid.sp[axis];
  std::vector<std::uint32_t> start(static_cast<std::size_t>(grid.nx) + 1);
  for (std::int64_t p = 0; p < planes; ++p)
  {
    boundaryCheckpoint();
    const auto rowBegin = [&](std::int64_t t) {
      return static_cast<std::uint64_t>(grid.nx * (axis == 1 ? t + grid.ny * p : p + grid.ny * t));
    };
    std::fill(start.begin(), start.end(), 0U);
    std::uint32_t count = 0;
    for (std::int64_t t = 0; t < len; ++t)
    {
      const std::uint64_t row = rowBegin(t);
      grid.mask.forEachIn(row,
        row + static_cast<std::uint64_t>(grid.nx),
        [&](std::uint64_t lin)
        {
          ++start[lin - row + 1];
          ++count;
        });
    }
    if (count == 0)
    {
      continue;
    }
    for (std::int64_t i = 0; i < grid.nx; ++i)
    {
      start[i + 1] += start[i];
    }
    planeRank.resize(count);
    planePosition.resize(count);
    for (std::int64_t t = 0; t < len; ++t)
    {
      const std::uint64_t row = rowBegin(t);
      std::uint32_t rank = grid.mask.rankBefore(row);
      grid.mask.forEachIn(row,
        row + static_cast<std::uint64_t>(grid.nx),
        [&](std::uint64_t lin)
        {
          const std::uint32_t slot = start[lin - row]++;
          planeRank[slot] = rank++;
          planePosition[slot] = static_cast<std::uint32_t>(t);
        });
    }
    // Now start[i] is the end of column i (and the beginning of column i + 1).
    std::uint32_t begin = 0;
    for (std::int64_t i = 0; i < grid.nx; ++i)
    {
      const std::uint32_t end = start[i];
      std::uint32_t a = begin;
      while (a < end)
      {
        std::uint32_t b = a + 1;
        while (b < end && planePosition[b] == planePosition[b - 1] + 1)
        {
          ++b;
        }
        envelopeOfRun(planeRank.data() + a, planePosition[a], b - a, len, s, origin[axis]);
        a = b;
      }
      begin = end;
    }
    boundaryScratchBytes = std::max(boundaryScratchBytes,
      (planeRank.capacity() + planePosition.capacity() + start.size()) * sizeof(std::uint32_t));
    if (!boundaryQuiet)
    {
      meter.tick(count);
    }
  }
}

void BoundaryCodeStage::envelopeOfRun(const std::uint32_t* ranks,
  std::uint32_t first,
  std::uint32_t count,
  std::int64_t len,
  double spacing,
  std::int64_t offset)
{
  // Sites (position mm, value mm^2): the bounding background voxels and the run's finite values;
  // lower envelope of the parabolas (Felzenszwalb & Huttenlocher's 1D distance transform).
  siteX.clear();
  siteF.clear();
  if (first > 0)
  {
    siteX.push_back((static_cast<double>(offset + first) - 1.0) * spacing);
    siteF.push_back(0.0);
  }
  for (std::uint32_t q = 0; q < count; ++q)
  {
    const float f = bs[ranks[q]];
    if (f < kInf)
    {
      siteX.push_back(static_cast<double>(offset + first + q) * spacing);
      siteF.push_back(f);
    }
  }
  if (static_cast<std::int64_t>(first + count) < len)
  {
    siteX.push_back(static_cast<double>(offset + first + count) * spacing);
    siteF.push_back(0.0);
  }
  if (siteX.empty())
  {
    return; // no finite value along this run yet
  }
  const std::size_t m = siteX.size();
  envelopeSite.resize(m);
  envelopeFrom.resize(m + 1);
  std::size_t top = 0;
  envelopeSite[0] = 0;
  envelopeFrom[0] = -kInf;
  envelopeFrom[1] = kInf;
  for (std::size_t q = 1; q < m; ++q)
  {
    double cut = 0.0;
    while (true)
    {
      const std::size_t v = envelopeSite[top];
      cut = ((siteF[q] + siteX[q] * siteX[q]) - (siteF[v] + siteX[v] * siteX[v])) /
            (2.0 * (siteX[q] - siteX[v]));
      if (cut <= envelopeFrom[top] && top > 0)
      {
        --top;
        continue;
      }
      break;
    }
    if (cut <= envelopeFrom[top])
    {
      envelopeSite[top] = q; // top == 0: the new parabola is lower everywhere
      continue;
    }
    ++top;
    envelopeSite[top] = q;
    envelopeFrom[top] = cut;
    envelopeFrom[top + 1] = kInf;
  }
  std::size_t k = 0;
  for (std::uint32_t q = 0; q < count; ++q)
  {
    const double x = static_cast<double>(offset + first + q) * spacing;
    while (envelopeFrom[k + 1] < x)
    {
      ++k;
    }
    const std::size_t v = envelopeSite[k];
    bs[ranks[q]] = static_cast<float>((x - siteX[v]) * (x - siteX[v]) + siteF[v]);
  }
}

void BoundaryCodeStage::start()
{
  // A thread costs ~0.2 MB of stack and heap arena: worth it only for large vessels.
  constexpr std::size_t kThreadFrom = 1U << 17;
  if (bs.size() >= kThreadFrom)
  {
    boundaryQuiet = true;
    try
    {
      boundaryThread = std::thread([this] { computeOnThread(); });
      return;
    }
    catch (const std::system_error&)
    {
      boundaryQuiet = false; // no thread available: compute it here
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  compute();
  meter.stageSeconds.emplace_back(
    "bs", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
}

void BoundaryCodeStage::computeOnThread()
{
  try
  {
    const auto t0 = std::chrono::steady_clock::now();
    compute();
    boundarySeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  catch (...)
  {
    boundaryError = std::current_exception(); // rethrown by await()
  }
}

void BoundaryCodeStage::await()
{
  if (!boundaryThread.joinable())
  {
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  boundaryThread.join();
  const double waited =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (boundaryError)
  {
    std::rethrow_exception(boundaryError);
  }
  // "bs" is the thread's own time; "bs(wait)" the part the caller waited for.
  meter.stageSeconds.emplace_back("bs", boundarySeconds);
  meter.stageSeconds.emplace_back("bs(wait)", waited);
  meter.tick(2 * bs.size());
}

BoundaryCodeStage::~BoundaryCodeStage()
{
  if (boundaryThread.joinable())
  {
    meter.stopRequested =
      true; // the run is unwinding (cancelled or failed): no one needs the BS code
    boundaryThread.join();
  }
}

void BoundaryCodeStage::compute()
{
  // Timed by the caller (it may run on a second thread: no StageTimer, whose list is shared).
  // bs holds squared distances (mm^2) until the last pass.
  rowPass();
  linePass(1);
  linePass(2);
  for (float& d : bs)
  {
    d = std::sqrt(d);
  }
  planeRank = {};
  planePosition = {};
  siteX = {};
  siteF = {};
  envelopeSite = {};
  envelopeFrom = {};
}

} // namespace skeleton
} // namespace vtouch
