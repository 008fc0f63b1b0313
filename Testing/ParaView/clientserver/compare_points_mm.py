"""How far a distributed run's points are from the single run's, to the last bit (issue 19 item 2).

    pvpython Testing/ParaView/clientserver/compare_points_mm.py SINGLE.vtp OTHER.vtp [...]

For each OTHER (measure_cs_topology.py --save PREFIX writes PREFIX_r<ranks>.vtp) against SINGLE:
the points, the largest distance from a point to the nearest point of the other run either way
(mm, printed with 3 significant digits: 0 is bit for bit), the points with an exact twin
(distance 0) either way, and where the largest departure lies. A measurement: nothing asserted.
"""

import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader


def points(path):
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    return vtk_to_numpy(reader.GetOutput().GetPoints().GetData()).astype(np.float64)


def nearest(a, b):
    """For each point of `a`, the distance (mm) to the nearest point of `b`."""
    out = np.empty(len(a))
    for start in range(0, len(a), 512):
        block = a[start:start + 512]
        out[start:start + 512] = np.sqrt(((block[:, None, :] - b[None, :, :]) ** 2).sum(axis=2)).min(axis=1)
    return out


def main(argv):
    if len(argv) < 3:
        print(__doc__)
        return 2
    single = points(argv[1])
    for other_path in argv[2:]:
        other = points(other_path)
        there, back = nearest(other, single), nearest(single, other)
        worst = int(np.argmax(there))
        print(f"{other_path}: {len(other)} points for {len(single)}; farthest {there.max():.3g} / "
              f"{back.max():.3g} mm; exact twins {int((there == 0).sum())} / {int((back == 0).sum())}; "
              f"farthest at {other[worst].round(2).tolist()} mm")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
