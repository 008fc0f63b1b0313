// Mouse position in a render view -> the pointer device's millimetres, the frame the haptic
// session's POINTER device expects (vtkVesselTouchHapticSession::SetPointerPosition).
//
// The session moves its cursor by hand motion: cursor_px += delta(hand mm) x PixelsPerDeviceMm x
// zoom, starting at the viewport centre when the device opens (the PointerDevice then follows the
// pointer from wherever it is). So the mapping is centred on the viewport and scaled by
// 1 / PixelsPerDeviceMm: at zoom 1 and pseudo-haptic gain 1 the session's cursor moves one
// viewport pixel per mouse pixel, and the haptic zoom r makes it move r pixels. The device frame
// has x to the right and y up, like the viewport (VTK display coordinates, bottom-left origin).
#pragma once

#include "vtouchVector.h"

namespace vtouch
{

class ViewPointerMapping
{
public:
  /// Widget size in logical (Qt) pixels and the number of render-window pixels per logical pixel
  /// (QWidget::devicePixelRatioF). Non-positive values are ignored.
  void setWidgetSize(double width_px, double height_px, double devicePixelRatio = 1.0);
  /// Viewport pixels per device millimetre at zoom 1 (the session's PixelsPerDeviceMm, default 4).
  void setPixelsPerDeviceMm(double pixelsPerDeviceMm);

  double viewportWidth_px() const { return this->Width_px * this->Ratio; }
  double viewportHeight_px() const { return this->Height_px * this->Ratio; }
  double pixelsPerDeviceMm() const { return this->PixelsPerMm; }

  /// A widget position (logical px, origin top-left, y down) -> viewport px (render-window
  /// pixels, origin bottom-left, y up), as vtkRenderWindowInteractor converts Qt events.
  Vec2 widgetToViewport_px(const Vec2& widget_px) const;
  /// Viewport px -> device mm (origin at the viewport centre).
  Vec2 viewportToDevice_mm(const Vec2& viewport_px) const;
  /// Device mm -> viewport px (inverse of viewportToDevice_mm).
  Vec2 deviceToViewport_px(const Vec2& device_mm) const;
  /// widgetToViewport_px then viewportToDevice_mm.
  Vec2 widgetToDevice_mm(const Vec2& widget_px) const;

private:
  double Width_px = 800.0;
  double Height_px = 600.0;
  double Ratio = 1.0;
  double PixelsPerMm = 4.0;
};

} // namespace vtouch
