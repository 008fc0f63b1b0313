#include "vtouchViewPointerMapping.h"

#include <cmath>

namespace vtouch
{
namespace
{
bool positive(double v)
{
  return std::isfinite(v) && v > 0.0;
}
} // namespace

void ViewPointerMapping::setWidgetSize(double width_px, double height_px, double devicePixelRatio)
{
  if (positive(width_px) && positive(height_px))
  {
    this->Width_px = width_px;
    this->Height_px = height_px;
  }
  if (positive(devicePixelRatio))
  {
    this->Ratio = devicePixelRatio;
  }
}

void ViewPointerMapping::setPixelsPerDeviceMm(double pixelsPerDeviceMm)
{
  if (positive(pixelsPerDeviceMm))
  {
    this->PixelsPerMm = pixelsPerDeviceMm;
  }
}

Vec2 ViewPointerMapping::widgetToViewport_px(const Vec2& widget_px) const
{
  return { widget_px.x * this->Ratio, this->viewportHeight_px() - 1.0 - widget_px.y * this->Ratio };
}

Vec2 ViewPointerMapping::viewportToDevice_mm(const Vec2& viewport_px) const
{
  const Vec2 centre{ 0.5 * this->viewportWidth_px(), 0.5 * this->viewportHeight_px() };
  return (viewport_px - centre) * (1.0 / this->PixelsPerMm);
}

Vec2 ViewPointerMapping::deviceToViewport_px(const Vec2& device_mm) const
{
  const Vec2 centre{ 0.5 * this->viewportWidth_px(), 0.5 * this->viewportHeight_px() };
  return centre + device_mm * this->PixelsPerMm;
}

Vec2 ViewPointerMapping::widgetToDevice_mm(const Vec2& widget_px) const
{
  return this->viewportToDevice_mm(this->widgetToViewport_px(widget_px));
}

} // namespace vtouch
