// Builds ViewModel snapshots from a SceneTopology and a HostCamera (GUI/worker thread only).
#pragma once

#include "vtouchViewModel.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace vtouch
{

/// Not thread-safe: one builder per producing thread. Keeps scratch buffers between builds so a
/// rebuild on every camera change does not reallocate (a 1 M-point build stays within a frame).
class ViewModelBuilder
{
public:
  /// Capture radius of the contact map in pixels: the cursor makes contact with a vessel when it
  /// is within this distance of a centerline pixel. Default 12 px; range [0, 64].
  void setCaptureRadius_px(double r);
  double captureRadius_px() const { return this->CaptureRadius_px; }
  /// Threads used by the distance transform: 1 or 2 (a helper thread per build). Default 2.
  void setThreads(int threads) { this->Threads = threads < 2 ? 1 : 2; }

  /// Builds a snapshot. `recycled` (may be null) is a snapshot nobody else references any more
  /// (see ViewModelExchange::takeRecyclable); its buffers are reused instead of allocating.
  /// The contact map: every centerline point is splatted to its pixel with a depth test (nearest to
  /// the viewer wins where vessels overlap), then each pixel takes the screen-nearest splatted
  /// pixel within the capture radius by an exact Euclidean distance transform
  /// (Felzenszwalb-Huttenlocher), O(width x height) whatever the radius.
  std::shared_ptr<ViewModel> build(const std::shared_ptr<const SceneTopology>& topology,
    const HostCamera& camera,
    std::shared_ptr<ViewModel> recycled = nullptr);

private:
  void rasterize(ViewModel& vm);
  void columnSweep(int w, int h, int x0, int x1);
  void rowEnvelope(ViewModel& vm, int y0, int y1, int part);
  template<typename F>
  void inParallel(F&& job);

  double CaptureRadius_px = 12.0;
  int Threads = 2;
  std::uint64_t NextGeneration = 1;
  std::vector<float> SeedDepth;
  std::vector<std::int32_t> Seed;
  std::vector<std::int32_t> NearRow; // nearest seeded row in the column, -1 when farther than R
  std::vector<int> EnvSite;
  std::vector<float> EnvStart;
};

} // namespace vtouch
