#!/usr/bin/python3
"""Unit tests of Utilities/bench/centerline_metrics.py (ctest Bench.CenterlineMetrics): the
measures the raw-angiogram benchmark and ParaView.RawAngiogramCenterlineAccuracy rely on, on
geometry whose answers are known."""
import os
import sys
import unittest

import numpy as np

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import centerline_metrics as cm  # noqa: E402


def line(a, b):
    return np.array([a, b], float), [np.array([0, 1])]


class CenterlineMetrics(unittest.TestCase):
    def test_offset_copy_of_the_axis_is_precise_complete_and_localised(self):
        truth, tl = line([0, 0, 0], [100, 0, 0])
        ext, el = line([0, 0.2, 0], [100, 0.2, 0])
        m = cm.measure(ext, el, truth, np.array([1.0, 1.0]), tl, 1.0)
        self.assertEqual(m["precision"], 1.0)
        self.assertEqual(m["recall_r1_2"], 1.0)
        self.assertAlmostEqual(m["mean_dist_vox"], 0.2, places=6)
        self.assertEqual(m["false_vessel_points"], 0)
        self.assertAlmostEqual(m["extracted_length_vox"], 100.0)

    def test_spur_outside_the_vessel_lowers_precision_by_its_length_and_counts_as_false(self):
        truth, tl = line([0, 0, 0], [100, 0, 0])
        ext = np.array([[0, 0, 0], [100, 0, 0], [50, 10, 0], [50, 35, 0]], float)
        m = cm.measure(ext, [np.array([0, 1]), np.array([2, 3])], truth, np.array([1.0, 1.0]),
                       tl, 1.0)
        self.assertAlmostEqual(m["precision"], 100.0 / 125.0, delta=0.01)
        self.assertEqual(m["false_vessel_points"], 2)
        self.assertAlmostEqual(m["false_vessel_length_vox"], 25.0, delta=0.6)
        self.assertLess(m["mean_dist_vox"], 1e-9)  # the matched part lies on the axis
        self.assertGreater(m["mean_dist_all_vox"], 3.0)

    def test_recall_is_per_radius_class_and_tolerance_grows_with_the_radius(self):
        truth = np.array([[0, 0, 0], [50, 0, 0], [0, 20, 0], [50, 20, 0]], float)
        radius = np.array([0.55, 0.55, 3.0, 3.0])
        tl = [np.array([0, 1]), np.array([2, 3])]
        # Only the thick vessel, 2.5 voxels off its axis: within its radius (3), so covered.
        ext, el = line([0, 22.5, 0], [50, 22.5, 0])
        m = cm.measure(ext, el, truth, radius, tl, 1.0)
        self.assertEqual(m["recall_r0.5_0.6"], 0.0)
        self.assertEqual(m["recall_r2_up"], 1.0)
        self.assertTrue(np.isnan(m["recall_r1_2"]))  # no vessel in that class
        self.assertAlmostEqual(m["recall_all"], 0.5, delta=0.01)
        # Inside the thick vessel's wall: not within 1.5 voxels of the axis, yet not false.
        self.assertEqual(m["precision"], 0.0)
        self.assertEqual(m["false_vessel_points"], 0)

    def test_sparse_and_dense_extractions_weigh_alike(self):
        truth, tl = line([0, 0, 0], [100, 0, 0])
        sparse = np.array([[0, 0.5, 0], [100, 0.5, 0], [100, 0.5, 0], [100, 30.5, 0]], float)
        dense = np.vstack([np.c_[np.arange(0, 101), np.full(101, 0.5), np.zeros(101)],
                           np.c_[np.full(31, 100), np.arange(0, 31) + 0.5, np.zeros(31)]])
        a = cm.measure(sparse, [np.array([0, 1]), np.array([2, 3])], truth, np.ones(2), tl, 1.0)
        b = cm.measure(dense, [np.arange(101), np.arange(101, 132)], truth, np.ones(2), tl, 1.0)
        self.assertAlmostEqual(a["precision"], b["precision"], delta=0.005)
        self.assertAlmostEqual(a["precision"], 101.0 / 130.0, delta=0.01)

    def test_distances_are_in_voxels_of_the_smallest_spacing(self):
        truth, tl = line([0, 0, 0], [50, 0, 0])
        ext, el = line([0, 0.6, 0], [50, 0.6, 0])  # 0.6 mm = 1.2 voxels of 0.5 mm
        m = cm.measure(ext, el, truth, np.array([1.0, 1.0]), tl, 0.5)
        self.assertAlmostEqual(m["mean_dist_vox"], 1.2, places=6)
        self.assertEqual(m["precision"], 1.0)
        ext, el = line([0, 0.8, 0], [50, 0.8, 0])  # 1.6 voxels: beyond the tolerance
        self.assertEqual(cm.measure(ext, el, truth, np.array([1.0, 1.0]), tl, 0.5)["precision"],
                         0.0)

    def test_empty_extraction_has_zero_precision_and_recall(self):
        truth, tl = line([0, 0, 0], [10, 0, 0])
        m = cm.measure(np.zeros((0, 3)), [], truth, np.array([1.0, 1.0]), tl, 1.0)
        self.assertEqual(m["precision"], 0.0)
        self.assertEqual(m["recall_r0.5_up"], 0.0)
        self.assertEqual(m["false_vessel_points"], 0)

    def test_coverage_of_a_reference(self):
        reference = np.c_[np.arange(10.0), np.zeros(10), np.zeros(10)]
        ext, el = line([0, 0.9, 0], [4, 0.9, 0])
        self.assertAlmostEqual(cm.coverage(ext, el, reference, 1.0, 0.25), 0.5)

    def test_otsu_threshold_separates_two_modes_like_skimage(self):
        rng = np.random.default_rng(3)
        values = np.r_[rng.normal(400, 30, 50000), rng.normal(1000, 30, 2000)]
        t = cm.otsu_threshold(values)
        self.assertGreater(t, 500)
        self.assertLess(t, 900)
        try:
            from skimage.filters import threshold_otsu
        except ImportError:
            return
        self.assertAlmostEqual(t, float(threshold_otsu(values)), places=6)

    def test_vessel_threshold_applies_otsu_again_above_it_when_otsu_splits_the_tissue(self):
        rng = np.random.default_rng(4)
        # Broad tissue and few vessels: Otsu's two classes split the tissue.
        values = np.r_[rng.normal(400, 60, 200000), rng.normal(1000, 30, 1500)]
        self.assertGreater((values > cm.otsu_threshold(values)).mean(), 0.2)
        t, method = cm.vessel_threshold(values)
        self.assertEqual(method, "otsu_upper")
        self.assertGreater(t, 600)
        self.assertLess(t, 950)
        # Two clean modes: plain Otsu.
        values = np.r_[rng.normal(400, 20, 100000), rng.normal(1000, 20, 2000)]
        self.assertEqual(cm.vessel_threshold(values)[1], "otsu")

if __name__ == "__main__":
    unittest.main()
