#include "vtouchDistributedBenchPhantom.h"

#include <cstdlib>
#include <vector>

namespace vtouch
{

DistributedBenchPhantom::DistributedBenchPhantom(int argc, char** argv)
{
  this->N = argc > 1 ? std::atoi(argv[1]) : 112;
  this->Margin = argc > 2 ? std::atoi(argv[2]) : 8;
  this->Segments = argc > 3 ? std::atoi(argv[3]) : 60;
  this->Spec.shape = PhantomShape::RawAngiogram;
  this->Spec.dimensions = { this->N, this->N, this->N };
  this->Spec.angiogramSegments = this->Segments;
  this->Spec.clutterCount = 0;
  this->Spec.noiseStdDev = 0.0;
  this->Spec.biasAmplitude = 0.0;
  this->Generator = std::make_unique<PhantomGenerator>(this->Spec);
  if (!this->Generator->ok())
  {
    this->Error = this->Generator->error();
    return;
  }
  if (this->N < 8 || this->Margin < 1)
  {
    this->Error = "N must be 8 or more and the ghost margin 1 voxel or more (got N " +
                  std::to_string(this->N) + ", margin " + std::to_string(this->Margin) + ")";
    return;
  }
  std::vector<float> voxels(static_cast<std::size_t>(this->N) * this->N * this->N);
  this->Generator->fill(voxels.data());
  this->Threshold =
    static_cast<float>(0.5 * (this->Spec.tissueIntensity + this->Spec.peakIntensity));
  this->Whole = SparseVesselMask(this->dims());
  for (std::size_t v = 0; v < voxels.size(); ++v)
  {
    if (voxels[v] >= this->Threshold)
    {
      this->Whole.set(v);
    }
  }
  this->Whole.finalize();
}

} // namespace vtouch
