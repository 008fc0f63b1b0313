"""Integration test: the VesselTouch reader streams pieces (issue 19, "readers that stream").

Run as ``pvpython test_reader_pieces.py`` with VESSELTOUCH_PLUGIN set (see test_readers.py for the
test volume writer). A parallel pipeline asks each rank for piece r of n; the reader must answer
with a sub-extent that it read alone.

What is checked, for an uncompressed NRRD, NIfTI and MetaImage file, a DICOM series and a .nii.gz:
- the pieces r = 0..n-1 of n (n = 2, 3, 5) tile the whole extent (by cells, VTK's convention: neighbours share one boundary layer of points), and every
  voxel of every piece holds the value the whole read gives at that index;
- uncompressed files read exactly their piece's bytes (field data ReaderVoxelBytesRead), a DICOM
  series opens only the files of its piece's slices (ReaderFilesRead), and the reader says which
  files stream (ReaderReadsPiecesAlone: 0 for .nii.gz, which decodes the whole file per piece);
- the origin, spacing and direction of a piece are those of the whole volume;
- with one ghost level asked, each piece grows by one layer inside the volume and marks exactly
  that layer as duplicate points (vtkGhostType), as a distributed filter needs;
- a piece asked for again grown by ghost levels copies the voxels it holds when a view holds them
  too (ReaderVoxelBytesReused) and reads only the rest; held by the reader alone or compressed,
  it reads everything again.
Exits non-zero on any failure.
"""

import os
import shutil
import subprocess
import tempfile

import numpy as np

from paraview.simple import Delete, LoadPlugin, OpenDataFile
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkImageData
from vtouch_testing import Check, plugin_path, test_volume_writer

LoadPlugin(plugin_path(), ns=globals())
CHECK = Check("reader pieces")
check = CHECK.true


def reader_for(path):
    if os.path.isdir(path):
        proxy = VesselTouchDICOMSeriesReader(FileName=path)  # noqa: F821 (from LoadPlugin)
    else:
        proxy = OpenDataFile(path)  # the VesselTouch reader for every extension (test_readers.py)
    return proxy, proxy.GetClientSideObject()


def field(image, name):
    return image.GetFieldData().GetArray(name).GetValue(0)


def as_array(image):
    dims = [image.GetExtent()[2 * a + 1] - image.GetExtent()[2 * a] + 1 for a in range(3)]
    values = vtk_to_numpy(image.GetPointData().GetScalars())
    return values.reshape(dims[2], dims[1], dims[0])  # [k, j, i]


def check_ghosts(name, reader, whole, whole_extent, n):
    """Piece r of n with one ghost level: the piece grown by one layer (inside the volume), the
    grown layers marked as duplicate points in vtkGhostType, the voxels still the file's."""
    for r in range(n):
        reader.UpdatePiece(r, n, 0)
        plain = reader.GetOutput().GetExtent()
        reader.UpdatePiece(r, n, 1)
        piece = reader.GetOutput()
        e = piece.GetExtent()
        grown = [max(plain[a] - 1, whole_extent[a]) if a % 2 == 0 else
                 min(plain[a] + 1, whole_extent[a]) for a in range(6)]
        check(list(e) == grown, "%s: piece %d/%d with a ghost level is %s, not %s"
              % (name, r, n, list(e), grown))
        ghosts = piece.GetPointData().GetArray("vtkGhostType")
        check(ghosts is not None, "%s: piece %d/%d has no vtkGhostType array" % (name, r, n))
        if ghosts is None:
            continue
        flags = vtk_to_numpy(ghosts).reshape(e[5] - e[4] + 1, e[3] - e[2] + 1, e[1] - e[0] + 1)
        own = np.zeros(flags.shape, dtype=bool)
        own[plain[4] - e[4]:plain[5] - e[4] + 1, plain[2] - e[2]:plain[3] - e[2] + 1,
            plain[0] - e[0]:plain[1] - e[0] + 1] = True
        duplicate = (flags & 1) != 0  # vtkDataSetAttributes::DUPLICATEPOINT
        check(np.array_equal(duplicate, ~own),
              "%s: piece %d/%d marks other points as ghosts than its grown layer" % (name, r, n))
        values = as_array(piece)
        check(np.array_equal(values, whole[e[4]:e[5] + 1, e[2]:e[3] + 1, e[0]:e[1] + 1]),
              "%s: piece %d/%d with ghosts holds other values" % (name, r, n))


def check_pieces(name, path, streams, dicom=False):
    proxy, reader = reader_for(path)
    reader.UpdatePiece(0, 1, 0)
    whole_image = reader.GetOutput()
    whole = as_array(whole_image).copy()
    whole_extent = whole_image.GetExtent()
    origin, spacing = whole_image.GetOrigin(), whole_image.GetSpacing()
    direction = [whole_image.GetDirectionMatrix().GetElement(r, c)
                 for r in range(3) for c in range(3)]
    check(field(whole_image, 'ReaderReadsPiecesAlone') == (1 if streams else 0),
          "%s: GetReadsPiecesAlone() is %d" % (name, field(whole_image, 'ReaderReadsPiecesAlone')))
    item = whole.dtype.itemsize
    for n in (2, 3, 5):
        covered = np.zeros(whole.shape, dtype=np.int32)
        for r in range(n):
            reader.UpdatePiece(r, n, 0)
            piece = reader.GetOutput()
            e = piece.GetExtent()
            if e[1] < e[0] or e[3] < e[2] or e[5] < e[4]:
                continue  # an empty piece
            for a in range(3):
                check(e[2 * a] >= whole_extent[2 * a] and e[2 * a + 1] <= whole_extent[2 * a + 1],
                      "%s: piece %d/%d extent %s outside %s" % (name, r, n, e, whole_extent))
            values = as_array(piece)
            box = whole[e[4]:e[5] + 1, e[2]:e[3] + 1, e[0]:e[1] + 1]
            check(values.shape == box.shape and np.array_equal(values, box),
                  "%s: piece %d/%d holds other values than the whole read" % (name, r, n))
            # Image pieces are split by cells: neighbours share their boundary layer of points.
            # Each piece owns its points up to, not including, its upper layer (the last piece
            # along an axis owns that layer too), and those owned points tile the volume once.
            own = [e[2 * a + 1] + (1 if e[2 * a + 1] == whole_extent[2 * a + 1] else 0)
                   for a in range(3)]
            covered[e[4]:own[2], e[2]:own[1], e[0]:own[0]] += 1
            check(np.allclose(piece.GetOrigin(), origin) and np.allclose(piece.GetSpacing(), spacing),
                  "%s: piece %d/%d origin/spacing differ" % (name, r, n))
            piece_direction = [piece.GetDirectionMatrix().GetElement(i, j)
                               for i in range(3) for j in range(3)]
            check(np.allclose(piece_direction, direction),
                  "%s: piece %d/%d direction differs" % (name, r, n))
            # What the previous piece held and is still held here (`values` of the last round
            # keeps it) is copied, not read again (ReaderVoxelBytesReused); the rest is read.
            reused = field(piece, 'ReaderVoxelBytesReused')
            if streams and not dicom:
                check(field(piece, 'ReaderVoxelBytesRead') + reused == values.size * item,
                      "%s: piece %d/%d read %d bytes and copied %d for %d voxel bytes"
                      % (name, r, n, field(piece, 'ReaderVoxelBytesRead'), reused,
                         values.size * item))
            if dicom:
                slice_bytes = (e[1] - e[0] + 1) * (e[3] - e[2] + 1) * item
                check(field(piece, 'ReaderFilesRead') + reused // slice_bytes == e[5] - e[4] + 1
                      and reused % slice_bytes == 0,
                      "%s: piece %d/%d opened %d files and copied %d bytes for %d slices"
                      % (name, r, n, field(piece, 'ReaderFilesRead'), reused, e[5] - e[4] + 1))
            if not streams:
                check(field(piece, 'ReaderVoxelBytesRead') == whole.size * item,
                      "%s: a compressed piece should decode the whole file" % name)
        check_ghosts(name, reader, whole, whole_extent, n)
        check(covered.min() == 1 and covered.max() == 1,
              "%s: %d pieces do not tile the volume once (coverage %d..%d)"
              % (name, n, covered.min(), covered.max()))
    Delete(proxy)


def check_grown_piece_reuse(name, path, streams):
    """A piece asked for again grown by ghost levels (a distributed VesselCenterline after the view
    showed the piece): held elsewhere too (a representation's shallow copy), the voxels it holds
    are copied and only the rest is read; held by the reader's output alone, or from a compressed
    file, or asked for more than twice as large (the whole volume), everything is read again (the
    peak memory stays the new piece's)."""
    proxy, reader = reader_for(path)
    reader.UpdatePiece(0, 1, 0)
    whole = as_array(reader.GetOutput()).copy()
    item = whole.dtype.itemsize

    def voxels(e):
        return (e[1] - e[0] + 1) * (e[3] - e[2] + 1) * (e[5] - e[4] + 1)

    for held in (True, False):
        reader.UpdatePiece(0, 2, 0)
        piece = reader.GetOutput().GetExtent()
        view_copy = vtkImageData()
        if held:
            view_copy.ShallowCopy(reader.GetOutput())  # what a view's representation keeps
        reader.UpdatePiece(0, 2, 2)
        grown = reader.GetOutput()
        e = grown.GetExtent()
        check(voxels(e) > voxels(piece), "%s: the grown piece %s is larger than %s"
              % (name, e, piece))
        reused = field(grown, "ReaderVoxelBytesReused")
        read = field(grown, "ReaderVoxelBytesRead")
        if held and streams:
            check(reused == voxels(piece) * item and read == (voxels(e) - voxels(piece)) * item,
                  "%s: the grown piece copied the %d bytes held and read only the other %d "
                  "(copied %d, read %d)" % (name, voxels(piece) * item,
                                            (voxels(e) - voxels(piece)) * item, reused, read))
        else:
            check(reused == 0, "%s: nothing copied when %s (copied %d)"
                  % (name, "the piece was held only by the reader" if streams else
                     "the file is compressed", reused))
        check(np.array_equal(as_array(grown), whole[e[4]:e[5] + 1, e[2]:e[3] + 1, e[0]:e[1] + 1]),
              "%s: the grown piece (%s) holds the file's values" % (name, "held" if held else
                                                                     "not held"))
        del view_copy
        reader.UpdatePiece(1, 2, 0)  # another piece in between: the next round starts afresh
    # The whole volume after a quarter piece, held by a view: more than twice the piece, read anew
    # (the copy is for a piece grown by its ghost margin; on the first rank asked for the whole
    # volume it raised the peak memory).
    reader.UpdatePiece(0, 4, 0)
    quarter = reader.GetOutput().GetExtent()
    view_copy = vtkImageData()
    view_copy.ShallowCopy(reader.GetOutput())
    reader.UpdatePiece(0, 1, 0)
    full = reader.GetOutput()
    check(voxels(full.GetExtent()) > 2 * voxels(quarter),
          "%s: the whole volume is more than twice the piece %s" % (name, quarter))
    check(field(full, "ReaderVoxelBytesReused") == 0 and
          field(full, "ReaderVoxelBytesRead") == voxels(full.GetExtent()) * item,
          "%s: the whole volume after a held quarter piece is read anew (copied %d, read %d)"
          % (name, field(full, "ReaderVoxelBytesReused"), field(full, "ReaderVoxelBytesRead")))
    check(np.array_equal(as_array(full), whole), "%s: the whole volume holds the file's values" % name)
    del view_copy
    Delete(proxy)


def main():
    tmp = tempfile.mkdtemp(prefix="vtouch-pieces-")
    try:
        size = ["23", "17", "11"]
        for name, streams in (("v.nrrd", True), ("v.nhdr", True), ("v.nii", True),
                              ("v.mha", True), ("v.mhd", True), ("v.nii.gz", False)):
            path = os.path.join(tmp, name)
            subprocess.run([test_volume_writer(), "volume", path, "oblique", "int16"] + size, check=True,
                           stdout=subprocess.DEVNULL)
            check_pieces(name, path, streams)
            if name in ("v.nrrd", "v.nii.gz"):
                check_grown_piece_reuse(name, path, streams)
        series = os.path.join(tmp, "dicom")
        os.makedirs(series)
        subprocess.run([test_volume_writer(), "dicom", series, "1.2.826.0.1.3680043.2.1125.91", "oblique",
                        "-1", "IM", "23", "17", "11"], check=True, stdout=subprocess.DEVNULL)
        check_pieces("DICOM series", series, True, dicom=True)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    CHECK.finish()


main()
