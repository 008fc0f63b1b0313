"""Centerline accuracy against a ground-truth vessel tree (issue 16, item 5). NumPy + SciPy only,
so that pvpython, /usr/bin/python3 and the tests all import it.

    m = measure(extracted_mm, extracted_lines, truth_mm, truth_radius_mm, truth_lines, voxel_mm)

extracted_mm: (N, 3) world points; extracted_lines: list of index arrays (polylines), or None for
a point set (e.g. skeleton voxels). truth_*: the phantom's port 1 (one polyline per vessel,
"Radius" in mm). Every length below is measured along the curves: polylines are resampled every
0.05 voxel (truth) and 0.25 voxel (extraction), so dense and sparse outputs weigh alike.

Measures (distances in voxels of the smallest spacing, tolerance TOLERANCE_VOX = 1.5):
  precision                fraction of the extracted centerline within 1.5 voxels of a true axis
  recall_<class>           fraction of the true axis whose radius is in the class that lies within
                           max(1.5 voxels, radius) of the extraction; classes (radius in voxels)
                           r0.5_0.6, r0.6_0.75, r0.75_1, r1_2, r2_up; recall_all over all radii,
                           recall_r0.5_up and recall_r1_up over r >= 0.5 and r >= 1 voxel
  mean_dist_vox            mean distance of the matched extraction (within 1.5 voxels) to the
                           true axis: the localisation; mean_dist_all_vox over all of it, and
                           p95_dist_vox its 95th percentile
  false_vessel_points      extracted points (as given, not resampled) more than 1.5 voxels outside
                           every true vessel (distance to the axis minus the radius there);
                           false_vessel_length_vox the extracted length there
  extracted_length_vox, truth_length_vox
"""
import math

import numpy as np

TOLERANCE_VOX = 1.5
RADIUS_CLASSES = (("r0.5_0.6", 0.5, 0.6), ("r0.6_0.75", 0.6, 0.75), ("r0.75_1", 0.75, 1.0),
                  ("r1_2", 1.0, 2.0), ("r2_up", 2.0, math.inf))


def resample(points, lines, step, values=None):
    """Points every <= step along each polyline (and linearly interpolated values); a point set
    (lines None) is returned as is. Returns (points, values)."""
    points = np.asarray(points, float).reshape(-1, 3)
    if lines is None:
        return points, (None if values is None else np.asarray(values, float))
    out, vals = [], []
    for line in lines:
        line = np.asarray(line, int)
        if len(line) == 0:
            continue
        p = points[line]
        v = None if values is None else np.asarray(values, float)[line]
        out.append(p[:1])
        if v is not None:
            vals.append(v[:1])
        if len(line) < 2:
            continue
        seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
        counts = np.maximum(1, np.ceil(seg / step).astype(int))
        for i, c in enumerate(counts):
            t = (np.arange(1, c + 1) / c)[:, None]
            out.append(p[i] + (p[i + 1] - p[i]) * t)
            if v is not None:
                vals.append(v[i] + (v[i + 1] - v[i]) * t[:, 0])
    if not out:
        return np.zeros((0, 3)), (None if values is None else np.zeros(0))
    return np.vstack(out), (None if values is None else np.concatenate(vals))


def polyline_length(points, lines):
    points = np.asarray(points, float).reshape(-1, 3)
    if lines is None:
        return float(len(points))
    return float(sum(np.linalg.norm(np.diff(points[np.asarray(l, int)], axis=0), axis=1).sum()
                     for l in lines if len(l) > 1))


def outside_distance(points, truth, radius, voxel_mm):
    """For each point: min over the true axis of (distance - radius there), in mm. Exact to the
    truth's sampling: the axis is split in radius bins of 0.05 voxel, one k-d tree per bin."""
    from scipy.spatial import cKDTree

    best = np.full(len(points), np.inf)
    if len(points) == 0 or len(truth) == 0:
        return best
    bins = np.floor(radius / (0.05 * voxel_mm)).astype(int)
    for b in np.unique(bins):
        sel = bins == b
        d, i = cKDTree(truth[sel]).query(points)
        best = np.minimum(best, d - radius[sel][i])
    return best


def measure(extracted_mm, extracted_lines, truth_mm, truth_radius_mm, truth_lines, voxel_mm):
    from scipy.spatial import cKDTree

    tol = TOLERANCE_VOX * voxel_mm
    truth, radius = resample(truth_mm, truth_lines, 0.05 * voxel_mm, truth_radius_mm)
    given = np.asarray(extracted_mm, float).reshape(-1, 3)
    ext, _ = resample(given, extracted_lines, 0.25 * voxel_mm)
    result = {"extracted_points": int(len(given)),
              "extracted_length_vox": polyline_length(given, extracted_lines) / voxel_mm
              if extracted_lines is not None else float(len(given)),
              "truth_length_vox": polyline_length(truth_mm, truth_lines) / voxel_mm}
    if len(ext) == 0:
        result.update(precision=0.0, mean_dist_vox=math.nan, mean_dist_all_vox=math.nan,
                      p95_dist_vox=math.nan, false_vessel_points=0, false_vessel_length_vox=0.0,
                      recall_all=0.0, recall_r1_up=0.0)
        result["recall_r0.5_up"] = 0.0
        for name, _, _ in RADIUS_CLASSES:
            result["recall_" + name] = 0.0
        return result
    d_ext, _ = cKDTree(truth).query(ext)
    matched = d_ext <= tol
    result["precision"] = float(matched.mean())
    result["mean_dist_vox"] = float(d_ext[matched].mean() / voxel_mm) if matched.any() else math.nan
    result["mean_dist_all_vox"] = float(d_ext.mean() / voxel_mm)
    result["p95_dist_vox"] = float(np.percentile(d_ext, 95) / voxel_mm)
    # Recall: true axis within max(1.5 voxels, radius) of the extraction.
    d_truth, _ = cKDTree(ext).query(truth)
    covered = d_truth <= np.maximum(tol, radius)
    r_vox = radius / voxel_mm
    for name, lo, hi in RADIUS_CLASSES:
        sel = (r_vox >= lo - 1e-9) & (r_vox < hi - 1e-9)
        result["recall_" + name] = float(covered[sel].mean()) if sel.any() else math.nan
    result["recall_all"] = float(covered.mean())
    sel = r_vox >= 0.5 - 1e-9
    result["recall_r0.5_up"] = float(covered[sel].mean()) if sel.any() else math.nan
    sel = r_vox >= 1.0 - 1e-9
    result["recall_r1_up"] = float(covered[sel].mean()) if sel.any() else math.nan
    # False vessels: extraction outside every true vessel by more than the tolerance.
    out_given = outside_distance(given, truth, radius, voxel_mm)
    result["false_vessel_points"] = int((out_given > tol).sum())
    out_ext = outside_distance(ext, truth, radius, voxel_mm)
    result["false_vessel_length_vox"] = float((out_ext > tol).sum() * 0.25)
    return result


def coverage(extracted_mm, extracted_lines, reference_mm, within_mm, step_mm):
    """Fraction of the reference points within within_mm of the (resampled) extraction."""
    from scipy.spatial import cKDTree

    ext, _ = resample(extracted_mm, extracted_lines, step_mm)
    if len(ext) == 0:
        return 0.0
    d, _ = cKDTree(ext).query(np.asarray(reference_mm, float).reshape(-1, 3))
    return float((d <= within_mm).mean())


def otsu_threshold(values, bins=256):
    """Otsu's threshold (N. Otsu, IEEE Trans. SMC 9:62, 1979: the threshold maximising the
    between-class variance) on a 256-bin histogram, as skimage.filters.threshold_otsu computes it."""
    values = np.asarray(values).ravel()
    hist, edges = np.histogram(values, bins=bins, range=(float(values.min()), float(values.max())))
    centres = (edges[:-1] + edges[1:]) / 2
    hist = hist.astype(float)
    w1 = np.cumsum(hist)
    w2 = np.cumsum(hist[::-1])[::-1]
    m1 = np.cumsum(hist * centres) / np.maximum(w1, 1e-300)
    m2 = (np.cumsum((hist * centres)[::-1]) / np.maximum(w2[::-1], 1e-300))[::-1]
    variance = w1[:-1] * w2[1:] * (m1[:-1] - m2[1:]) ** 2
    return float(centres[:-1][np.argmax(variance)])


# Vessels fill a few per cent of an angiogram at most: a mask above this fraction means Otsu's
# threshold split the background tissue (its two classes are dark and bright tissue, not tissue
# and vessels; this happens when the vessels are too few to weigh in the histogram).
MAXIMUM_VESSEL_FRACTION = 0.05


def vessel_threshold(volume):
    """(threshold, method): Otsu's threshold when it keeps at most MAXIMUM_VESSEL_FRACTION of the
    volume ("otsu"); else Otsu again on the voxels above it, until the mask is that small
    ("otsu_upper", at most four times: Otsu restricted to the upper class, the idea of H. Cai et
    al.'s iterative triclass thresholding, IEEE Trans. Image Process. 23:1038, 2014)."""
    values = np.asarray(volume).ravel()
    t = otsu_threshold(values)
    method = "otsu"
    for _ in range(4):
        upper = values[values > t]
        if len(upper) <= MAXIMUM_VESSEL_FRACTION * len(values) or len(upper) < 2:
            break
        t = otsu_threshold(upper)
        method = "otsu_upper"
    return t, method


def vtk_lines(poly):
    """(points (N, 3), list of index arrays) of a vtkPolyData's polylines (VTK 9)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    if poly is None or poly.GetNumberOfPoints() == 0:
        return np.zeros((0, 3)), []
    points = vtk_to_numpy(poly.GetPoints().GetData()).astype(float)
    cells = poly.GetLines()
    offsets = vtk_to_numpy(cells.GetOffsetsArray()).astype(int)
    conn = vtk_to_numpy(cells.GetConnectivityArray()).astype(int)
    return points, [conn[offsets[i]:offsets[i + 1]] for i in range(len(offsets) - 1)]
