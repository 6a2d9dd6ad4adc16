#!/usr/bin/python3
"""Unit tests of scripts/plotting/voronoi.py (`throng plot --density voronoi`, docs/plot.md) on
hand-made frames whose Voronoi densities are known (ctest: plot_voronoi): two agents sharing a room,
a lone agent's cut-off circle, a lattice, non-walkable ground left out, the mean over frames; and
the Voronoi speed (`--speed voronoi`) on cells whose shares are known. Needs
numpy and pandas (Debian's python3-numpy, python3-pandas): /usr/bin/python3."""
import importlib.util
import math
import os
import sys
import unittest

try:
    import numpy as np
    import pandas as pd
except ImportError:
    sys.exit("plot_voronoi_test: numpy or pandas is missing: apt-get install python3-numpy python3-pandas")

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
# plotting.geometry imports python/throng/analysis.py as throng_analysis (scripts/plot.py loads it so).
_spec = importlib.util.spec_from_file_location("throng_analysis", os.path.join(ROOT, "python", "throng", "analysis.py"))
sys.modules["throng_analysis"] = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(sys.modules["throng_analysis"])
from plotting import geometry as G  # noqa: E402
from plotting import voronoi as V  # noqa: E402


def frames(*positions):
    """A trajectory table: frame k holds the agents at positions[k] (a list of (x, y))."""
    rows = [(k, i, x, y) for k, ps in enumerate(positions) for i, (x, y) in enumerate(ps)]
    return pd.DataFrame(rows, columns=["frame", "id", "x", "y"])


def room(w, h):
    return [np.array([[0, 0], [w, 0], [w, h], [0, h]], float)]


class VoronoiDensity(unittest.TestCase):
    def density(self, traj, w, h, cell=1.0, rings=None, cutoff=10.0):
        xs, ys = G.grid((0.0, 0.0, float(w), float(h)), cell)
        d, used = V.voronoi_density(traj, xs, ys, room(w, h) if rings is None else rings, G.inside_walkable,
                                    cutoff=cutoff, per_cell=4)
        return d, used

    def test_two_agents_share_a_room_by_halves(self):
        d, used = self.density(frames([(1, 1), (3, 1)]), 4, 2)
        self.assertEqual(used, 1)
        np.testing.assert_allclose(d, np.full((4, 2), 0.25), atol=1e-9)

    def test_a_lone_agent_owns_its_cut_off_circle(self):
        d, _ = self.density(frames([(10, 10)]), 20, 20, cutoff=2.0)
        self.assertAlmostEqual(d.sum(), 1.0, places=9)
        self.assertEqual(d[0, 0], 0.0)
        self.assertEqual(d[13, 10], 0.0)
        self.assertAlmostEqual(d[10, 10], 1 / (math.pi * 4), delta=0.01)

    def test_a_half_metre_lattice_reads_four_per_square_metre(self):
        pts = [(0.25 + a * 0.5, 0.25 + b * 0.5) for a in range(20) for b in range(20)]
        d, _ = self.density(frames(pts), 10, 10, cutoff=2.0)
        np.testing.assert_allclose(d, np.full((10, 10), 4.0), atol=1e-9)

    def test_ground_outside_the_walkable_area_belongs_to_nobody(self):
        # The walkable area is the left half of a 4 x 2 m box: one agent owns 4 m^2, a quarter per cell.
        d, _ = self.density(frames([(1, 1)]), 4, 2, rings=room(2, 2))
        np.testing.assert_allclose(d[:2], np.full((2, 2), 0.25), atol=1e-9)
        np.testing.assert_allclose(d[2:], 0.0)

    def test_frames_are_averaged_and_thinned_to_at_most_max_frames(self):
        d, used = self.density(frames([(1, 1), (3, 1)], [(2, 1)]), 4, 2)
        self.assertEqual(used, 2)
        np.testing.assert_allclose(d, np.full((4, 2), (0.25 + 0.125) / 2), atol=1e-9)
        xs, ys = G.grid((0.0, 0.0, 4.0, 2.0), 1.0)
        _, used = V.voronoi_density(frames(*[[(1, 1)]] * 30), xs, ys, room(4, 2), G.inside_walkable, max_frames=7)
        self.assertEqual(used, 7)


class VoronoiSpeed(unittest.TestCase):
    """voronoi_speed: sum_i v_i |V_i & M| / sum_i |V_i & M| per cell, on hand-computed cells."""

    def speed(self, positions, speeds, w, h, cutoff=10.0):
        traj = frames(positions)
        sp = pd.DataFrame([(i, 0, v) for i, v in enumerate(speeds) if v is not None], columns=["id", "frame", "speed"])
        xs, ys = G.grid((0.0, 0.0, float(w), float(h)), 1.0)
        v, used = V.voronoi_speed(traj, sp, xs, ys, room(w, h), G.inside_walkable, cutoff=cutoff, per_cell=4)
        self.assertEqual(used, 1)
        return v

    def test_each_speed_fills_its_voronoi_cell(self):
        v = self.speed([(0.5, 1), (3.5, 1)], [1.0, 2.0], 4, 2)
        np.testing.assert_allclose(v[:2], 1.0, atol=1e-9)
        np.testing.assert_allclose(v[2:], 2.0, atol=1e-9)

    def test_a_shared_cell_is_the_area_weighted_mean(self):
        # Agents at x 0.25 and 1.25 split at x 0.75: cell 0 is 3/4 the first's (1 m/s), 1/4 the second's (3 m/s).
        v = self.speed([(0.25, 0.5), (1.25, 0.5)], [1.0, 3.0], 2, 1)
        self.assertAlmostEqual(v[0, 0], 1.5, places=9)
        self.assertAlmostEqual(v[1, 0], 3.0, places=9)

    def test_an_agent_without_a_speed_owns_ground_that_counts_for_neither(self):
        v = self.speed([(0.5, 1), (3.5, 1)], [1.0, None], 4, 2)
        np.testing.assert_allclose(v[:2], 1.0, atol=1e-9)
        self.assertTrue(np.isnan(v[2:]).all())
        far = self.speed([(10, 10)], [1.0], 20, 20, cutoff=2.0)
        self.assertEqual(far[10, 10], 1.0)
        self.assertTrue(np.isnan(far[0, 0]))


if __name__ == "__main__":
    unittest.main()
