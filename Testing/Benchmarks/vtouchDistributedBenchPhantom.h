// The set-up of the distributed stages' benchmarks (issue 19 item 2): the raw-angiogram
// phantom's vessel tree from their command line, thresholded half way from the tissue to the
// vessels' peak into the whole vessel mask the pieces are cut from. One place for what
// vesseltouch-distributed-seedcode and vesseltouch-distributed-root each carried
// (duplicates --change; branch hdup).
#pragma once

#include "vtouchPhantomGenerator.h"
#include "vtouchSparseVesselMask.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>

namespace vtouch
{

class DistributedBenchPhantom
{
public:
  /// Reads `[N=112] [ghost margin voxels=8] [segments=60]` from the command line and, when
  /// usable, makes the phantom (N^3 voxels, `segments` vessel segments, no clutter, noise or
  /// bias) and its mask.
  DistributedBenchPhantom(int argc, char** argv);

  /// False when the setup is unusable: error() says why.
  bool ok() const { return this->Error.empty(); }
  const std::string& error() const { return this->Error; }

  int n() const { return this->N; }
  int margin() const { return this->Margin; }
  int segments() const { return this->Segments; }
  std::array<std::int64_t, 3> dims() const { return { this->N, this->N, this->N }; }
  const PhantomSpec& spec() const { return this->Spec; }
  const PhantomGenerator& generator() const { return *this->Generator; }
  /// The mask's threshold: half way from the tissue to the vessels' peak (partial volume
  /// included).
  float threshold() const { return this->Threshold; }
  /// The voxels at or above the threshold (whole-volume index).
  const SparseVesselMask& whole() const { return this->Whole; }

private:
  int N = 112;
  int Margin = 8;
  int Segments = 60;
  PhantomSpec Spec;
  std::unique_ptr<PhantomGenerator> Generator;
  float Threshold = 0.0F;
  SparseVesselMask Whole;
  std::string Error;
};

} // namespace vtouch
