// Mouse (widget pixels) -> pointer-device millimetres (Logic/View/vtouchViewPointerMapping).
#include "vtouchViewPointerMapping.h"

#include <gtest/gtest.h>

TEST(ViewPointerMapping, CentreOfTheViewIsTheDeviceOrigin)
{
  vtouch::ViewPointerMapping mapping;
  mapping.setWidgetSize(800.0, 600.0, 1.0);
  mapping.setPixelsPerDeviceMm(4.0);
  // Widget pixel (400, 299) is viewport pixel (400, 300): the centre.
  const vtouch::Vec2 mm = mapping.widgetToDevice_mm({ 400.0, 299.0 });
  EXPECT_DOUBLE_EQ(mm.x, 0.0);
  EXPECT_DOUBLE_EQ(mm.y, 0.0);
}

TEST(ViewPointerMapping, YIsFlippedAndScaledByPixelsPerMm)
{
  vtouch::ViewPointerMapping mapping;
  mapping.setWidgetSize(800.0, 600.0, 1.0);
  mapping.setPixelsPerDeviceMm(4.0);
  const vtouch::Vec2 topLeft = mapping.widgetToViewport_px({ 0.0, 0.0 });
  EXPECT_DOUBLE_EQ(topLeft.x, 0.0);
  EXPECT_DOUBLE_EQ(topLeft.y, 599.0);
  // 40 px right and 40 px up on screen: +10 mm, +10 mm (device y up).
  const vtouch::Vec2 a = mapping.widgetToDevice_mm({ 400.0, 299.0 });
  const vtouch::Vec2 b = mapping.widgetToDevice_mm({ 440.0, 259.0 });
  EXPECT_DOUBLE_EQ(b.x - a.x, 10.0);
  EXPECT_DOUBLE_EQ(b.y - a.y, 10.0);
}

TEST(ViewPointerMapping, DevicePixelRatioScalesToRenderWindowPixels)
{
  vtouch::ViewPointerMapping mapping;
  mapping.setWidgetSize(400.0, 300.0, 2.0);
  EXPECT_DOUBLE_EQ(mapping.viewportWidth_px(), 800.0);
  EXPECT_DOUBLE_EQ(mapping.viewportHeight_px(), 600.0);
  const vtouch::Vec2 v = mapping.widgetToViewport_px({ 100.0, 0.0 });
  EXPECT_DOUBLE_EQ(v.x, 200.0);
  EXPECT_DOUBLE_EQ(v.y, 599.0);
}

TEST(ViewPointerMapping, DeviceToViewportInvertsViewportToDevice)
{
  vtouch::ViewPointerMapping mapping;
  mapping.setWidgetSize(640.0, 480.0, 1.0);
  mapping.setPixelsPerDeviceMm(2.5);
  const vtouch::Vec2 px{ 123.0, 456.0 };
  const vtouch::Vec2 back = mapping.deviceToViewport_px(mapping.viewportToDevice_mm(px));
  EXPECT_NEAR(back.x, px.x, 1e-12);
  EXPECT_NEAR(back.y, px.y, 1e-12);
}

TEST(ViewPointerMapping, IgnoresUnusableSizes)
{
  vtouch::ViewPointerMapping mapping;
  mapping.setWidgetSize(0.0, -3.0, 0.0);
  mapping.setPixelsPerDeviceMm(0.0);
  EXPECT_DOUBLE_EQ(mapping.viewportWidth_px(), 800.0);
  EXPECT_DOUBLE_EQ(mapping.viewportHeight_px(), 600.0);
  EXPECT_DOUBLE_EQ(mapping.pixelsPerDeviceMm(), 4.0);
}
