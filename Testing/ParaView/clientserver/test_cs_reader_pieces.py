"""Client/server integration test (issue 19): a 2-rank pvserver reads a volume in pieces and renders
its MIP for the client.

Run as ``pvpython test_cs_reader_pieces.py`` with VESSELTOUCH_PLUGIN (and optionally
VESSELTOUCH_TEST_VOLUME_WRITER) set, on a display (vtouch-xvfb-run). Starts
``mpiexec -np 2 pvserver`` on 127.0.0.1 with a free port (vtouch_pvserver.ParallelServer: every
wait timed out, the process group ended, the port freed), connects, and loads the plugin on both
sides from the same file.

What is checked:
- the VesselTouch reader opens an uncompressed NRRD on the server, distributed across the ranks:
  each rank holds a different piece, read alone (its field data ReaderVoxelBytesRead equals its
  piece's bytes, less than the whole volume's), and the pieces cover the volume;
- the voxels of each rank's piece, fetched by the client, equal the file's (the writer's values);
- the MIP (VesselTouch's ShowAsMIP) is rendered on the server (remote rendering forced) and the
  client's screenshot shows the volume: the bright voxel block is bright, the background black;
- after Disconnect the server exits within its time-out and the port is free again.
Exits non-zero on any failure.
"""

import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(HERE)]  # vtouch_pvserver here, vtouch_testing above
from vtouch_pvserver import run_connected  # noqa: E402
from vtouch_testing import Check, plugin_path, test_volume_writer  # noqa: E402

from paraview import servermanager as sm  # noqa: E402
from paraview import simple  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

PLUGIN = plugin_path()
CHECK = Check("client/server reader pieces")
check = CHECK.true

RANK_SCRIPT = r"""
from vtkmodules.vtkParallelCore import vtkMultiProcessController
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray
image = self.GetInputDataObject(0, 0)
out = self.GetPolyDataOutput()
controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId() if controller else 0
points = vtkPoints()
points.InsertNextPoint(rank, 0, 0)
out.SetPoints(points)
verts = vtkCellArray()
verts.InsertNextCell(1)
verts.InsertCellPoint(0)
out.SetVerts(verts)
def add(name, values):
    a = vtkDoubleArray()
    a.SetName(name)
    a.SetNumberOfComponents(len(values))
    a.InsertNextTuple(values)
    out.GetPointData().AddArray(a)
e = image.GetExtent()
bytes_read = image.GetFieldData().GetArray("ReaderVoxelBytesRead")
add("rank", [rank])
add("extent", list(e))
add("points", [image.GetNumberOfPoints()])
add("bytes_read", [bytes_read.GetValue(0) if bytes_read else -1])
"""


def expected_voxels(size):
    # vtouch::test::testVoxelValue(i, j, k) = i + 10 j + 100 k - 50, as [k, j, i]
    k, j, i = np.meshgrid(np.arange(size[2]), np.arange(size[1]), np.arange(size[0]),
                          indexing="ij")
    return (i + 10 * j + 100 * k - 50).astype(np.int16)


def check_pieces(reader, size):
    per_rank = simple.ProgrammableFilter(Input=reader, OutputDataSetType="vtkPolyData",
                                         Script=RANK_SCRIPT)
    table = sm.Fetch(per_rank)
    pd = table.GetPointData()
    n = table.GetNumberOfPoints()
    check(n == 2, "expected one piece per rank (2), got %d" % n)
    whole_points = size[0] * size[1] * size[2]
    covered = np.zeros((size[2], size[1], size[0]), dtype=np.int32)
    ranks = set()
    for p in range(n):
        rank = int(pd.GetArray("rank").GetValue(p))
        e = [int(v) for v in pd.GetArray("extent").GetTuple(p)]
        points = int(pd.GetArray("points").GetValue(p))
        bytes_read = pd.GetArray("bytes_read").GetValue(p)
        ranks.add(rank)
        print("rank %d: extent %s, %d points, %d bytes read" % (rank, e, points, bytes_read))
        check(0 < points < whole_points, "rank %d holds %d of %d points: not a piece"
              % (rank, points, whole_points))
        check(bytes_read == 2 * points, "rank %d read %d bytes for a %d-voxel piece"
              % (rank, bytes_read, points))
        covered[e[4]:e[5] + 1, e[2]:e[3] + 1, e[0]:e[1] + 1] += 1
    check(ranks == {0, 1}, "pieces came from ranks %s, not 0 and 1" % sorted(ranks))
    check(covered.min() >= 1, "the pieces leave voxels unread")
    simple.Delete(per_rank)


def check_voxels(reader, size):
    want = expected_voxels(size)
    for rank in (0, 1):
        image = sm.Fetch(reader, rank)  # that rank's piece
        e = image.GetExtent()
        dims = [e[2 * a + 1] - e[2 * a] + 1 for a in range(3)]
        values = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(dims[2], dims[1], dims[0])
        check(np.array_equal(values, want[e[4]:e[5] + 1, e[2]:e[3] + 1, e[0]:e[1] + 1]),
              "the voxels of rank %d's piece %s differ from the file's" % (rank, list(e)))


def check_mip(reader, folder):
    import vesseltouch
    view = simple.CreateView("RenderView")
    view.ViewSize = [400, 300]
    view.RemoteRenderThreshold = 0.0  # render on the server, composite, send the image
    view.OrientationAxesVisibility = 0
    view.Background = [0, 0, 0]
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    rep = vesseltouch.ShowAsMIP(reader, view)
    check(vesseltouch.mip.BlendMode(rep) == 1, "the MIP's blend mode is not maximum intensity")
    view.CameraPosition = [0, 0, 1]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 1, 0]
    view.ResetCamera()
    simple.Render(view)
    shot = os.path.join(folder, "cs_mip.png")
    simple.SaveScreenshot(shot, view, ImageResolution=[400, 300])
    from vtkmodules.vtkIOImage import vtkPNGReader
    png = vtkPNGReader()
    png.SetFileName(shot)
    png.Update()
    img = png.GetOutput()
    pixels = vtk_to_numpy(img.GetPointData().GetScalars()).reshape(300, 400, -1)[:, :, :3]
    brightness = pixels.astype(float).mean(axis=2)
    centre = brightness[120:180, 160:240].mean()
    corner = brightness[:20, :20].mean()
    print("MIP screenshot: centre %.1f, corner %.1f" % (centre, corner))
    check(centre > 60.0, "the server-rendered MIP is dark at the volume's centre (%.1f)" % centre)
    check(corner < 10.0, "the MIP's background is not black (%.1f)" % corner)
    keep = os.environ.get("VESSELTOUCH_CS_SCREENSHOT")
    if keep:
        shutil.copy(shot, keep)
    simple.Delete(rep)
    simple.Delete(view)


def main():
    folder = tempfile.mkdtemp(prefix="vtouch-cs-")
    size = [40, 30, 24]
    path = os.path.join(folder, "volume.nrrd")
    subprocess.run([test_volume_writer(), "volume", path, "axial", "int16"] + [str(s) for s in size],
                   check=True, stdout=subprocess.DEVNULL)
    def body():
        reader = simple.OpenDataFile(path)
        check(reader.GetXMLName().startswith("Anatomical"),
              "the server opened the NRRD with %s, not the VesselTouch reader" % reader.GetXMLName())
        reader.UpdatePipeline()
        check_pieces(reader, size)
        check_voxels(reader, size)
        check_mip(reader, folder)

    try:
        run_connected(PLUGIN, check, body)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    CHECK.finish()


main()
