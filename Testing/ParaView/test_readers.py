"""Integration test of the VesselTouch readers (vtkVesselTouchImageReader) in pvpython.

Run as ``pvpython test_readers.py`` with VESSELTOUCH_PLUGIN (path of VesselTouch.so) and
VESSELTOUCH_SHARED_DATA (the shared data folder) set. The DICOM and ITK-written volumes come from
the test writer vtouchWriteTestVolume (Testing/Logic/IO), found through
VESSELTOUCH_TEST_VOLUME_WRITER or in the plugin's build tree. Exits non-zero on any failure.

What is checked:
- tiny volumes with an oblique direction and anisotropic spacing, written by hand here (NRRD in
  LPS and in RAS space, MetaImage, NIfTI .nii.gz with a RAS sform) and by ITK (.nrrd .nhdr .nii
  .nii.gz .mha .mhd, a DICOM series whose file names run against the slice order), read back
  with the right world (LPS) position and value of every voxel;
- paraview.simple.OpenDataFile picks the VesselTouch reader for every extension;
- a DICOM folder with two series: both listed, the largest read, the other on request;
- the shared VMTK aorta: its reference centerline, converted from RAS to LPS, lies in the
  level-set vessel (value < 0) probed in world coordinates; in RAS output it does with no
  conversion; without the conversion it does not (the test can fail);
- bad input (2D, 4D, vector, 64-bit, truncated, corrupt, missing slice, missing file): an error
  message, an empty output, no crash.
"""

import gzip
import json
import os
import shutil
import struct
import subprocess
import sys
import tempfile

import numpy as np

from paraview import servermanager as sm
from vtouch_testing import test_volume_writer
from paraview.simple import Delete, LoadPlugin, OpenDataFile, XMLPolyDataReader
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.util.vtkConstants import VTK_STRING

PLUGIN = os.environ["VESSELTOUCH_PLUGIN"]
SHARED = os.environ["VESSELTOUCH_SHARED_DATA"]
LoadPlugin(PLUGIN, ns=globals())

FAILURES = []


def check(condition, message):
    if not condition:
        FAILURES.append(message)
        print("FAIL:", message)


def itk_write(*args):
    out = subprocess.run([test_volume_writer()] + [str(a) for a in args], check=True,
                         capture_output=True, text=True).stdout
    lines = [line for line in out.splitlines() if line.startswith("{")]
    return json.loads(lines[-1]) if lines else None


# ---- geometry shared with Testing/Logic/IO/vtouchTestVolumes.cxx --------------------------------

def voxel_value(i, j, k):
    return i + 10 * j + 100 * k - 50


def oblique_direction():
    a, b = np.radians(30.0), np.radians(20.0)
    rz = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    rx = np.array([[1, 0, 0], [0, np.cos(b), -np.sin(b)], [0, np.sin(b), np.cos(b)]])
    return rx @ rz


SIZE = (6, 5, 4)
SPACING = np.array([0.7, 1.1, 2.5])
ORIGIN = np.array([-12.5, 30.25, 101.0])  # LPS
DIRECTION = oblique_direction()          # columns: LPS directions of the index axes
LPS_TO_RAS = np.diag([-1.0, -1.0, 1.0])


def volume_array():
    k, j, i = np.meshgrid(range(SIZE[2]), range(SIZE[1]), range(SIZE[0]), indexing="ij")
    return voxel_value(i, j, k).astype("<i2")  # z, y, x order: x fastest on disk


def world_lps(ijk, origin=ORIGIN, spacing=SPACING, direction=DIRECTION):
    return origin + direction @ (spacing * np.asarray(ijk, dtype=float))


# ---- hand-written files (independent of ITK's writers) -----------------------------------------

def fmt(v):
    return repr(float(v))


def write_nrrd(path, space):
    to_space = np.eye(3) if space == "left-posterior-superior" else LPS_TO_RAS
    origin = to_space @ ORIGIN
    axes = [to_space @ (DIRECTION[:, a] * SPACING[a]) for a in range(3)]
    header = ("NRRD0004\ntype: int16\ndimension: 3\nspace: %s\nsizes: %d %d %d\n"
              "space directions: %s\nkinds: domain domain domain\nendian: little\n"
              "encoding: raw\nspace origin: (%s)\n\n") % (
        space, SIZE[0], SIZE[1], SIZE[2],
        " ".join("(%s)" % ",".join(fmt(c) for c in axis) for axis in axes),
        ",".join(fmt(c) for c in origin))
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(volume_array().tobytes())


def write_mha(path, array=None, origin=ORIGIN, spacing=SPACING, direction=DIRECTION):
    array = volume_array() if array is None else array
    # MetaImage TransformMatrix lists the direction of index axis 0, then axis 1, then axis 2.
    matrix = " ".join(fmt(direction[r, a]) for a in range(3) for r in range(3))
    nz, ny, nx = array.shape
    header = ("ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
              "CompressedData = False\nTransformMatrix = %s\nOffset = %s\n"
              "ElementSpacing = %s\nDimSize = %d %d %d\nElementType = MET_SHORT\n"
              "ElementDataFile = LOCAL\n") % (
        matrix, " ".join(fmt(c) for c in origin), " ".join(fmt(s) for s in spacing), nx, ny, nz)
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(array.astype("<i2").tobytes())


def write_nifti_gz(path):
    """NIfTI-1 with only an sform (scanner RAS): srow = RAS direction * spacing, RAS origin."""
    affine = LPS_TO_RAS @ DIRECTION @ np.diag(SPACING)
    offset = LPS_TO_RAS @ ORIGIN
    hdr = bytearray(348)
    struct.pack_into("<i", hdr, 0, 348)
    struct.pack_into("<8h", hdr, 40, 3, SIZE[0], SIZE[1], SIZE[2], 1, 1, 1, 1)
    struct.pack_into("<hh", hdr, 70, 4, 16)  # DT_INT16, bitpix
    struct.pack_into("<8f", hdr, 76, 1.0, SPACING[0], SPACING[1], SPACING[2], 1, 1, 1, 1)
    struct.pack_into("<f", hdr, 108, 352.0)  # vox_offset
    struct.pack_into("<f", hdr, 112, 1.0)    # scl_slope
    struct.pack_into("<B", hdr, 123, 2)      # xyzt_units: mm
    struct.pack_into("<hh", hdr, 252, 0, 1)  # qform_code 0, sform_code 1 (scanner)
    for row in range(3):
        struct.pack_into("<4f", hdr, 280 + 16 * row, *affine[row], offset[row])
    hdr[344:348] = b"n+1\0"
    with gzip.open(path, "wb") as f:
        f.write(bytes(hdr) + b"\0\0\0\0" + volume_array().tobytes())


# ---- reading through the plugin -----------------------------------------------------------------

class Messages:
    """Errors and warnings of the reader's VTK object, captured instead of printed."""

    def __init__(self, proxy):
        self.errors, self.warnings = [], []
        vtk_object = proxy.GetClientSideObject()
        vtk_object.AddObserver("ErrorEvent", self._on_error)
        vtk_object.AddObserver("WarningEvent", self._on_warning)

    @calldata_type(VTK_STRING)
    def _on_error(self, obj, event, text):
        self.errors.append(text)

    @calldata_type(VTK_STRING)
    def _on_warning(self, obj, event, text):
        self.warnings.append(text)


def open_volume(path, **properties):
    reader = OpenDataFile(path)
    check(reader is not None and reader.GetXMLName().startswith("Anatomical"),
          "%s: OpenDataFile did not pick the VesselTouch reader (%s)"
          % (path, reader.GetXMLName() if reader else None))
    for name, value in properties.items():
        setattr(reader, name, value)
    messages = Messages(reader)
    reader.GetClientSideObject().Modified()  # re-open now that the messages are captured
    reader.UpdatePipeline()
    return reader, sm.Fetch(reader), messages


def check_volume(label, image, origin=ORIGIN, spacing=SPACING, direction=DIRECTION, tol=1e-4):
    check(tuple(image.GetDimensions()) == SIZE, "%s: dimensions %s" % (label, image.GetDimensions()))
    if tuple(image.GetDimensions()) != SIZE:
        return
    got_dir = np.array([[image.GetDirectionMatrix().GetElement(r, c) for c in range(3)]
                        for r in range(3)])
    check(np.allclose(image.GetOrigin(), origin, atol=tol), "%s: origin %s" % (label, image.GetOrigin()))
    check(np.allclose(image.GetSpacing(), spacing, atol=tol), "%s: spacing %s" % (label, image.GetSpacing()))
    check(np.allclose(got_dir, direction, atol=tol), "%s: direction %s" % (label, got_dir.tolist()))
    values = vtk_to_numpy(image.GetPointData().GetScalars())
    for ijk in [(0, 0, 0), (5, 0, 0), (0, 4, 0), (0, 0, 3), (5, 4, 3), (2, 3, 1), (4, 1, 2)]:
        want = world_lps(ijk, origin, spacing, direction)
        got = [0.0, 0.0, 0.0]
        image.TransformIndexToPhysicalPoint(*ijk, got)
        check(np.allclose(got, want, atol=1e-3), "%s: voxel %s at %s, expected %s"
              % (label, ijk, got, want))
        point = image.FindPoint(want)  # world -> voxel through the direction matrix
        check(point == ijk[0] + SIZE[0] * (ijk[1] + SIZE[1] * ijk[2]),
              "%s: world %s found voxel id %d" % (label, want, point))
        check(values[point] == voxel_value(*ijk), "%s: value at %s is %s, expected %s"
              % (label, ijk, values[point], voxel_value(*ijk)))


def test_hand_written_files(tmp):
    files = {"lps.nrrd": lambda p: write_nrrd(p, "left-posterior-superior"),
             "ras.nrrd": lambda p: write_nrrd(p, "right-anterior-superior"),
             "oblique.mha": write_mha,
             "ras-sform.nii.gz": write_nifti_gz}
    for name, write in files.items():
        path = os.path.join(tmp, name)
        write(path)
        reader, image, messages = open_volume(path)
        check(not messages.errors, "%s: errors %s" % (name, messages.errors))
        check(image.GetPointData().GetScalars().GetDataType() == 4,  # VTK_SHORT
              "%s: scalar type %s" % (name, image.GetPointData().GetScalars().GetDataTypeAsString()))
        check_volume(name, image)
    # RAS output: the same voxels, x and y negated.
    reader, image, _ = open_volume(os.path.join(tmp, "ras-sform.nii.gz"), OutputFrame=1)
    check_volume("ras-sform.nii.gz in RAS", image, LPS_TO_RAS @ ORIGIN, SPACING,
                 LPS_TO_RAS @ DIRECTION)


def test_itk_written_files(tmp):
    for name in ["itk.nrrd", "itk.nhdr", "itk.nii", "itk.nii.gz", "itk.mha", "itk.mhd"]:
        path = os.path.join(tmp, name)
        geometry = itk_write("volume", path, "oblique", "int16")
        check(np.allclose(np.array(geometry["direction"]).reshape(3, 3), DIRECTION),
              "test writer geometry differs from this test's")
        _, image, messages = open_volume(path)
        check(not messages.errors, "%s: errors %s" % (name, messages.errors))
        check_volume(name, image)
    for pixel, vtk_type in [("int8", 15), ("uint8", 3), ("uint16", 5), ("int32", 6),
                            ("uint32", 7), ("float", 10), ("double", 11)]:
        path = os.path.join(tmp, "type-%s.mha" % pixel)
        itk_write("volume", path, "axial", pixel)
        _, image, _ = open_volume(path)
        scalars = image.GetPointData().GetScalars()
        check(scalars is not None and scalars.GetDataType() == vtk_type,
              "%s: VTK type %s, expected %d" % (pixel, scalars and scalars.GetDataType(), vtk_type))


def test_value_range_cache(tmp):
    """The reader computes each piece's range and finite range as it reads and hands them to VTK's
    range cache (vtkVesselTouchImageReader::CacheValueRange): the ranges ParaView then reads are
    those of the voxels, and come from the cache, not from VTK's slow scan."""
    from vtkmodules.vtkCommonCore import vtkAbstractArray
    name = "range.nrrd"
    path = os.path.join(tmp, name)
    write_nrrd(path, "left-posterior-superior")
    reader, _, _ = open_volume(path)
    algorithm = reader.GetClientSideObject()
    algorithm.Modified()
    algorithm.Update()  # a fresh read that nothing has asked a range of yet
    scalars = algorithm.GetOutputDataObject(0).GetPointData().GetScalars()
    info = scalars.GetInformation()
    check(info.Has(vtkAbstractArray.PER_COMPONENT()) and
          info.Has(vtkAbstractArray.PER_FINITE_COMPONENT()),
          "%s: the reader did not cache the range and the finite range" % name)
    want = volume_array()
    check(tuple(scalars.GetRange(0)) == (float(want.min()), float(want.max())),
          "%s: range %s, the voxels span %s..%s" % (name, scalars.GetRange(0), want.min(), want.max()))
    check(tuple(scalars.GetFiniteRange(0)) == (float(want.min()), float(want.max())),
          "%s: finite range %s" % (name, scalars.GetFiniteRange(0)))
    data_range = reader.GetDataInformation().GetPointDataInformation().GetArrayInformation(
        scalars.GetName()).GetComponentRange(0)
    check(tuple(data_range) == (float(want.min()), float(want.max())),
          "%s: ParaView's data information range %s" % (name, tuple(data_range)))
    # Floating voxels: NaN never counts, infinities only in the plain range.
    floats = want.astype("<f4")
    floats[0, 0, 0] = np.nan
    floats[1, 1, 1] = np.inf
    floats[2, 2, 2] = -1000.25  # the smallest, off the integer grid
    fpath = os.path.join(tmp, "range-float.nrrd")
    with open(fpath, "wb") as f:
        f.write(("NRRD0004\ntype: float\ndimension: 3\nsizes: %d %d %d\nencoding: raw\n"
                 "endian: little\n\n" % SIZE).encode("ascii"))
        f.write(floats.tobytes())
    freader, _, _ = open_volume(fpath)
    fscalars = freader.GetClientSideObject().GetOutputDataObject(0).GetPointData().GetScalars()
    finite = floats[np.isfinite(floats)]
    check(tuple(fscalars.GetRange(0)) == (float(finite.min()), float("inf")),
          "float volume: range %s, expected (%s, inf)" % (fscalars.GetRange(0), finite.min()))
    check(tuple(fscalars.GetFiniteRange(0)) == (float(finite.min()), float(finite.max())),
          "float volume: finite range %s, expected (%s, %s)"
          % (fscalars.GetFiniteRange(0), finite.min(), finite.max()))
    Delete(freader)
    Delete(reader)


def test_dicom_series(tmp):
    folder = os.path.join(tmp, "dicom")
    itk_write("dicom", folder, "1.2.826.0.1.3680043.2.1125.9.1", "oblique", -1, "IM", 6, 5, 4,
              ".dcm")
    # One file (its series is read) and the folder (through the proxy: a folder has no extension).
    _, image, messages = open_volume(os.path.join(folder, "IM0001.dcm"))
    check(not messages.errors, "DICOM file: errors %s" % messages.errors)
    check_volume("DICOM series from a file", image)
    reader = VesselTouchDICOMSeriesReader(FileName=folder)
    messages = Messages(reader)
    reader.UpdatePipeline()
    check_volume("DICOM series from its folder", sm.Fetch(reader))

    # A second, smaller series in the same folder.
    itk_write("dicom", folder, "1.2.826.0.1.3680043.2.1125.9.2", "axial", -1, "B", 6, 5, 3)
    reader = VesselTouchDICOMSeriesReader()
    messages = Messages(reader)
    reader.FileName = folder
    reader.UpdatePipeline()
    reader.UpdatePropertyInformation()
    uids = list(reader.GetProperty("SeriesInstanceUIDInfo"))
    check(uids == ["1.2.826.0.1.3680043.2.1125.9.1", "1.2.826.0.1.3680043.2.1125.9.2"],
          "series listed: %s" % uids)
    check(any("2 DICOM series" in w for w in messages.warnings),
          "no warning about two series: %s" % messages.warnings)
    check(sm.Fetch(reader).GetDimensions()[2] == 4, "the largest series was not read")
    reader.SeriesInstanceUID = "1.2.826.0.1.3680043.2.1125.9.2"
    reader.UpdatePipeline()
    image = sm.Fetch(reader)
    check(tuple(image.GetDimensions()) == (6, 5, 3), "series by UID: %s" % (image.GetDimensions(),))


def probe_world(image, points):
    """Trilinear values of `image` at world points, through its origin, spacing and direction."""
    dims = np.array(image.GetDimensions())
    values = vtk_to_numpy(image.GetPointData().GetScalars()).reshape(dims[::-1])  # z, y, x
    direction = np.array([[image.GetDirectionMatrix().GetElement(r, c) for c in range(3)]
                          for r in range(3)])
    index = (np.linalg.inv(direction) @ (points - np.array(image.GetOrigin())).T).T
    index /= np.array(image.GetSpacing())
    out = np.full(len(points), np.inf)
    for n, (x, y, z) in enumerate(index):
        i0 = np.floor([x, y, z]).astype(int)
        if np.any(i0 < 0) or np.any(i0 + 1 >= dims):
            continue
        f = np.array([x, y, z]) - i0
        cube = values[i0[2]:i0[2] + 2, i0[1]:i0[1] + 2, i0[0]:i0[0] + 2]
        wz = np.array([1 - f[2], f[2]])[:, None, None]
        wy = np.array([1 - f[1], f[1]])[None, :, None]
        wx = np.array([1 - f[0], f[0]])[None, None, :]
        out[n] = float(np.sum(cube * wz * wy * wx))
    return out


def test_vmtk_aorta():
    folder = os.path.join(SHARED, "vmtk-aorta")
    _, levelset, messages = open_volume(os.path.join(folder, "aorta-final-levelset.mha"))
    check(not messages.errors, "aorta level set: %s" % messages.errors)
    _, ct, _ = open_volume(os.path.join(folder, "aorta.mha"))
    check(tuple(ct.GetDimensions()) == (157, 393, 34), "aorta dims %s" % (ct.GetDimensions(),))
    centerline = XMLPolyDataReader(FileName=[os.path.join(folder, "aorta-centerline.vtp")])
    points_ras = vtk_to_numpy(sm.Fetch(centerline).GetPoints().GetData()).astype(float)
    check(len(points_ras) == 409, "centerline points: %d" % len(points_ras))

    # VMTK wrote the centerline in RAS; the reader gives LPS: the documented conversion.
    inside_lps = np.mean(probe_world(levelset, points_ras @ LPS_TO_RAS.T) < 0)
    check(inside_lps == 1.0, "aorta: %.1f %% of the centerline in the vessel (LPS)"
          % (100 * inside_lps))
    # RAS output: the centerline as VMTK wrote it.
    _, levelset_ras, _ = open_volume(os.path.join(folder, "aorta-final-levelset.mha"), OutputFrame=1)
    inside_ras = np.mean(probe_world(levelset_ras, points_ras) < 0)
    check(inside_ras == 1.0, "aorta: %.1f %% of the centerline in the vessel (RAS)"
          % (100 * inside_ras))
    # Without the conversion the centerline misses the vessel: the check above can fail.
    wrong = np.mean(probe_world(levelset, points_ras) < 0)
    print("aorta: centerline inside the vessel: %.1f %% (LPS image, centerline RAS->LPS), "
          "%.1f %% (RAS image), %.1f %% (no conversion)"
          % (100 * inside_lps, 100 * inside_ras, 100 * wrong))
    check(wrong < 0.05, "aorta: %.1f %% inside with no RAS->LPS conversion" % (100 * wrong))


def test_bad_input(tmp):
    def cut(path):
        size = os.path.getsize(path)
        with open(path, "r+b") as f:
            f.truncate(size * 2 // 3)

    cases = []
    itk_write("bad2d", os.path.join(tmp, "flat.mha"))
    cases.append(("flat.mha", "2D image"))
    itk_write("bad4d", os.path.join(tmp, "time.nrrd"))
    cases.append(("time.nrrd", "4D image"))
    itk_write("badvector", os.path.join(tmp, "vector.mha"))
    cases.append(("vector.mha", "3 components"))
    itk_write("volume", os.path.join(tmp, "long.nrrd"), "axial", "int64")
    cases.append(("long.nrrd", "unsupported pixel type"))
    for name in ["cut.nii.gz", "cut.mha", "cut.nrrd", "cut.nii"]:
        itk_write("volume", os.path.join(tmp, name), "axial", "int16", 40, 40, 20)
        cut(os.path.join(tmp, name))
        cases.append((name, "truncated" if "nrrd" not in name else "cannot read"))
    with open(os.path.join(tmp, "junk.nhdr"), "w") as f:
        f.write("NRRD0004\nthis: is not\na header\n")
    cases.append(("junk.nhdr", "NRRD"))
    itk_write("dicom", os.path.join(tmp, "gap"), "1.2.826.0.1.3680043.2.1125.9.3", "axial", 2,
              "IM", 6, 5, 6)
    cases.append(("gap/IM0000", "missing slice"))
    cases.append(("missing.nii.gz", "does not exist"))

    readers = {"mha": VesselTouchMetaImageReader, "nrrd": VesselTouchNRRDReader,
               "nhdr": VesselTouchNRRDReader, "gz": VesselTouchNIfTIReader,
               "nii": VesselTouchNIfTIReader}
    for name, expected in cases:
        path = os.path.join(tmp, name)
        make = readers.get(name.rsplit(".", 1)[-1], VesselTouchDICOMSeriesReader)
        reader = make()
        messages = Messages(reader)
        reader.FileName = path
        reader.UpdatePipeline()
        image = sm.Fetch(reader)
        text = " | ".join(messages.errors)
        check(any(expected in e for e in messages.errors),
              "%s: expected an error with '%s', got: %s" % (name, expected, text or "none"))
        check(image.GetNumberOfPoints() == 0, "%s: output not empty" % name)
        shown = text.split("VesselTouch reader: ", 1)[-1].strip()
        print("bad input %-14s -> %s" % (name, shown[:150]))


def main():
    tmp = tempfile.mkdtemp(prefix="vtouch-readers-")
    try:
        test_hand_written_files(tmp)
        test_itk_written_files(tmp)
        test_value_range_cache(tmp)
        test_dicom_series(tmp)
        test_vmtk_aorta()
        test_bad_input(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    if FAILURES:
        print("%d failure(s)" % len(FAILURES))
        return 1
    print("test_readers: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
