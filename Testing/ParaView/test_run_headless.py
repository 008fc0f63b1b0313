"""The main job headless: `Utilities/run.sh --headless --no-build` on this build tree, into a
temporary folder. Checks what it writes: the screenshot shows the agent cone (red beside blue)
on a vessel of the MIP (bright pixels around it), force.png is a real plot, trace.npz holds the
log and its measures, loop_statistics.json the real-time and offline loop statistics, report.txt
the summary."""

import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from vtouch_testing import Check  # noqa: E402

import numpy  # noqa: E402
from paraview.vtk.util.numpy_support import vtk_to_numpy  # noqa: E402
from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402

check = Check("run.sh --headless")
source = os.environ["VESSELTOUCH_SOURCE_DIR"]
build = os.environ["VESSELTOUCH_BINARY_DIR"]


def read_png(path):
    """(height, width, 3) uint8, row 0 at the top."""
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    width, height, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars())
    return pixels.reshape(height, width, -1)[::-1, :, :3]


def dilate(mask, radius):
    """Pixels within ``radius`` (Chebyshev) of a true pixel."""
    out = numpy.zeros_like(mask)
    padded = numpy.pad(mask, radius)
    h, w = mask.shape
    for dy in range(2 * radius + 1):
        for dx in range(2 * radius + 1):
            out |= padded[dy:dy + h, dx:dx + w]
    return out


with tempfile.TemporaryDirectory(prefix="vesseltouch-run-") as out:
    env = dict(os.environ)
    env.pop("VESSELTOUCH_OUTPUT_DIR", None)
    result = subprocess.run(["bash", os.path.join(source, "Utilities", "run.sh"), "--headless",
                             "--no-build", "--build", build, "--output", out],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
                            universal_newlines=True, timeout=240)
    print(result.stdout)
    check.equal(result.returncode, 0, "run.sh --headless exits cleanly")
    files = ("screenshot.png", "force.png", "trace.npz", "loop_statistics.json", "report.txt")
    for name in files:
        check.true(os.path.exists(os.path.join(out, name)), "run.sh wrote %s" % name)
    if not all(os.path.exists(os.path.join(out, name)) for name in files):
        check.finish()

    # The agent cone on a vessel of the MIP.
    image = read_png(os.path.join(out, "screenshot.png")).astype(int)
    r, g, b = image[..., 0], image[..., 1], image[..., 2]
    red = (r > 120) & (r > 2 * g + 20) & (r > 2 * b + 20)
    blue = (b > 120) & (b > 2 * r + 20) & (b > 2 * g + 20)
    grey = (abs(r - g) < 12) & (abs(g - b) < 12)
    bright = grey & (r > 90)
    check.true(red.sum() > 30 and blue.sum() > 10, "the cone shows red sides and a blue base "
               "(%d red, %d blue pixels)" % (red.sum(), blue.sum()))
    beside = red & dilate(blue, 3)
    check.true(beside.sum() > 3, "red and blue pixels touch (%d)" % beside.sum())
    cone = dilate(red | blue, 2)
    near = bright & dilate(cone, 25) & ~cone
    check.true(near.sum() > 40, "bright MIP pixels (a vessel) surround the cone (%d)" % near.sum())
    background = (r < 25) & (g < 25) & (b < 25)
    check.true(0.3 < background.mean() < 0.995, "the MIP is white vessels on black (%.3f dark)"
               % background.mean())
    statistics = json.load(open(os.path.join(out, "loop_statistics.json")))
    agent = statistics.get("agent_in_screenshot", {})
    if "pixel" in agent:
        x, y = (int(round(v)) for v in agent["pixel"])
        patch = (red | blue)[max(y - 30, 0):y + 30, max(x - 30, 0):x + 30]
        check.true(patch.sum() > 20, "the cone is where the log puts the agent (%d, %d)" % (x, y))

    # force.png: a plot, not an empty figure.
    plot = read_png(os.path.join(out, "force.png")).astype(int)
    check.true(plot.shape[0] >= 400 and plot.shape[1] >= 600, "force.png size %r" % (plot.shape,))
    coloured = (numpy.abs(plot[..., 0] - plot[..., 2]) > 60)
    check.true(coloured.sum() > 500, "force.png has coloured curves (%d px)" % coloured.sum())
    check.true(os.path.getsize(os.path.join(out, "force.png")) > 20000, "force.png is not trivial")

    # The trace behind them.
    trace = numpy.load(os.path.join(out, "trace.npz"))
    n = len(trace["time"])
    check.true(n >= 1000, "trace.npz: %d ticks" % n)
    for key in ("force", "position", "state", "force_magnitude", "force_along_travel", "depth_mm"):
        check.true(key in trace and len(trace[key]) == n, "trace.npz has %s" % key)
    tracing = trace["state"] == 1
    check.true(tracing.mean() > 0.5, "the scripted hand traces a vessel (%.2f)" % tracing.mean())
    check.true(float(trace["force_magnitude"].max()) > 0.05, "a force is felt (%.3f N)"
               % trace["force_magnitude"].max())
    check.true(bool(numpy.isfinite(trace["force"]).all())
               and float(trace["force_magnitude"].max()) <= 3.0 + 1e-9, "forces finite, bounded")
    depth = trace["depth_mm"][tracing]
    check.true(float(depth.max() - depth.min()) > 1.0, "the traced vessel changes depth (%.1f mm)"
               % (depth.max() - depth.min()))

    # Loop statistics and the report.
    realtime = statistics.get("realtime", {})
    check.true(realtime.get("ticks", 0) > 100, "real-time ticks recorded (%r)"
               % realtime.get("ticks"))
    check.true(realtime.get("nominal_rate_Hz") == 1000.0, "real-time nominal rate 1 kHz")
    check.true("offline" in statistics and "note" in statistics["offline"],
               "offline statistics labelled apart")
    report = open(os.path.join(out, "report.txt")).read()
    for text in ("VesselCenterline", "VesselTouchSession", "trace:", "real time:", "period error"):
        check.true(text in report, "report.txt mentions %r" % text)
check.finish()
