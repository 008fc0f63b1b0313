"""The topology and geometry of a VesselCenterline output, for comparing two runs (issue 19).

A distributed run stitches each rank's clipped paths, so its path decomposition may differ from a
single-process run's (a path that a single run traced from one tip to the root can come out as
two paths joined at a junction that is the same point): the comparison is of the network, not of
the path list. ``graph(polydata)`` gives:
- ``ends``: path ends that are neither attached to another path nor a junction's parent point;
- ``junctions``: distinct junction points (parent points, merged within half a voxel);
- ``bifurcations``: the junction points where three or more branches meet (positions);
- ``cycles``: independent loops, junctions - paths + connected parts;
- ``paths`` and ``points`` (N x 3).
"""

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy


def _field(polydata, name):
    a = polydata.GetFieldData().GetArray(name)
    return [] if a is None else [int(a.GetComponent(i, 0)) for i in range(a.GetNumberOfTuples())]


def graph(polydata, voxel_mm):
    points = (vtk_to_numpy(polydata.GetPoints().GetData()) if polydata.GetPoints()
              else np.zeros((0, 3)))
    lines = polydata.GetLines()
    offsets = vtk_to_numpy(lines.GetOffsetsArray()) if lines.GetNumberOfCells() else [0]
    ids = vtk_to_numpy(lines.GetConnectivityArray()) if lines.GetNumberOfCells() else []
    chains = [points[ids[a:b]] for a, b in zip(offsets[:-1], offsets[1:])]
    head, tail = _field(polydata, "PathHeadJunction"), _field(polydata, "PathTailJunction")
    child, parent = _field(polydata, "JunctionChildPath"), _field(polydata, "JunctionParentPath")
    parent_point = _field(polydata, "JunctionParentPoint")
    parents = set(zip(parent, parent_point))
    end_points = []
    for p, chain in enumerate(chains):
        if head[p] < 0 and (p, 0) not in parents:
            end_points.append(chain[0])
        if tail[p] < 0 and (p, len(chain) - 1) not in parents:
            end_points.append(chain[-1])
    ends = len(end_points)
    # Junction points, merged within half a voxel (two paths attached at one point: one node),
    # and their degree: branches leaving the node (2 per path running through it, 1 per path
    # ending there). A node of degree 2 only joins two paths of one vessel (where a single run's
    # fronts met, or a stitched loop closes): not a bifurcation.
    nodes = []
    for p, i in parents:
        x = chains[p][i]
        if not any(np.linalg.norm(x - y) <= 0.5 * voxel_mm for y in nodes):
            nodes.append(x)
    bifurcations = []
    for x in nodes:
        degree = 0
        for chain in chains:
            near = np.nonzero(np.linalg.norm(chain - x, axis=1) <= 0.5 * voxel_mm)[0]
            if len(near) == 0:
                continue
            ends_near = {0, len(chain) - 1} & set(int(i) for i in near)
            through = len(set(int(i) for i in near) - ends_near) > 0
            degree += len(ends_near) + (2 if through else 0)
        if degree >= 3:
            bifurcations.append(x)
    root = list(range(len(chains)))

    def find(a):
        while root[a] != a:
            a = root[a]
        return a
    for c, p in zip(child, parent):
        root[find(c)] = find(p)
    parts = sum(1 for i in range(len(chains)) if find(i) == i)
    return {"paths": len(chains), "ends": ends, "end_points": end_points, "junctions": len(nodes),
            "bifurcations": bifurcations,
            "cycles": len(child) - len(chains) + parts, "points": points, "chains": chains,
            "parents": sorted(parents)}


def farthest_point_voxels(a, b, voxel_mm):
    """The largest distance from a point of `a` to its nearest point of `b`, in voxels."""
    if len(a) == 0 or len(b) == 0:
        return float("inf")
    worst = 0.0
    for start in range(0, len(a), 512):
        block = a[start:start + 512]
        d = np.sqrt(((block[:, None, :] - b[None, :, :]) ** 2).sum(axis=2)).min(axis=1)
        worst = max(worst, float(d.max()))
    return worst / voxel_mm
