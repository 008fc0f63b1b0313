// Cancel from another thread (the GUI's Cancel, issue 16 item 6): the centerline's stages stop at
// their next check point with no output, and free what they allocated on the way out (ASan's leak
// check runs these tests too; the TSan build runs them for the flag's and the BS thread's
// synchronisation: label `threads`).
//
// Each test runs the computation on a worker thread whose progress callback reads an atomic flag
// set by the test's thread, as the panel's Cancel sets it. To cancel at a chosen check point
// deterministically, the callback waits there until the test's thread has set the flag.
#include "vtouchPhantomGenerator.h"
#include "vtouchProgress.h"
#include "vtouchVesselCandidateRegion.h"
#include "vtouchVoxelCoding.h"

#include <gtest/gtest.h>
#include <itkMultiThreaderBase.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <thread>
#include <vector>

namespace vtouch
{
namespace
{

/// ITK's smoothing (the tubularity) runs on the calling thread here: ITK's own thread pool is not
/// what these tests are about, and TSan, which does not see into the uninstrumented ITK library,
/// reports the pool's internal hand-offs.
void itkOnTheCallingThread()
{
  itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(1);
}

/// A raw-angiogram phantom (random tree, partial volume, noise, plates and blobs) of 96^3 voxels
/// and the world position of its root, where a user would click.
struct Angiogram
{
  std::vector<float> voxels;
  VolumeView<float> view;
  std::array<std::int64_t, 3> seed{};

  Angiogram()
  {
    itkOnTheCallingThread();
    PhantomSpec spec;
    spec.shape = PhantomShape::RawAngiogram;
    spec.dimensions = { 96, 96, 96 };
    spec.noiseStdDev = 20.0;
    PhantomGenerator generator(spec);
    EXPECT_TRUE(generator.ok()) << generator.error();
    voxels.resize(96 * 96 * 96);
    EXPECT_TRUE(generator.fill(voxels.data()));
    view.voxels = voxels.data();
    view.dims = { 96, 96, 96 };
    const Vec3 root = generator.centerline().paths.at(0).points.at(0).position_World_mm;
    seed = { std::llround(root.x), std::llround(root.y), std::llround(root.z) };
  }
};

/// The progress values of an uncancelled run: where its check points are.
std::vector<double> checkPoints(const Angiogram& a)
{
  std::vector<double> seen;
  VesselCandidateRegion::Settings s;
  s.useSeed = true;
  s.seed = a.seed;
  s.progress = [&seen](double f)
  {
    seen.push_back(f);
    return true;
  };
  const VesselCandidateRegion::Result r = VesselCandidateRegion::extract(a.view, s);
  EXPECT_TRUE(r.ok) << r.message;
  return seen;
}

/// What a run cancelled from another thread at check point `at` did.
struct CancelledRun
{
  bool threwCancelled = false;
  bool finished = false;
  int checkPointsAfterCancel = 0;
  double lastProgress = -1.0;
};

CancelledRun cancelAt(const Angiogram& a, std::size_t at)
{
  std::atomic<bool> cancel{ false };
  std::atomic<bool> reached{ false };
  CancelledRun run;
  std::thread worker(
    [&]()
    {
      VesselCandidateRegion::Settings s;
      s.useSeed = true;
      s.seed = a.seed;
      std::size_t calls = 0;
      s.progress = [&](double f)
      {
        if (calls++ == at)
        {
          reached = true;
          while (!cancel.load()) // the test's thread sets it now
          {
            std::this_thread::yield();
          }
        }
        run.lastProgress = f;
        if (cancel.load())
        {
          ++run.checkPointsAfterCancel;
          return false;
        }
        return true;
      };
      try
      {
        VesselCandidateRegion::extract(a.view, s);
        run.finished = true;
      }
      catch (const Cancelled&)
      {
        run.threwCancelled = true;
      }
    });
  while (!reached.load())
  {
    std::this_thread::yield();
  }
  cancel = true;
  worker.join();
  return run;
}

TEST(CancelCandidateRegion, EveryStageStopsAtItsNextCheckPoint)
{
  const Angiogram a;
  const std::vector<double> seen = checkPoints(a);
  ASSERT_FALSE(seen.empty());
  // The stages' shares of the progress (VesselCandidateRegion::extract): range, grow, depth,
  // tubularity, necks. Each has check points, and a cancel at the first of each stops the run.
  const double stages[][2] = {
    { 0.0, 0.1 }, { 0.1, 0.2 }, { 0.2, 0.25 }, { 0.25, 0.9 }, { 0.9, 1.0 }
  };
  for (const auto& stage : stages)
  {
    std::size_t first = seen.size();
    for (std::size_t i = 0; i < seen.size(); ++i)
    {
      if (seen[i] >= stage[0] && seen[i] < stage[1])
      {
        first = i;
        break;
      }
    }
    ASSERT_LT(first, seen.size()) << "no check point in [" << stage[0] << ", " << stage[1] << ")";
    const CancelledRun run = cancelAt(a, first);
    EXPECT_TRUE(run.threwCancelled) << "stage from " << stage[0];
    EXPECT_FALSE(run.finished);
    // Promptly: the check point that saw the flag was the last one.
    EXPECT_EQ(run.checkPointsAfterCancel, 1) << "stage from " << stage[0];
    EXPECT_LT(run.lastProgress, stage[1]);
  }
}

TEST(CancelCandidateRegion, CheckPointsAreDenseInTheLongStages)
{
  // The tubularity (most of the time on raw angiograms) reports at every tile; the whole run
  // reports tens of times, so a cancel waits for at most a few per cent of it.
  const Angiogram a;
  const std::vector<double> seen = checkPoints(a);
  const auto inTubularity =
    std::count_if(seen.begin(), seen.end(), [](double f) { return f >= 0.25 && f < 0.9; });
  EXPECT_GE(inTubularity, 8);
  for (std::size_t i = 1; i < seen.size(); ++i)
  {
    EXPECT_GE(seen[i], seen[i - 1] - 1e-12) << "progress goes forward";
  }
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
}

/// A thick tube of about 3e5 voxels: the BS code runs on the coder's second thread.
SparseVesselMask thickTube()
{
  const std::array<std::int64_t, 3> d{ 200, 64, 64 };
  SparseVesselMask mask(d);
  for (std::int64_t k = 0; k < d[2]; ++k)
    for (std::int64_t j = 0; j < d[1]; ++j)
      for (std::int64_t i = 4; i < d[0] - 4; ++i)
      {
        if ((j - 32) * (j - 32) + (k - 32) * (k - 32) <= 24 * 24)
        {
          mask.set(static_cast<std::uint64_t>(i + d[0] * (j + d[1] * k)));
        }
      }
  mask.finalize();
  return mask;
}

TEST(CancelVoxelCoder, CancelWhileTheBoundaryThreadRunsStopsAndJoinsIt)
{
  const SparseVesselMask mask = thickTube();
  ASSERT_GT(mask.vesselCount(), std::uint64_t{ 1 } << 17);
  VoxelCodingParameters p;
  p.hasSeed = true;
  p.seedIndex = { 10, 32, 32 };
  std::atomic<bool> cancel{ false };
  std::atomic<bool> reached{ false };
  int after = 0;
  bool threw = false;
  std::thread worker(
    [&]()
    {
      int calls = 0;
      try
      {
        VoxelCoder coder(mask, p);
        coder.run(
          [&](double)
          {
            if (calls++ == 0) // the first check point: the BS thread has just started
            {
              reached = true;
              while (!cancel.load())
              {
                std::this_thread::yield();
              }
            }
            if (cancel.load())
            {
              ++after;
              return false;
            }
            return true;
          });
      }
      catch (const Cancelled&) // VoxelCodingAborted is one
      {
        threw = true;
      }
    });
  while (!reached.load())
  {
    std::this_thread::yield();
  }
  cancel = true;
  worker.join(); // returns only once the coder joined its BS thread
  EXPECT_TRUE(threw);
  EXPECT_EQ(after, 1);
}

TEST(CancelVoxelCoder, AnUncancelledRunStillCodesTheTube)
{
  const SparseVesselMask mask = thickTube();
  VoxelCodingParameters p;
  p.hasSeed = true;
  p.seedIndex = { 10, 32, 32 };
  std::atomic<int> calls{ 0 };
  RawSkeleton out;
  std::thread worker(
    [&]()
    {
      VoxelCoder coder(mask, p);
      out = coder.run(
        [&](double)
        {
          ++calls;
          return true;
        });
    });
  worker.join();
  EXPECT_GE(out.paths.size(), 1U);
  EXPECT_GE(calls.load(), 4);
}

} // namespace
} // namespace vtouch
