#include "vtouchLateralGradientForceLaw.h"

#include <algorithm>
#include <cmath>

namespace vtouch
{

Vec2 LateralGradientForceLaw::compute(const ForceInput& in, ForceRequest&) noexcept
{
  const ViewModel& vm = *in.view;
  if (!in.cursor_px.isFinite())
  {
    return {};
  }
  const double h = std::max(1.0, this->probe_px);
  const int cx = static_cast<int>(std::floor(in.cursor_px.x));
  const int cy = static_cast<int>(std::floor(in.cursor_px.y));
  const int hp = static_cast<int>(std::lround(h));
  const int gxp = vm.contactAt(cx + hp, cy);
  const int gxm = vm.contactAt(cx - hp, cy);
  const int gyp = vm.contactAt(cx, cy + hp);
  const int gym = vm.contactAt(cx, cy - hp);
  const int centre = vm.contactAt(cx, cy);
  const int ref =
    centre >= 0 ? centre : (gxp >= 0 ? gxp : (gxm >= 0 ? gxm : (gyp >= 0 ? gyp : gym)));
  if (ref < 0)
  {
    return {};
  }
  const double mmPerPx = vm.mmPerPixel(ref);
  auto diff = [&](int plus, int minus)
  {
    if (plus < 0 || minus < 0)
    {
      return 0.0;
    }
    return (vm.depth_mm(plus) - vm.depth_mm(minus)) / (2.0 * hp * mmPerPx);
  };
  const Vec2 gradZ{ diff(gxp, gxm), diff(gyp, gym) };
  return gradZ * in.zoneGain_N;
}

} // namespace vtouch
