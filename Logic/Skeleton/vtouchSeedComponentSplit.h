// The distributed raw seeded mode on the seed's rank (issue 19 item 2): its piece of the seed's
// network splits into the seed's 26-connected component there (coded from the seed, as the
// single run codes the whole network) and the parts that reach the seed only outside the piece
// (coded from roots of their own); their skeletons are then appended into the piece's one.
#pragma once

#include "vtouchQSkeleton.h"
#include "vtouchSparseVesselMask.h"
#include "vtouchTubeNeckCutter.h"

#include <array>
#include <cstdint>
#include <utility>

namespace vtouch
{

class SeedComponentSplit
{
public:
  struct Parts
  {
    SparseVesselMask seedComponent; ///< finalized
    SparseVesselMask rest;          ///< finalized; empty when the component is the whole mask
  };

  /// `mask` (finalized) split at `seed` (an index of its grid; a seed outside the mask leaves
  /// an empty component and the whole mask as the rest).
  static Parts split(const SparseVesselMask& mask, const std::array<std::int64_t, 3>& seed)
  {
    Parts p{ TubeNeckCutter::component(mask, seed), SparseVesselMask(mask.dims()) };
    mask.forEach(
      [&](std::uint64_t lin)
      {
        if (!p.seedComponent.test(lin))
        {
          p.rest.set(lin);
        }
      });
    p.rest.finalize();
    return p;
  }

  /// `b`'s paths and junctions after `a`'s, their indices shifted.
  static QSkeleton appended(const QSkeleton& a, const QSkeleton& b)
  {
    QSkeleton out = a;
    const int paths = static_cast<int>(a.paths.size());
    const int junctions = static_cast<int>(a.junctions.size());
    for (SkeletonPath p : b.paths)
    {
      p.id += paths;
      p.head.junction += p.head.junction >= 0 ? junctions : 0;
      p.tail.junction += p.tail.junction >= 0 ? junctions : 0;
      out.paths.push_back(std::move(p));
    }
    for (Junction j : b.junctions)
    {
      j.childPath += paths;
      j.parentPath += paths;
      out.junctions.push_back(j);
    }
    return out;
  }
};

} // namespace vtouch
