"""Does ParaView 5.11's MIP (Volume representation, BlendMode 1) honour the direction matrix of
images from the VesselTouch reader?

Three 24^3 volumes hold one bright bar. A has the direction diag(-1, 1, 1) (index i runs toward
-x); B has the identity direction and its voxels mirrored along i with its origin moved so that
its bar sits at the same world place as A's; C is A's voxels with the identity direction (what a
renderer that ignores the direction would show). Seen from +z with a parallel camera, A must look
like B and unlike C. Run as ``pvpython test_readers_mip.py`` under Xvfb with VESSELTOUCH_PLUGIN
set; exits non-zero on failure. Also checks vesseltouch.ShowPatientOrientation's labels.
"""

import os
import shutil
import sys
import tempfile

import numpy as np

from paraview.simple import (CreateRenderView, Delete, FindSource, GetDisplayProperties, Hide,
                             LoadPlugin, OpenDataFile, Render, SaveScreenshot, Show)
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader

LoadPlugin(os.environ["VESSELTOUCH_PLUGIN"], ns=globals())
import vesseltouch  # noqa: E402  (embedded in the plugin)

N = 24
SPACING = 1.0


def write_mha(path, array, origin, direction):
    matrix = " ".join(repr(float(direction[r, a])) for a in range(3) for r in range(3))
    header = ("ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
              "CompressedData = False\nTransformMatrix = %s\nOffset = %s\n"
              "ElementSpacing = 1 1 1\nDimSize = %d %d %d\nElementType = MET_UCHAR\n"
              "ElementDataFile = LOCAL\n") % (matrix, " ".join(repr(float(c)) for c in origin),
                                               N, N, N)
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(np.ascontiguousarray(array, dtype=np.uint8).tobytes())


def mip_image(view, path, folder, name):
    reader = OpenDataFile(path)
    rep = vesseltouch.ShowAsMIP(reader, view)
    Render(view)  # paraview.simple resets the camera on a view's first render: do it first
    camera = view.GetActiveCamera()
    camera.SetPosition(0.0, 0.0, 200.0)
    camera.SetFocalPoint(0.0, 0.0, 0.0)
    camera.SetViewUp(0.0, 1.0, 0.0)
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 30.0
    Render(view)
    png = os.path.join(folder, name + ".png")
    SaveScreenshot(png, view, ImageResolution=[240, 240])
    Hide(reader, view)
    png_reader = vtkPNGReader()
    png_reader.SetFileName(png)
    png_reader.Update()
    image = png_reader.GetOutput()
    nx, ny, _ = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(ny, nx, -1)
    return pixels[:, :, :3].astype(float).mean(axis=2), rep


def check_orientation_labels(view, path):
    """vesseltouch.ShowPatientOrientation: L beyond +x in LPS, R beyond +x in RAS, and so on."""
    failures = []
    reader = OpenDataFile(path)
    Show(reader, view)
    for frame, plus_x, plus_y in ((0, "L", "P"), (1, "R", "A")):
        reader.OutputFrame = frame
        texts = vesseltouch.ShowPatientOrientation(reader, view)
        bounds = reader.GetDataInformation().GetBounds()
        if sorted(texts) != sorted("LRAPSI"):
            failures.append("orientation labels: %s" % sorted(texts))
            continue
        where = {label: GetDisplayProperties(text, view).BillboardPosition
                 for label, text in texts.items()}
        if not (where[plus_x][0] > bounds[1] and where["LR".replace(plus_x, "")][0] < bounds[0]):
            failures.append("frame %d: %s not at +x (%s, bounds %s)" % (frame, plus_x, where, bounds))
        if not (where[plus_y][1] > bounds[3] and where["S"][2] > bounds[5]):
            failures.append("frame %d: %s/S misplaced (%s)" % (frame, plus_y, where))
        Render(view)
    vesseltouch.HidePatientOrientation()
    if FindSource("PatientOrientation-L") is not None:
        failures.append("HidePatientOrientation left the labels")
    Hide(reader, view)
    return failures


def main():
    folder = tempfile.mkdtemp(prefix="vtouch-mip-")
    failures = []
    try:
        bar = np.zeros((N, N, N))  # z, y, x
        bar[:, 4:8, 3:7] = 255     # i in [3, 7), j in [4, 8)
        flip = np.diag([-1.0, 1.0, 1.0])
        write_mha(os.path.join(folder, "a.mha"), bar, (0.0, 0.0, 0.0), flip)
        # B: voxel i of A is voxel N-1-i of B, at x = -i = origin_x + (N-1-i).
        write_mha(os.path.join(folder, "b.mha"), bar[:, :, ::-1], (-(N - 1.0), 0.0, 0.0), np.eye(3))
        write_mha(os.path.join(folder, "c.mha"), bar, (0.0, 0.0, 0.0), np.eye(3))

        view = CreateRenderView()
        view.ViewSize = [240, 240]
        view.OrientationAxesVisibility = 0
        view.Background = [0.0, 0.0, 0.0]
        images = {}
        for name in "abc":
            images[name], rep = mip_image(view, os.path.join(folder, name + ".mha"), folder, name)
            if vesseltouch.mip.BlendMode(rep) != 1:
                failures.append("%s: blend mode is not maximum intensity" % name)

        def bright_x(img):
            ys, xs = np.nonzero(img > 0.5 * img.max())
            return xs.mean() if len(xs) else float("nan")

        centre = images["a"].shape[1] / 2.0
        xa, xb, xc = (bright_x(images[n]) for n in "abc")
        print("bar centre in screen x (image centre %.0f): A %.1f, B %.1f, C %.1f"
              % (centre, xa, xb, xc))
        diff_ab = np.abs(images["a"] - images["b"]).mean()
        diff_ac = np.abs(images["a"] - images["c"]).mean()
        print("mean |A - B| = %.2f, mean |A - C| = %.2f (grey levels)" % (diff_ab, diff_ac))
        if not xa < centre:
            failures.append("A's bar (world x < 0) is drawn right of centre: direction ignored")
        if not abs(xa - xb) < 3:
            failures.append("A and B differ: bar at %.1f vs %.1f px" % (xa, xb))
        if not diff_ab < 0.25 * diff_ac:
            failures.append("A looks more like C (direction ignored) than like B")
        failures.extend(check_orientation_labels(view, os.path.join(folder, "a.mha")))
        # Delete the view now: destroying it at interpreter exit crashes ParaView 5.11 under Xvfb
        # (X error in vtkOpenGLFXAAFilter::ReleaseGraphicsResources).
        Delete(view)
        del view
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    for f in failures:
        print("FAIL:", f)
    if failures:
        return 1
    print("test_readers_mip: the MIP honours the direction matrix")
    return 0


if __name__ == "__main__":
    sys.exit(main())
