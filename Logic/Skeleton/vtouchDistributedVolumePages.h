// The whole volume's intensities on the first rank, as pages fetched from their owners (issue 19
// item 2, the raw modes' refinement over the whole stitched paths, h19r). The raw path's
// after-coding stages (RawSkeletonRefinement) read the volume only through SectionForeground and
// SectionIntensity, by the whole volume's linear index; on a parallel pvserver no rank holds the
// whole volume, so the first rank answers those reads from pages of it:
//  - a page is a cube of kPageEdge_voxels voxels of the whole volume's index (those past the
//    volume's end cut off); pages are numbered x fastest;
//  - each voxel of a page is answered by exactly one rank, its owner (PieceLayout::owned: the
//    executive's split, not the grown piece), with its intensity exactly (floats for the values a
//    float holds exactly, which every 8/16-bit integer and float value is; doubles otherwise);
//  - only the first rank holds pages: the owners' parts are gathered to it, never all-gathered.
// The reads run on the first rank with no thread. A read of a page not held records the page and
// throws (a private exception); run() catches it, fetches the missing pages in one collective
// round and runs the reader again (from scratch: the reader must start from an untouched copy),
// until a run completes. Every rank loops in lock step: each round the first rank broadcasts
// either the pages it wants or the end, and every rank makes the same collective calls whatever
// fails where (a reader's error, an owner that cannot read its voxels or holds no piece).
#pragma once

#include "vtouchPieceLayout.h"
#include "vtouchRankCollectives.h"
#include "vtouchSectionSampler.h"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vtouch
{

class DistributedVolumePages
{
public:
  /// The pages' edge (voxels). Project rule: the refinement reads around the paths, at most
  /// 4.5 r + 6 voxels from a point (the prefetch bound, DistributedRawRefinement), so a page
  /// should be of the order of that reach: 16 voxels (4096 voxels, 16 KiB as floats) keeps what
  /// the first rank fetches near the vessels (a page of 32 would hold 8 times the voxels for a
  /// path grazing it) while the parts' headers (3 words each) stay under 0.2 % of the payload
  /// and a 1024^3 volume has 2^18 pages (one 64-byte slot each on the first rank).
  static constexpr std::int64_t kPageEdge_voxels = 16;

  /// An owner's intensity of a voxel it owns (whole-volume index); empty: the rank holds no piece.
  using OwnedIntensity = std::function<double(const std::array<std::int64_t, 3>& voxel_Whole)>;

  /// What the rounds did.
  struct Outcome
  {
    bool completed = false;         ///< a run of the reader completed (first rank)
    std::string message;            ///< why not ("" when completed or nothing was to read)
    int rounds = 0;                 ///< fetching rounds (the final "end" broadcast not counted)
    int runs = 0;                   ///< runs of the reader (first rank)
    std::int64_t pagesFetched = 0;  ///< pages held at the end (first rank)
    std::int64_t bytesGathered = 0; ///< payload gathered to the first rank, all rounds
  };

  /// `layout`: the ranks' pieces (the same on every rank); `mine`: this rank's owned voxels'
  /// intensities (empty when it holds no piece: the first rank then fails a run that needs
  /// them, every rank alike).
  DistributedVolumePages(RankCollectives& collectives,
    const PieceLayout& layout,
    OwnedIntensity mine);

  /// The page of whole-volume voxel `v` (each index inside the volume).
  std::int64_t pageOf(const std::array<std::int64_t, 3>& v) const;
  /// The pages, numbered x fastest, per axis.
  const std::array<std::int64_t, 3>& pagesPerAxis() const { return this->PerAxis; }
  bool holds(std::int64_t page) const;

  /// First rank: the volume in [lower, upper] (inIntensityRange) and its intensities over the
  /// whole volume's index, read from the pages (valid while this object lives; a read of a page
  /// not held throws the private miss: only a reader under run() may read).
  SectionForeground inRange(double lower, double upper) const;
  SectionIntensity intensity() const;

  /// Collective: every rank calls it once. On the first rank `prefetch` (pages, any order,
  /// duplicates allowed) is fetched in one round, then `reader` runs (it must start from its
  /// own untouched input each time), and after a miss the missing page and the pages around it
  /// are fetched and `reader` runs again, until it completes or throws something else (its
  /// message is the outcome's). The other ranks' `prefetch` and `reader` are ignored; an empty
  /// `reader` on the first rank ends the rounds at once (nothing to read).
  Outcome run(const std::vector<std::int64_t>& prefetch, const std::function<void()>& reader);

private:
  struct Page
  {
    std::vector<float> floats;   ///< the page's voxels, x fastest (when every part was floats)
    std::vector<double> doubles; ///< the same when a part was not (a page is one or the other)
    std::int64_t filled = 0;     ///< voxels answered
    bool complete = false;       ///< every voxel of the page answered
  };
  /// A page's voxels (whole index, inclusive).
  VoxelBox pageBox(std::int64_t page) const;
  double value(std::uint64_t lin) const;
  /// This rank's parts of `pages` (owner side): per part the page, its encoding, its words.
  std::vector<std::int64_t> parts(const std::vector<std::int64_t>& pages) const;
  /// First rank: stores rank `r`'s parts; "" or why they are unusable.
  std::string store(int r, const std::vector<std::int64_t>& words);
  /// First rank: the requested pages that are not complete, as a message ("" when all are).
  std::string incomplete(const std::vector<std::int64_t>& pages) const;

  RankCollectives& Collectives;
  PieceLayout Layout;
  OwnedIntensity Mine;
  std::array<std::int64_t, 3> PerAxis{ 0, 0, 0 };
  std::vector<Page> Pages; ///< first rank: one slot per page (64 bytes; empty until fetched)
  mutable std::vector<std::int64_t> Missed; ///< the reader's misses since its run started
};

} // namespace vtouch
