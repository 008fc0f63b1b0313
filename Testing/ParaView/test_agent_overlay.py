"""The agent over the cached MIP: a red-and-blue cone drawn where the agent is, over a non-blank
MIP; agent-only frames reuse the MIP image (the volume is not rendered again); a camera, data or
transfer-function change re-renders it; the blue base shows only when the agent heads away from
the viewer. No wall-clock assertion: Testing/Benchmarks/agent_framerate.py measures the rate.
"""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check, plugin_path  # noqa: E402

from paraview import simple  # noqa: E402

check = Check("AgentOverlay")
simple.LoadPlugin(plugin_path(), ns=globals())
import vesseltouch  # noqa: E402

WIDTH, HEIGHT = 400, 300
view = simple.CreateView("RenderView")
view.ViewSize = [WIDTH, HEIGHT]
view.UseColorPaletteForBackground = 0
view.Background = [0.0, 0.0, 0.0]
view.OrientationAxesVisibility = 0  # its red X axis would count as agent pixels
phantom = VesselPhantom(Shape="Tree", Dimensions=[64, 64, 64])  # noqa: F821
rep = vesseltouch.ShowAsMIP(phantom, view)
simple.Render(view)
bounds = phantom.GetDataInformation().GetBounds()
centre = [(bounds[2 * i] + bounds[2 * i + 1]) / 2.0 for i in range(3)]

# Independent count of the scene renderer's (volume) renders.
scene_renders = [0]
view.GetRenderer().AddObserver("StartEvent", lambda *_: scene_renders.__setitem__(
    0, scene_renders[0] + 1))

overlay = vesseltouch.AgentOverlay(view, rep, size_mm=0.25 * (bounds[1] - bounds[0]))


def view_direction():
    camera = view.GetRenderer().GetActiveCamera()
    p, f = camera.GetPosition(), camera.GetFocalPoint()
    d = [b - a for a, b in zip(p, f)]
    n = math.sqrt(sum(c * c for c in d))
    return [c / n for c in d]


def colours_near(image, point, radius=40):
    """(red, blue, bright grey) pixel counts in a square around the agent's projection."""
    x, y = overlay.ProjectToDisplay(point)
    row, col = int(round(HEIGHT - 1 - y)), int(round(x))
    patch = image[max(row - radius, 0):row + radius, max(col - radius, 0):col + radius].astype(int)
    r, g, b = patch[..., 0], patch[..., 1], patch[..., 2]
    red = int(((r > 120) & (r > 2 * g + 20) & (r > 2 * b + 20)).sum())
    blue = int(((b > 120) & (b > 2 * r + 20) & (b > 2 * g + 20)).sum())
    return red, blue


def bright_fraction(image):
    grey = image.astype(float)
    neutral = (abs(grey[..., 0] - grey[..., 2]) < 20) & (abs(grey[..., 0] - grey[..., 1]) < 20)
    return float(((grey.mean(axis=2) > 64) & neutral).mean())


def toward(sign, sideways=0.0):
    """sign = +1: away from the viewer, -1: toward it; plus ``sideways`` times screen-right."""
    v = view_direction()
    up = view.GetRenderer().GetActiveCamera().GetViewUp()
    right = [v[1] * up[2] - v[2] * up[1], v[2] * up[0] - v[0] * up[2], v[0] * up[1] - v[1] * up[0]]
    return [sign * c + sideways * r for c, r in zip(v, right)]


# 1. The first frame is a full render; it fills the cache.
away_oblique = toward(+1.0, 2.0)  # heading away from the viewer, mostly sideways
reused = overlay.MoveAgent(centre, away_oblique, 0.0, "tracing")
check.true(not reused, "the first frame renders the volume (no cache yet)")
check.equal(overlay.captures, 1, "the first full render is captured")
image_full = overlay.CaptureWindow()
red, blue = colours_near(image_full, centre)
check.true(red > 30 and blue > 30, "red sides and blue base near the agent (full frame): "
           "%d red, %d blue pixels" % (red, blue))
check.true(bright_fraction(image_full) > 0.005, "the MIP under the agent is not blank (%.4f)"
           % bright_fraction(image_full))

# 2. Moving the agent reuses the cached MIP: no volume render, a different image.
renders_before = scene_renders[0]
moved = [centre[0] + 6.0, centre[1] - 4.0, centre[2]]
reused = overlay.MoveAgent(moved, away_oblique, 40.0, "tracing")
check.true(reused and overlay.last_frame_cached, "an agent-only frame reuses the cache")
check.equal(scene_renders[0], renders_before, "the volume is not rendered for agent-only frames")
image_cached = overlay.CaptureWindow()
check.true((image_cached != image_full).any(), "moving the agent changes the image")
red, blue = colours_near(image_cached, moved)
check.true(red > 30 and blue > 30, "red and blue near the moved agent (cached frame): "
           "%d red, %d blue" % (red, blue))
check.true(bright_fraction(image_cached) > 0.005, "the cached frame still shows the MIP (%.4f)"
           % bright_fraction(image_cached))
for k in range(5):
    overlay.MoveAgent([moved[0] - k, moved[1], moved[2]], away_oblique, 10.0 * k, "tracing")
check.equal(scene_renders[0], renders_before, "five more agent frames, still no volume render")
check.equal(overlay.cached_frames, 6, "six cached frames counted")

# 3. Blue base visible heading away from the viewer, hidden heading toward it.
overlay.MoveAgent(centre, toward(+1.0), 0.0, "tracing")
red, blue = colours_near(overlay.CaptureWindow(), centre)
check.true(blue > 50, "heading away from the viewer shows the blue base (%d blue)" % blue)
overlay.MoveAgent(centre, toward(-1.0), 0.0, "tracing")
red, blue = colours_near(overlay.CaptureWindow(), centre)
check.true(blue == 0 and red > 50, "heading toward the viewer hides the base: %d blue, %d red"
           % (blue, red))
check.true(overlay.last_frame_cached, "those frames reused the cache too")

# 4. Exploring state: the yellow cursor, no cone.
overlay.MoveAgent(centre, toward(+1.0), 0.0, "exploring")
image = overlay.CaptureWindow()
red, blue = colours_near(image, centre)
x, y = overlay.ProjectToDisplay(centre)
pixel = image[int(round(HEIGHT - 1 - y)), int(round(x))].astype(int)
check.true(red == 0 and blue == 0, "exploring hides the cone (%d red, %d blue)" % (red, blue))
check.true(pixel[0] > 150 and pixel[1] > 120 and pixel[2] < 80,
           "exploring shows the yellow cursor at the position (pixel %s)" % list(pixel))

# 5. A camera change (VTK level, as an interactor would do) invalidates the cache.
captures = overlay.captures
view.GetRenderer().GetActiveCamera().Azimuth(25.0)
check.true(not overlay.IsCacheValid(), "a camera change invalidates the cache")
renders_before = scene_renders[0]
reused = overlay.MoveAgent(centre, toward(+1.0, 2.0), 0.0, "tracing")
check.true(not reused, "the frame after a camera change re-renders the volume")
check.equal(scene_renders[0], renders_before + 1, "exactly one volume render")
check.equal(overlay.captures, captures + 1, "and the new MIP is captured")
check.true(overlay.MoveAgent(centre, toward(+1.0, 2.0), 5.0, "tracing"),
           "the next frame reuses the new cache")
red, blue = colours_near(overlay.CaptureWindow(), centre)
check.true(red > 30 and blue > 30, "agent drawn after the camera change: %d red, %d blue"
           % (red, blue))

# The same through the proxy (pvpython camera properties).
view.CameraPosition = [p + 1.0 for p in view.CameraPosition]
check.true(not overlay.MoveAgent(centre, toward(+1.0), 0.0), "a proxy camera change re-renders")

# 6. Data and transfer-function changes re-render the volume; so does Invalidate().
lut = simple.GetColorTransferFunction("Intensity")
lut.ApplyPreset("Cool to Warm", True)
check.true(not overlay.MoveAgent(centre, toward(+1.0), 0.0), "a transfer-function change "
           "re-renders the volume")
lut.ApplyPreset("Grayscale", True)
phantom.NoiseStandardDeviation = 5.0
check.true(not overlay.MoveAgent(centre, toward(+1.0), 0.0), "a data change re-renders")
check.true(overlay.MoveAgent(centre, toward(+1.0), 0.0), "then the cache is reused again")
overlay.Invalidate()
check.true(not overlay.MoveAgent(centre, toward(+1.0), 0.0), "Invalidate() forces a full render")

# 7. With the cache off every frame renders the volume (the benchmark's reference mode).
overlay.use_cache = False
renders_before = scene_renders[0]
overlay.MoveAgent(centre, toward(+1.0), 0.0)
overlay.MoveAgent(centre, toward(+1.0), 10.0)
check.equal(scene_renders[0], renders_before + 2, "use_cache=False renders the volume each frame")
overlay.use_cache = True

# 8. Bad input is refused clearly.
for bad in ([0.0, 0.0, 0.0], [float("nan"), 0.0, 1.0]):
    try:
        overlay.MoveAgent(centre, bad, 0.0)
        check.true(False, "a zero or NaN direction must raise")
    except ValueError as error:
        check.true("direction" in str(error), "clear message: %s" % error)
try:
    overlay.SetState("flying")
    check.true(False, "an unknown state must raise")
except ValueError:
    check.true(True, "unknown state refused")

# 9. Removing the overlay gives ParaView its view back: no agent in a normal screenshot.
layers = view.GetRenderWindow().GetNumberOfLayers()
overlay.Remove()
check.equal(view.GetRenderWindow().GetNumberOfLayers(), layers - 1, "the overlay layer is removed")
simple.Render(view)
red, blue = colours_near(overlay.CaptureWindow(), centre)
check.true(red == 0 and blue == 0, "no agent after Remove (%d red, %d blue)" % (red, blue))

# A render view still alive at exit is destroyed after its X connection (ParaView 5.11 teardown).
simple.Delete(view)
check.finish()
