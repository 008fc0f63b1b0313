#include "vtouchViewModelBuilder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <system_error>
#include <thread>

namespace vtouch
{

void ViewModelBuilder::setCaptureRadius_px(double r)
{
  this->CaptureRadius_px = std::isfinite(r) ? std::clamp(r, 0.0, 64.0) : 12.0;
}

std::shared_ptr<ViewModel> ViewModelBuilder::build(
  const std::shared_ptr<const SceneTopology>& topology,
  const HostCamera& camera,
  std::shared_ptr<ViewModel> recycled)
{
  std::shared_ptr<ViewModel> vm = recycled ? std::move(recycled) : std::make_shared<ViewModel>();
  vm->Topology = topology;
  vm->setCamera(camera);
  vm->Generation = this->NextGeneration++;
  vm->CaptureRadius_px = this->CaptureRadius_px;
  this->rasterize(*vm);
  return vm;
}

void ViewModelBuilder::rasterize(ViewModel& vm)
{
  const int w = vm.Camera.viewportWidth_px;
  const int h = vm.Camera.viewportHeight_px;
  const std::size_t npix = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  vm.MapWidth = w;
  vm.MapHeight = h;
  vm.ContactMap.assign(npix, -1);
  this->Seed.assign(npix, -1);
  this->SeedDepth.assign(npix, std::numeric_limits<float>::infinity());
  this->NearRow.resize(npix);

  // 1. Project every point (one streaming pass over packed float positions) and splat it to its
  //    pixel; the nearest to the viewer wins.
  const Mat4& v = vm.Camera.view_WorldToEye;
  const Mat4& p = vm.Camera.projection_EyeToClip;
  // Combined world -> clip rows (x, y, w) and the eye z row for depth.
  const Mat4 m = multiply(p, v);
  const float cx[4] = { float(m[0]), float(m[4]), float(m[8]), float(m[12]) };
  const float cy[4] = { float(m[1]), float(m[5]), float(m[9]), float(m[13]) };
  const float cw[4] = { float(m[3]), float(m[7]), float(m[11]), float(m[15]) };
  const float ez[4] = { float(v[2]), float(v[6]), float(v[10]), float(v[14]) };
  const float halfW = 0.5f * static_cast<float>(w);
  const float halfH = 0.5f * static_cast<float>(h);
  const float* xs = vm.Topology->positionsX();
  const float* ys = vm.Topology->positionsY();
  const float* zs = vm.Topology->positionsZ();
  const int n = vm.pointCount();
  float* seedDepth = this->SeedDepth.data();
  std::int32_t* seed = this->Seed.data();
  const float wf = static_cast<float>(w);
  const float hf = static_cast<float>(h);
  // Blocks: a branch-free, vectorizable projection into small buffers, then the scatter.
  constexpr int kBlock = 512;
  std::int32_t pixel[kBlock];
  float depthOf[kBlock];
  for (int b0 = 0; b0 < n; b0 += kBlock)
  {
    const int count = std::min(kBlock, n - b0);
    const float* bx = xs + b0;
    const float* by = ys + b0;
    const float* bz = zs + b0;
    for (int i = 0; i < count; ++i)
    {
      const float clipW = cw[0] * bx[i] + cw[1] * by[i] + cw[2] * bz[i] + cw[3];
      const float inv = 1.0f / clipW;
      const float x =
        ((cx[0] * bx[i] + cx[1] * by[i] + cx[2] * bz[i] + cx[3]) * inv + 1.0f) * halfW;
      const float y =
        ((cy[0] * bx[i] + cy[1] * by[i] + cy[2] * bz[i] + cy[3]) * inv + 1.0f) * halfH;
      // Branch-free (vectorizable): NaN and points behind the camera fail these comparisons too;
      // the clamps keep the float -> int conversions defined for any input.
      const int inside = (clipW > 0.0f) & (x >= 0.0f) & (y >= 0.0f) & (x < wf) & (y < hf);
      const float xc = x > 0.0f ? (x < wf - 1.0f ? x : wf - 1.0f) : 0.0f;
      const float yc = y > 0.0f ? (y < hf - 1.0f ? y : hf - 1.0f) : 0.0f;
      const int k = static_cast<int>(yc) * w + static_cast<int>(xc);
      pixel[i] = inside ? k : -1;
      depthOf[i] = -(ez[0] * bx[i] + ez[1] * by[i] + ez[2] * bz[i] + ez[3]);
    }
    for (int i = 0; i < count; ++i)
    {
      const std::int32_t k = pixel[i];
      if (k >= 0 && depthOf[i] < seedDepth[k])
      {
        seedDepth[k] = depthOf[i];
        seed[k] = b0 + i;
      }
    }
  }

  // 2 and 3: the distance transform, split in two halves (columns, then rows) run on this thread
  // and a helper thread: the halves write disjoint parts of the buffers.
  this->EnvSite.resize(2 * static_cast<std::size_t>(w));
  this->EnvStart.resize(2 * static_cast<std::size_t>(w) + 2);
  this->inParallel(
    [&](int part) { this->columnSweep(w, h, part == 0 ? 0 : w / 2, part == 0 ? w / 2 : w); });
  this->inParallel(
    [&](int part) { this->rowEnvelope(vm, part == 0 ? 0 : h / 2, part == 0 ? h / 2 : h, part); });
}

template<typename F>
void ViewModelBuilder::inParallel(F&& job)
{
  if (this->Threads < 2)
  {
    job(0);
    job(1);
    return;
  }
  std::thread helper;
  try
  {
    helper = std::thread([&job] { job(1); });
  }
  catch (const std::system_error&)
  {
    job(0);
    job(1); // no thread available: do both halves here
    return;
  }
  job(0);
  helper.join();
}

void ViewModelBuilder::columnSweep(int w, int h, int x0, int x1)
{
  // Nearest seeded row in each column within R, by a downward then an upward sweep (row-major
  // order keeps memory access contiguous; the selects are branch-free so they vectorize).
  const int r = static_cast<int>(std::floor(this->CaptureRadius_px));
  std::int32_t* nearRow = this->NearRow.data();
  const std::int32_t* seed = this->Seed.data();
  for (int x = x0; x < x1; ++x)
  {
    nearRow[x] = seed[x] >= 0 ? 0 : -1;
  }
  for (int y = 1; y < h; ++y)
  {
    const std::int32_t* seedRow = seed + static_cast<std::size_t>(y) * w;
    std::int32_t* out = nearRow + static_cast<std::size_t>(y) * w;
    const std::int32_t* prev = out - w;
    for (int x = x0; x < x1; ++x)
    {
      const std::int32_t p = prev[x];
      const std::int32_t carried = ((p >= 0) & (y - p <= r)) ? p : -1;
      out[x] = seedRow[x] >= 0 ? y : carried;
    }
  }
  for (int y = h - 2; y >= 0; --y)
  {
    std::int32_t* out = nearRow + static_cast<std::size_t>(y) * w;
    const std::int32_t* below = out + w;
    for (int x = x0; x < x1; ++x)
    {
      const std::int32_t b = below[x];
      const std::int32_t cur = out[x];
      const int take = (b >= 0) & (b - y <= r) & ((cur < 0) | (b - y < y - cur));
      out[x] = take ? b : cur;
    }
  }
}

void ViewModelBuilder::rowEnvelope(ViewModel& vm, int y0, int y1, int part)
{
  // Per row: lower envelope of the parabolas (x - x')^2 + dy(x')^2 over the columns' sites.
  const int w = vm.MapWidth;
  const float r2 = static_cast<float>(this->CaptureRadius_px * this->CaptureRadius_px);
  const std::int32_t* nearRow = this->NearRow.data();
  int* site = this->EnvSite.data() + static_cast<std::size_t>(part) * w;
  float* start = this->EnvStart.data() + static_cast<std::size_t>(part) * (w + 1);
  for (int y = y0; y < y1; ++y)
  {
    const std::int32_t* rowNear = nearRow + static_cast<std::size_t>(y) * w;
    auto f = [&](int x)
    {
      const float dy = static_cast<float>(rowNear[x] - y);
      return dy * dy;
    };
    int k = -1;
    for (int q = 0; q < w; ++q)
    {
      if (rowNear[q] < 0)
      {
        continue;
      }
      const float fq = f(q) + static_cast<float>(q) * q;
      float s = 0.0f;
      while (k >= 0)
      {
        const int p = site[k];
        s = (fq - (f(p) + static_cast<float>(p) * p)) / (2.0f * static_cast<float>(q - p));
        if (s > start[k])
        {
          break;
        }
        --k;
      }
      ++k;
      site[k] = q;
      start[k] = k == 0 ? -std::numeric_limits<float>::infinity() : s;
    }
    if (k < 0)
    {
      continue;
    }
    std::int32_t* out = vm.ContactMap.data() + static_cast<std::size_t>(y) * w;
    int j = 0;
    for (int x = 0; x < w; ++x)
    {
      while (j < k && start[j + 1] <= static_cast<float>(x))
      {
        ++j;
      }
      const int p = site[j];
      const float dx = static_cast<float>(x - p);
      if (dx * dx + f(p) <= r2)
      {
        out[x] = this->Seed[static_cast<std::size_t>(rowNear[p]) * w + p];
      }
    }
  }
}

} // namespace vtouch
