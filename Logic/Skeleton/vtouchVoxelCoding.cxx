// vtouch::VoxelCoder: runs the stages of the voxel coding in order, per component of the mask.
// The stages, their inputs and outputs: Docs/CENTERLINES.md, "Stage map".
#include "vtouchVoxelCoding.h"

#include "vtouchSkeletonBoundaryCodeStage.h"
#include "vtouchSkeletonClusterStage.h"
#include "vtouchSkeletonDraft.h"
#include "vtouchSkeletonEndStage.h"
#include "vtouchSkeletonGeometryStage.h"
#include "vtouchSkeletonLoopStage.h"
#include "vtouchSkeletonRunMeter.h"
#include "vtouchSkeletonSeedCodeStage.h"
#include "vtouchSkeletonTraceStage.h"
#include "vtouchSkeletonTracer.h"
#include "vtouchSkeletonVoxelCodes.h"
#include "vtouchSkeletonVoxelGrid.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

namespace vtouch
{

/// One run: the data the stages pass on (codes, clusters, the draft skeleton) and the stages that
/// keep state across components (the SS code's explorer, the tracer's index of skeleton voxels).
struct VoxelCoder::Impl
{
  Impl(const SparseVesselMask& mask,
    const VoxelCodingParameters& parameters,
    const std::function<bool(double)>& progress)
    : par(parameters)
    , meter(progress)
    , grid(mask, parameters.spacing_mm, parameters.clusterWidth_mm, parameters.first_Whole)
    , seedCode(grid, meter, codes, parameters.clusterWidth_mm)
    , clusterStage(grid, meter, codes, graph)
    , tracer(grid, meter, codes, graph, draft)
    , boundaryCode(grid, meter, codes.bs)
  {
  }

  RawSkeleton run();

  /// Stages 2-7 on one component: its SS code from `sources` (empty: already propagated), then
  /// the clusters (re-rooted at the thickest end when `chooseRoot`), trace, loops, ends, geometry.
  void handleComponent(const std::vector<std::uint32_t>& sources, bool chooseRoot);
  /// Stages 4-7 on the component's clusters.
  void traceComponent();
  /// Flags the last propagation's voxels as handled.
  void markComponent();
  /// Stages 3-7 on the voxels the given global SS field reaches (parameters' globalSs_mm).
  void codeGlobalField();

  const VoxelCodingParameters& par;
  skeleton::RunMeter meter;
  skeleton::VoxelGrid grid;
  skeleton::VoxelCodes codes;
  skeleton::ClusterGraph graph;
  skeleton::SkeletonDraft draft;
  skeleton::SeedCodeStage seedCode;
  skeleton::ClusterStage clusterStage;
  skeleton::SkeletonTracer tracer;
  /// The face tips' answers (VoxelCodingParameters::faceTipBands), per cluster; empty without.
  std::vector<std::int64_t> faceTipBands;
  // Last: destroyed first, its thread joined before the arrays it writes go.
  skeleton::BoundaryCodeStage boundaryCode;
};

void VoxelCoder::Impl::markComponent()
{
  for (std::uint32_t v : codes.order)
  {
    codes.flags[grid.mask.rank(v)] |= skeleton::VoxelCodes::kComponent;
  }
}

void VoxelCoder::Impl::codeGlobalField()
{
  codes.ss = *par.globalSs_mm;
  // What propagate() leaves: the reached voxels in SS order (ties by index), flagged kDone.
  codes.order.clear();
  grid.mask.forEach(
    [&](std::uint64_t lin)
    {
      if (codes.ss[grid.mask.rank(lin)] != skeleton::VoxelCodes::kInf)
      {
        codes.order.push_back(static_cast<std::uint32_t>(lin));
      }
    });
  const std::vector<float>& ss = codes.ss;
  const skeleton::VoxelGrid& g = grid;
  std::stable_sort(codes.order.begin(),
    codes.order.end(),
    [&](std::uint32_t a, std::uint32_t b) { return ss[g.mask.rank(a)] < ss[g.mask.rank(b)]; });
  for (std::uint32_t lin : codes.order)
  {
    codes.flags[grid.mask.rank(lin)] |= skeleton::VoxelCodes::kDone;
  }
  if (!codes.order.empty())
  {
    handleComponent({}, false);
    markComponent();
  }
  else if (par.faceTipBands)
  {
    par.faceTipBands(tracer); // collective: joins the face tips' rounds without clusters
  }
}

void VoxelCoder::Impl::handleComponent(const std::vector<std::uint32_t>& sources, bool chooseRoot)
{
  if (!sources.empty())
  {
    seedCode.propagate(sources);
  }
  boundaryCode.await(); // the clusters read bs
  clusterStage.build();
  if (par.faceTipBands && par.globalSs_mm)
  {
    faceTipBands = par.faceTipBands(tracer); // the global field on several ranks: collective
  }
  if (chooseRoot)
  {
    if (const std::optional<std::uint32_t> root = clusterStage.thickerRoot())
    {
      draft.skeleton.roots.back().moved = true;
      draft.skeleton.roots.back().thickest = grid.voxelArray(*root);
      seedCode.reset();
      seedCode.propagate({ *root });
      clusterStage.build();
    }
  }
  traceComponent();
  ++draft.skeleton.components;
}

void VoxelCoder::Impl::traceComponent()
{
  const skeleton::StageTimer timer{ meter, "trace(all)" };
  const std::size_t firstPath = draft.skeleton.paths.size();
  const bool globalField = par.globalSs_mm != nullptr;
  if (skeleton::TraceStage(tracer,
        par.minimumBranchLength,
        globalField,
        faceTipBands.empty() ? nullptr : &faceTipBands)
        .run() == 0)
  {
    return;
  }
  skeleton::LoopStage(tracer, par.minimumBranchLength, firstPath, globalField).run();
  skeleton::EndStage(grid, par.minimumBranchLength, draft, firstPath, &codes.ss).run();
  skeleton::GeometryStage(draft.skeleton, firstPath, grid.minSpacing).run();
}

RawSkeleton VoxelCoder::Impl::run()
{
  using skeleton::VoxelCodes;
  std::unique_ptr<skeleton::StageTimer> timer(new skeleton::StageTimer{ meter, "coder(all)" });
  const SparseVesselMask& mask = grid.mask;
  const std::uint64_t n = mask.vesselCount();
  RawSkeleton& out = draft.skeleton;
  out.vesselVoxels = n;
  meter.setTotalWork(n * 6);
  // The codes' arrays (17 bytes per vessel voxel): their first touch takes a while on large
  // masks, a check point after each.
  codes.bs.assign(n, VoxelCodes::kInf);
  meter.checkpoint();
  graph.label.assign(n, 0);
  meter.checkpoint();
  codes.flags.assign(n, 0);
  codes.ss.assign(n, VoxelCodes::kInf);
  meter.checkpoint();
  codes.order.reserve(n);
  // The BS code runs beside the first propagation(s); handleComponent() waits for it.
  boundaryCode.start();

  if (par.globalSs_mm)
  {
    codeGlobalField();
  }
  else if (par.hasSeed)
  {
    const std::int64_t* s = par.seedIndex.data();
    handleComponent({ static_cast<std::uint32_t>(grid.linOf(s[0], s[1], s[2])) }, false);
  }
  else
  {
    mask.forEach(
      [&](std::uint64_t lin)
      {
        if (codes.flags[mask.rank(lin)] & VoxelCodes::kComponent)
        {
          return;
        }
        const std::uint32_t root = seedCode.coarseExtremity(static_cast<std::uint32_t>(lin));
        if (root != skeleton::SeedCodeStage::kNoVoxel &&
            !(codes.flags[mask.rank(root)] & VoxelCodes::kComponent))
        {
          seedCode.propagate({ root });
          if (codes.ss[mask.rank(lin)] != VoxelCodes::kInf) // else the blocks joined two
          {                                                 // components: exact search
            markComponent();
            if (codes.order.size() < par.minimumComponentSize)
            {
              seedCode.reset();
              return;
            }
            out.roots.push_back({ { grid.voxelArray(root) } });
            handleComponent({}, true);
            markComponent();
            return;
          }
          seedCode.reset();
        }
        seedCode.propagate({ static_cast<std::uint32_t>(lin) });
        markComponent();
        if (codes.order.size() < par.minimumComponentSize)
        {
          seedCode.reset();
          return;
        }
        const std::vector<std::uint32_t> region = seedCode.extremityRegion();
        seedCode.reset();
        out.roots.emplace_back();
        for (const std::uint32_t v : region)
        {
          out.roots.back().extremity.push_back(grid.voxelArray(v));
        }
        handleComponent(region, true);
        markComponent();
      });
  }
  boundaryCode.await(); // no component was large enough: nothing waited for it yet
  // The block mask and the explorer's codes live until the end of the run.
  const std::size_t clusterBytes =
    graph.clusters.capacity() * sizeof(skeleton::Cluster) + seedCode.explorerBytes();
  const std::size_t queueBytes = seedCode.peakQueue() * sizeof(std::uint32_t);
  // While the BS code runs, its scratch coexists with the first propagation's queue.
  out.peakBytes = n * (2 * sizeof(float) + sizeof(std::uint32_t) + 1) +
                  codes.order.capacity() * sizeof(std::uint32_t) +
                  std::max(queueBytes + clusterBytes, boundaryCode.scratchBytes() + queueBytes);
  meter.finish();
  timer.reset();
  out.stageSeconds = std::move(meter.stageSeconds);
  return std::move(out);
}

VoxelCoder::VoxelCoder(const SparseVesselMask& mask, const VoxelCodingParameters& parameters)
  : Mask(mask)
  , Parameters(parameters)
{
  for (double s : parameters.spacing_mm)
  {
    if (!(s > 0.0) || !std::isfinite(s))
    {
      throw std::invalid_argument("voxel spacing must be positive and finite");
    }
  }
  const auto& d = mask.dims();
  if (static_cast<double>(d[0] + 2) * static_cast<double>(d[1] + 2) *
        static_cast<double>(d[2] + 2) >=
      4294967295.0)
  {
    throw std::invalid_argument("volume too large for 32-bit voxel indices (at most ~4e9 voxels)");
  }
  if (mask.vesselCount() >= 0x7FFFFFFFULL)
  {
    throw std::invalid_argument("too many vessel voxels (at most 2^31 - 1)");
  }
  if (!(parameters.minimumBranchLength >= 0.0) || !std::isfinite(parameters.minimumBranchLength))
  {
    throw std::invalid_argument("minimum branch length must be finite and >= 0");
  }
  if (parameters.globalSs_mm && parameters.globalSs_mm->size() != mask.vesselCount())
  {
    throw std::invalid_argument("the global SS field has " +
                                std::to_string(parameters.globalSs_mm->size()) + " values for " +
                                std::to_string(mask.vesselCount()) + " vessel voxels");
  }
  if (parameters.faceTipBands && !parameters.globalSs_mm)
  {
    throw std::invalid_argument("the face tips' answers need the global SS field (one call per "
                                "run: the coder calls them only in the global-field mode)");
  }
  if (parameters.hasSeed)
  {
    const auto& s = parameters.seedIndex;
    for (int a = 0; a < 3; ++a)
    {
      if (s[a] < 0 || s[a] >= d[a])
      {
        throw std::invalid_argument("seed outside the volume");
      }
    }
    if (!mask.test(static_cast<std::uint64_t>(s[0] + d[0] * (s[1] + d[1] * s[2]))))
    {
      throw std::invalid_argument("seed outside any vessel");
    }
  }
}

RawSkeleton VoxelCoder::run(const std::function<bool(double)>& progress)
{
  Impl impl(this->Mask, this->Parameters, progress);
  return impl.run();
}

} // namespace vtouch
