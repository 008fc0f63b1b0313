// Private to Logic/Skeleton: the state and stages of vtouch::VoxelCoder. The stages are defined
// in one file each: vtouchVoxelCodingCodes.cxx (BS and SS codes, clusters, root choice),
// vtouchVoxelCodingTrace.cxx (back-tracing, centre adjustment, paths, end trimming),
// vtouchVoxelCodingLoops.cxx (loop closing) and vtouchVoxelCoding.cxx (set-up and run).
#pragma once

#include "vtouchBucketQueue.h"
#include "vtouchVoxelCoding.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <thread>
#include <unordered_map>

namespace vtouch
{

struct VoxelCoder::Impl
{
  using P3 = std::array<double, 3>;
  static constexpr std::uint8_t kDone = 1;      // finalized in the current propagation
  static constexpr std::uint8_t kComponent = 2; // belongs to a component already handled
  static constexpr std::uint8_t kRegion = 4;    // scratch flag (extremity region)
  static constexpr std::uint8_t kSkeleton = 8;  // on a traced path
  static constexpr std::uint32_t kLabelled = 0x80000000U;
  static constexpr float kInf = std::numeric_limits<float>::infinity();
  static constexpr int kHalf = 13; // the first 13 offsets precede the voxel: each pair visited once

  struct Cluster
  {
    std::uint32_t band = 0;
    std::uint32_t count = 0;
    double sum[3] = { 0.0, 0.0, 0.0 };
    float maxBs = 0.0F;
    std::vector<std::uint32_t> lower;  // adjacent clusters of lower bands
    std::vector<std::uint32_t> higher; // adjacent clusters of higher bands
    int path = -1;                     // path and point that represent this cluster
    int point = -1;
    std::uint32_t bestVoxel = 0; // voxel of largest BS code
    bool onBorder = false;       // touches the volume border (an end cut by the field of view)
    std::array<double, 3> centroid() const
    {
      return { sum[0] / count, sum[1] / count, sum[2] / count };
    }
  };

  static void addUnique(std::vector<std::uint32_t>& v, std::uint32_t c)
  {
    if (std::find(v.begin(), v.end(), c) == v.end())
    {
      v.push_back(c);
    }
  }

  static double distance2(const std::array<double, 3>& a, const std::array<double, 3>& b)
  {
    return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
           (a[2] - b[2]) * (a[2] - b[2]);
  }

  static double distance(const std::array<double, 3>& a, const std::array<double, 3>& b)
  {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                     (a[2] - b[2]) * (a[2] - b[2]));
  }

  const SparseVesselMask& mask;
  VoxelCodingParameters par;
  const std::function<bool(double)>& progress;
  std::int64_t nx, ny, nz;
  std::uint32_t nx32, ny32;
  double inverseNx, inverseNy;
  double sp[3];
  double minSpacing, maxSpacing, bandWidth;
  float inverseBandWidth;
  int off[26][3];
  std::int64_t offLin[26];
  double offLen[26];
  float offLenF[26];
  double offMm[26][3];       // offsets in mm
  std::int64_t rowOffset[9]; // linear offset of the neighbour rows (dj, dk), di = 0

  std::vector<float> bs;          // boundary-seeded code: distance to the nearest background, mm
  std::vector<float> ss;          // single-seed code: geodesic distance from the root, mm
  std::vector<std::uint32_t> aux; // BS sources, then union-find / cluster labels
  std::vector<std::uint8_t> flags;
  std::vector<std::uint32_t> order; // one component in SS order
  std::vector<std::uint32_t> scratch;
  std::vector<Cluster> clusters;
  std::unordered_map<std::uint32_t, std::pair<int, int>> skeletonVoxel; // lin -> (path, point)
  RawSkeleton out;
  std::vector<std::array<bool, 2>> closedEnd; // per path: head/tail end is a rounded vessel end
  std::uint64_t work = 0;
  std::uint64_t totalWork = 1;
  std::size_t peakQueue = 0;

  /// Adds the wall time of its scope to out.stageSeconds[name].
  struct StageTimer
  {
    Impl& impl;
    const char* name;
    std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
    ~StageTimer()
    {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      for (auto& e : impl.out.stageSeconds)
      {
        if (e.first == name)
        {
          e.second += s;
          return;
        }
      }
      impl.out.stageSeconds.emplace_back(name, s);
    }
  };

  Impl(const SparseVesselMask& m,
    const VoxelCodingParameters& p,
    const std::function<bool(double)>& cb);

  /// a / d for d >= 1, with `inverse` = 1.0 / d (exact: the estimate is off by at most one).
  static std::uint32_t divide(std::uint32_t a, std::uint32_t d, double inverse)
  {
    auto q = static_cast<std::uint32_t>(static_cast<double>(a) * inverse);
    const std::uint64_t product = static_cast<std::uint64_t>(q) * d;
    if (product > a)
    {
      --q;
    }
    else if (product + d <= a)
    {
      ++q;
    }
    return q;
  }

  void coords(std::uint64_t lin, std::int64_t c[3]) const
  {
    // Linear indices fit 32 bits (checked in the constructor): 32-bit division is much cheaper.
    // A multiplication by the reciprocal, corrected by one, is cheaper than a division.
    const auto l = static_cast<std::uint32_t>(lin);
    const std::uint32_t r = divide(l, nx32, inverseNx);
    c[0] = static_cast<std::int64_t>(l - r * nx32);
    const std::uint32_t k = divide(r, ny32, inverseNy);
    c[1] = static_cast<std::int64_t>(r - k * ny32);
    c[2] = static_cast<std::int64_t>(k);
  }

  /// Calls f(neighbourLin, neighbourIndex, neighbourRank) for every 26-neighbour that is vessel
  /// (`count` = kHalf: only the 13 that precede it in scan order). This is the inner loop of every
  /// pass: away from the volume border a row of three neighbours needs one 3-bit mask window and
  /// one rank computation (their ranks are consecutive), instead of three tests and three ranks.
  template<typename F>
  void forNeighbours(std::uint64_t lin, F&& f, int count = 26) const
  {
    std::int64_t c[3];
    coords(lin, c);
    const bool interior =
      c[0] > 0 && c[0] < nx - 1 && c[1] > 0 && c[1] < ny - 1 && c[2] > 0 && c[2] < nz - 1;
    if (!interior)
    {
      for (int n = 0; n < count; ++n)
      {
        const std::int64_t i = c[0] + off[n][0], j = c[1] + off[n][1], k = c[2] + off[n][2];
        if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz)
        {
          continue;
        }
        const auto u = static_cast<std::uint64_t>(static_cast<std::int64_t>(lin) + offLin[n]);
        if (mask.test(u))
        {
          f(u, n, mask.rank(u));
        }
      }
      return;
    }
    // Rows q = 0..8 of three neighbours (dk, dj fixed; di = -1, 0, 1); row 4 holds the voxel.
    const int rows = count == kHalf ? 5 : 9;
    for (int q = 0; q < rows; ++q)
    {
      const std::uint64_t first =
        static_cast<std::uint64_t>(static_cast<std::int64_t>(lin) + rowOffset[q] - 1);
      const unsigned bits = mask.window3(first);
      // The voxel itself is not its neighbour, but it counts in the ranks after it.
      const unsigned wanted = q != 4 ? bits : bits & (count == kHalf ? 1U : 5U);
      if (!wanted)
      {
        continue;
      }
      std::uint32_t rank = mask.rankBefore(first);
      for (int di = 0; di < 3; ++di)
      {
        if ((wanted >> di) & 1U)
        {
          const int idx = 3 * q + di;
          f(first + static_cast<std::uint64_t>(di), idx > 13 ? idx - 1 : idx, rank);
        }
        rank += (bits >> di) & 1U;
      }
    }
  }

  void tick(std::uint64_t amount = 1)
  {
    work += amount;
    if ((work & 0xFFFF) < amount)
    {
      checkpoint();
    }
  }

  /// Reports the progress so far; throws VoxelCodingAborted when the caller asks to stop. Loops
  /// whose iterations are not counted as work (stale queue entries) call it every 2^16
  /// iterations.
  void checkpoint()
  {
    if (progress &&
        !progress(std::min(1.0, static_cast<double>(work) / static_cast<double>(totalWork))))
    {
      boundaryStop = true; // the BS thread stops too, before the unwinding joins it
      throw VoxelCodingAborted();
    }
  }

  // ---- boundary-seeded code: exact Euclidean distance (mm) to the nearest background voxel
  // centre, by a separable transform over the vessel runs (vtouchVoxelCodingBoundary.cxx).
  std::vector<double> siteX, siteF, envelopeFrom; // scratch of one run's lower envelope
  std::vector<std::size_t> envelopeSite;
  /// Squared distance along x to the row's background (runs of consecutive ranks).
  void boundaryRowPass();
  /// Squared distance after the pass along `axis` (1 = y, 2 = z), from the previous passes.
  void boundaryLinePass(int axis);
  std::vector<std::uint32_t> planeRank, planePosition; // one plane's voxels in column order
  /// One vessel run of a column: `count` ranks at positions first.. along an axis of `len` voxels.
  void envelopeOfRun(const std::uint32_t* ranks,
    std::uint32_t first,
    std::uint32_t count,
    std::int64_t len,
    double spacing);
  void computeBoundaryCode();

  // The BS code (bs and its own scratch) and the first propagations (ss, flags, order) touch
  // different arrays: the BS code runs on a second thread until the clusters need it. That
  // thread never reports progress (the callback is called from the caller's thread only) and
  // is joined before anything reads bs or aux, and by the destructor when a stage throws.
  std::thread boundaryThread;
  std::exception_ptr boundaryError;
  double boundarySeconds = 0.0;
  bool boundaryQuiet = false; // no tick() from the BS passes (second thread)
  /// Set by the caller's thread when the run stops (cancelled, or an error): the BS thread checks
  /// it at every plane and row chunk and gives up (Cancelled into boundaryError).
  std::atomic<bool> boundaryStop{ false };
  /// On the BS thread: throws Cancelled when boundaryStop is set.
  void boundaryCheckpoint() const
  {
    if (boundaryQuiet && boundaryStop.load(std::memory_order_relaxed))
    {
      throw Cancelled();
    }
  }
  std::size_t boundaryScratchBytes = 0; // the BS code's largest scratch array
  void startBoundaryCode();
  void boundaryCodeOnThread();
  /// Joins the BS thread (if any), rethrows its error and accounts its time and progress.
  void awaitBoundaryCode();
  ~Impl();

  // ---- single-seed code: exact geodesic (26-neighbour, metric edge lengths) Dijkstra.
  void propagate(const std::vector<std::uint32_t>& sources);

  void resetPropagation();

  /// The automatic root: the cluster of voxels farthest from an arbitrary start (double
  /// propagation), reduced to the voxel at its centroid (the end cap is centred on the axis).
  std::vector<std::uint32_t> extremityRegion();

  /// The exploratory half of the double propagation on the 2x2x2 block mask (about a sixth of
  /// the voxels of a thick vessel): the far end of `lin`'s component from `lin`'s block, as the
  /// vessel voxel nearest that end cap's centre. kNoVoxel for small masks (the exact search is
  /// as cheap) or when no vessel voxel lies near it. Any extremity gives a valid SS code, and the
  /// tree's root is moved to its thickest end afterwards anyway.
  std::uint32_t coarseExtremity(std::uint32_t lin);
  static constexpr std::uint32_t kNoVoxel = 0xFFFFFFFFU;
  std::function<bool(double)> noProgress; // the explorer reports no progress of its own
  std::unique_ptr<SparseVesselMask> coarseMask;
  std::unique_ptr<Impl> explorer;

  std::uint32_t band(std::uint32_t r) const
  {
    return static_cast<std::uint32_t>(ss[r] * inverseBandWidth);
  }

  std::uint32_t find(std::uint32_t r)
  {
    while (aux[r] != r)
    {
      aux[r] = aux[aux[r]];
      r = aux[r];
    }
    return r;
  }

  // ---- clusters: connected parts of equal SS band, and the cluster graph.
  void buildClusters();

  std::uint32_t clusterOf(std::uint32_t lin) const { return aux[mask.rank(lin)] & ~kLabelled; }

  double radiusAt(std::uint32_t lin) const
  {
    // BS is the distance to the nearest background voxel centre. The wall lies about half a voxel
    // before that centre, and the traced voxel sits up to half a voxel off the true axis (the
    // adjusted centre does not): the two biases cancel on average (calibrated on phantoms).
    return std::max(static_cast<double>(bs[mask.rank(lin)]), 0.5 * minSpacing);
  }

  std::array<std::int64_t, 3> voxelArray(std::uint32_t lin) const
  {
    std::int64_t c[3];
    coords(lin, c);
    return { c[0], c[1], c[2] };
  }

  std::array<double, 3> centerOf(std::uint32_t lin) const
  {
    std::int64_t c[3];
    coords(lin, c);
    return { c[0] * sp[0], c[1] * sp[1], c[2] * sp[2] };
  }

  /// Center adjustment: the centroid of the voxels of `lin`'s cluster (a slab of the SS code across
  /// the vessel) that lie within about one radius of it. Restricting the slab to the neighbourhood
  /// keeps the point in its own branch where a slab still spans two branches near a bifurcation.
  std::array<double, 3> adjustedCenter(std::uint32_t lin);
  /// The voxel of largest BS in `lin`'s slab (cluster) within the distance the ridge can be from
  /// it: where a trace that was held off the ridge should have been.
  std::uint32_t ridgeVoxelNear(std::uint32_t lin, std::uint32_t cluster);
  std::vector<std::uint32_t> ridgeScratch;

  struct Trace
  {
    std::vector<std::uint32_t> voxels; // from the start down, excluding the attachment point
    int path = -1;                     // attachment (path, point); -1 = free end (the root)
    int point = -1;
    double length = 0.0;
  };

  /// A skeleton voxel at or next to `lin`, as (path, point), or path -1.
  std::pair<int, int> touchedSkeleton(std::uint32_t lin) const;

  /// Center-adjusted back-tracing: from `start`, step to the 26-neighbour of lower SS code with the
  /// largest BS code (the ridge of the distance map, i.e. the vessel centre) until the trace
  /// touches the skeleton already traced, or reaches the root. Touches are ignored while the SS
  /// code is above `ignoreAbove` (a loop closure starts next to the skeleton). If the trace runs
  /// alongside the skeleton through more than `patience` clusters already on it without touching,
  /// it attaches to the current cluster's point.
  Trace descend(std::uint32_t start, float ignoreAbove, std::size_t patience) const;

  void markPoint(int path, int point, std::uint32_t lin);

  /// Makes a path of `t` reversed: head at the attachment (or the root), tail at the start voxel,
  /// or, with `tailPath` >= 0, at point (tailPath, tailPoint) of the skeleton (a loop closure).
  void emitPath(const Trace& t, bool startOnBorder, int tailPath, int tailPoint);

  /// A vessel that ends inside the volume ends in a cap; its centerline ends at the cap's centre,
  /// one radius back from the apex, where the medial axis would go on to the apex
  /// (vtouchVoxelCodingEnds.cxx). Points that other paths attach to are kept.
  void trimClosedEnds(std::size_t firstPath);
  struct EndCap
  {
    std::size_t trim = 0; ///< points to drop at the end
    /// Where the new end point goes (on the axis, at the cap's centre), when the cap was measured.
    std::optional<std::array<double, 3>> centre_mm;
  };
  /// The cap at one free end of `path` (its tail when `fromTail`); see trimClosedEnds.
  EndCap measureEndCap(const RawSkeletonPath& path,
    bool fromTail,
    const std::vector<char>& pinned) const;
  /// The vessel mask (1 vessel, 0 background) interpolated trilinearly at `p_mm` (scaled index
  /// frame); -1 where the interpolation needs a voxel outside the volume.
  double maskValueAt(const std::array<double, 3>& p_mm) const;
  /// Distance (mm) from `from` along the unit direction `dir` to the wall, where maskValueAt()
  /// falls below one half (steps of a quarter of the smallest voxel side, interpolated between
  /// them); < 0 when `from` is not inside, or the march leaves the volume or goes beyond
  /// `limit_mm` first.
  double distanceToWall(const std::array<double, 3>& from,
    const std::array<double, 3>& dir,
    double limit_mm) const;

  /// A branch trace that reaches the skeleton across a thick junction touches it early, on the
  /// crotch side: the corner is cut. Extend the branch's own axis (its centres between `far` and
  /// `near` radii of the touch) to the parent path and attach there, dropping the trace voxels
  /// within `near` radii of the touch (appendSkeletonPoint bridges the gap with a straight voxel
  /// line).
  void joinAlongBranchAxis(Trace& t, double junctionRadius);

  /// The mirror of joinAlongBranchAxis for a path that goes on through a bifurcation: beyond the
  /// junction (toward its tail, the other child) its trace runs on the ridge of the merged lumen,
  /// inside the child's own axis. Its centres within one junction radius of the junction point are
  /// put on the straight line from the junction to the first centre beyond that radius. Junctions
  /// already `recentred` (a vessel running through: vtouchJunctionRecentring.h) are left alone.
  void straightenThroughPaths(std::size_t firstPath, const std::vector<bool>& recentred);

  void traceComponent();

  /// Where a branch trace starts: the voxel at the tip cluster's centroid when it is vessel (the
  /// last band at a flat or rounded end is a ring or cap centred on the axis), else the cluster's
  /// most central voxel.
  std::uint32_t tipStart(const Cluster& c) const;

  /// The vessel radius at a point of a path (vtouch::nearbyRadius): near an end cap or a junction
  /// the radius at the point itself underestimates the vessel a spur grows from.
  double nearbyRadius(int path, int point) const;

  /// Where a trace of `length` reaches a path at its free end (the root, usually), the vessel it
  /// would leave from is the path's own within `length` of that end: its largest radius there.
  /// A thin strand of noise voxels on an end cap can become the root; the other strands that
  /// reach the root are spurs of the vessel, not branches of the strand. 0 elsewhere.
  double endCapRadius(int path, int point, double length) const;

  /// Distance from a point to the nearest skeleton point (brute force: used for a few loop
  /// candidates only).
  double distanceToSkeleton(const std::array<double, 3>& q) const;

  std::size_t patienceFor(const Cluster& c) const
  {
    return static_cast<std::size_t>(
             std::ceil(4.0 * std::max(1.0, static_cast<double>(c.maxBs)) / bandWidth)) +
           3;
  }

  /// Where two fronts of the SS propagation meet, a cluster touches two or more lower clusters. A
  /// lower one not yet on the skeleton may be the other front: trace down from it (B) and, if the
  /// cluster itself is not on the skeleton, from the cluster too (A), and join the two traces into
  /// one path attached at both ends: a loop. A trace B that meets the skeleton as soon as touches
  /// count is one front split by noise, not a loop.
  void closeLoops();

  /// Where the two fronts of a ring met, a cluster touches the skeleton on both sides; when both
  /// sides were traced already (each from its own tip, e.g. strands of noise on the wall where the
  /// fronts met), closeLoops() finds no untraced side, and the ring stays open. A cluster whose
  /// skeleton neighbours are a step apart in the vessel but far apart along the skeleton closes
  /// the ring with a short path between them.
  void closeTracedLoops(std::size_t firstPath);

  /// Where the fronts of a ring met amid noise, the meeting zone can hold several SS maxima: each
  /// front is traced from a tip of its own (often a strand of noise on the wall), short of the
  /// other front, and no cluster touches both (closeTracedLoops() finds nothing). A free end's
  /// stem (where the vessel is, not the strand) that faces a point of the skeleton across a short
  /// gap of vessel (within four radii, within 60 degrees of its outward direction, the straight
  /// segment inside the mask) that the skeleton reaches only the long way round is joined to it
  /// by a short path, like a trace that touches the skeleton (pruneStubEnds() then cuts the
  /// strand beyond the stem).
  void joinFacingEnds(std::size_t firstPath);
  /// The vessel voxels of the cheapest way from `from` to `to` (both excluded, in that order)
  /// along the ridge of the BS code, searched within half their distance plus two `radius` of
  /// their midpoint; empty when there is none.
  std::vector<std::uint32_t> medialBridge(std::uint32_t from,
    std::uint32_t to,
    double radius) const;

  /// Adds junction `j` to `links` in both directions: (path << 32 | point) of the child's end
  /// -> the parent's place, and back (the graph skeletonDistance() walks).
  void linkJunction(const RawJunction& j,
    std::unordered_multimap<std::uint64_t, std::pair<int, int>>& links) const;

  /// Length of the shortest way along the skeleton between two (path, point) places, with the
  /// junctions as `links` ((path << 32 | point) -> place, both directions); infinity when it is
  /// longer than `cutoff` (the search stops there: its cost follows the cutoff, not the skeleton).
  double skeletonDistance(std::pair<int, int> from,
    std::pair<int, int> to,
    double cutoff,
    const std::unordered_multimap<std::uint64_t, std::pair<int, int>>& links) const;

  /// A free path end that goes on less than a spur's length (MinimumBranchLength local radii)
  /// beyond the outermost point another path attaches to is a spur of its own: cut at that point.
  /// Where the second front of a ring is attached next to the first trace's start, the start's
  /// last voxels would otherwise stick out as an end point of a vessel that has none.
  void pruneStubEnds(std::size_t firstPath);

  /// Any extremity gives a valid SS code, but back-tracing toward a thin end cuts the corners of
  /// the bifurcations on the way (the geodesic hugs the inner wall of a sharp turn). Rooting the
  /// code at the thickest extremity (the inflow trunk of a vascular tree) makes every trace enter
  /// the trunk at an obtuse angle. Costs one more propagation.
  void rootAtThickestEnd();

  RawSkeleton run();
};

} // namespace vtouch
