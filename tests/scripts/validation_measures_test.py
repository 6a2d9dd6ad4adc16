#!/usr/bin/python3
"""Unit tests of scripts/validation/measures.py and the bands of experiments.py on hand-made
trajectories whose answers are known (ctest: validation_measures). Needs numpy (Debian's
python3-numpy): run with /usr/bin/python3 tests/scripts/validation_measures_test.py."""
import math
import os
import sys
import unittest

try:
    import numpy as np
except ImportError:
    sys.exit("validation_measures_test: numpy is missing: apt-get install python3-numpy (scripts/deps.sh does it)")

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from validation import experiments as E  # noqa: E402
from validation import measures as M  # noqa: E402
from validation import scenarios as S  # noqa: E402


def traj(rows, fps=10.0, radius=0.2, population=None):
    """Trajectories from (id, frame, x, y) rows, every body of `radius`."""
    ids = sorted({int(r[0]) for r in rows})
    return M.Trajectories(rows, fps, {i: radius for i in ids},
                          {i: (population or {}).get(i, 0) for i in ids})


def straight(pid, frames, x0, y0, vx, vy, fps=10.0):
    return [(pid, f, x0 + vx * f / fps, y0 + vy * f / fps) for f in frames]


class Speed(unittest.TestCase):
    def test_constant_velocity_is_measured_everywhere_including_the_ends(self):
        t = traj(straight(0, range(30), 0.0, 0.0, 1.2, -0.5))
        np.testing.assert_allclose(t.vx, 1.2, atol=1e-9)
        np.testing.assert_allclose(t.vy, -0.5, atol=1e-9)
        np.testing.assert_allclose(t.speed, 1.3, atol=1e-9)

    def test_central_difference_over_plus_minus_0_3_s(self):
        # 1 m/s up to frame 10, then standing at x = 1: at frame 12 (10 fps, +-3 frames) the
        # difference spans frames 9 (x = 0.9) and 15 (x = 1.0): 0.1 m / 0.6 s.
        rows = [(0, f, min(f, 10) / 10.0, 0.0) for f in range(30)]
        t = traj(rows)
        self.assertAlmostEqual(t.speed[12], 0.1 / 0.6)
        self.assertAlmostEqual(t.speed[0], 1.0)  # one-sided at the start: frames 0..3
        self.assertAlmostEqual(t.speed[29], 0.0)

    def test_persons_do_not_mix(self):
        rows = straight(0, range(10), 0, 0, 1.0, 0) + straight(1, range(10), 50, 0, -2.0, 0)
        t = traj(rows)
        np.testing.assert_allclose(t.vx[t.id == 0], 1.0, atol=1e-9)
        np.testing.assert_allclose(t.vx[t.id == 1], -2.0, atol=1e-9)


class DensityAndFlow(unittest.TestCase):
    def test_classic_density_and_mean_speed_in_an_area(self):
        # Three walkers inside the 2 m x 1 m area, one outside, all at 1 m/s in y.
        rows = []
        for pid, x in enumerate((0.5, 1.0, 1.5, 5.0)):
            rows += straight(pid, range(5), x, 0.2, 0.0, 1.0)
        t = traj(rows)
        _, rho, v = t.area_series((0.0, 2.0, 0.0, 1.0), (0, 0))
        self.assertAlmostEqual(rho[0], 1.5)
        self.assertAlmostEqual(v[0], 1.0)

    def test_flow_and_gaps_from_line_crossings(self):
        # Walkers at 1 m/s in +x cross x = 0 at 1.0, 2.0 and 4.0 s (10 fps: exact frames).
        rows = []
        for pid, t0 in enumerate((1.0, 2.0, 4.0)):
            rows += straight(pid, range(60), -t0, 0.0, 1.0, 0.0)
        t = traj(rows)
        times = t.crossings_axis(t.x, t.y, 0.0, +1)
        np.testing.assert_allclose(times, [1.0, 2.0, 4.0], atol=1e-9)
        f = M.flow_and_gaps(times)
        self.assertAlmostEqual(f["flow"], 2.0 / 3.0)
        self.assertAlmostEqual(f["longest_gap"], 2.0)
        self.assertEqual(f["passed"], 3)

    def test_crossing_instant_is_interpolated_and_direction_counts(self):
        # Walking -y through y = 0 between frames 3 and 4 (y = 0.15 - 0.05 f): at f = 3 -> 0.3 s;
        # a walker going +y through the same line is not counted.
        rows = straight(0, range(10), 0.0, 0.15, 0.0, -0.5) + straight(1, range(10), 0.0, -1.0, 0.0, 0.5)
        t = traj(rows)
        np.testing.assert_allclose(t.crossings(0.0), [0.3], atol=1e-9)


class Ring(unittest.TestCase):
    def test_tangential_speed_density_and_backward_samples(self):
        # 8 walkers on the circle r = 4 (ring 3..5, area 16 pi): 5 counter-clockwise at 0.25 rad/s
        # (1 m/s), one drifting back at 0.03 m/s (not a backward sample: the threshold is -0.05),
        # 2 clockwise at 0.125 rad/s (-0.5 m/s): density 8 / 16 pi, mean tangential speed
        # (5 - 0.03 - 1) / 8, backward fraction 2 / 8.
        rows = []
        for pid in range(8):
            w = 0.25 if pid < 5 else -0.0075 if pid == 5 else -0.125
            for f in range(200):
                a = pid * math.pi / 4 + w * f / 10.0
                rows.append((pid, f, 4 * math.cos(a), 4 * math.sin(a)))
        t = traj(rows)
        m = M.ring_measures(t, (0.0, 2 * math.pi), S.ring_area(3, 5), 2.0, 18.0)
        self.assertAlmostEqual(m["density"], 8 / (16 * math.pi), places=9)
        self.assertAlmostEqual(m["speed"], (5 * 1.0 - 0.03 - 2 * 0.5) / 8, places=2)
        self.assertAlmostEqual(m["backward_fraction"], 0.25)

    def test_ring_scenario_goals_are_ahead_and_cycle(self):
        s = S.ring(3, 5, 24, 50, slabs=12)
        self.assertEqual(len(s["populations"]), 12)
        self.assertEqual(sum(p["groups"] for p in s["populations"]), 24)
        self.assertEqual(s["populations"][0]["goals"][:3], ["slab1", "slab2", "slab3"])
        self.assertEqual(s["populations"][11]["goals"][0], "slab0")
        lap = 2 * math.pi * 4
        self.assertGreater(len(s["populations"][0]["goals"]) / 12 * lap, S.SPEED_MAX * 50)

    def test_spawn_waves_split_the_agents(self):
        s = S.in_waves(S.ring(3, 5, 25, 50), 2, 1.0)
        self.assertEqual(sum(p["groups"] for p in s["populations"]), 25)
        self.assertEqual(sorted({p.get("start", 0) for p in s["populations"]}), [0, 1.0])


class Bodies(unittest.TestCase):
    def test_overlap_depth_after_a_start_time(self):
        # Frames 0-9: 0.30 m apart (0.10 deep); from frame 10 on: 0.35 m apart (0.05 deep).
        rows = [(0, f, 0.0, 0.0) for f in range(20)]
        rows += [(1, f, 0.30 if f < 10 else 0.35, 0.0) for f in range(20)]
        t = traj(rows)
        self.assertAlmostEqual(M.max_overlap(t)["max_depth"], 0.10)
        late = M.max_overlap(t, 1.0)
        self.assertAlmostEqual(late["max_depth"], 0.05)
        self.assertAlmostEqual(late["at_s"], 1.0)
        self.assertEqual(late["agents_over_1cm"], 2)

    def test_ellipse_bodies_overlap_across_their_shoulders_not_front_to_back(self):
        # Shoulders 0.4 m across, chests 0.26 m deep (passage ratio 0.65), both facing +x. One 0.30 m
        # behind the other: discs would overlap by 0.10, ellipses stand 0.04 apart. Side by side
        # 0.30 m apart: 0.10 deep either way. Facing each other across 0.20 m: 0.06 deep.
        def pair(dx, dy, o1=(1.0, 0.0)):
            rows = [(0, 0, 0.0, 0.0), (1, 0, dx, dy)]
            t = M.Trajectories(rows, 10.0, {0: 0.2, 1: 0.2}, {0: 0, 1: 0},
                               ori=([1.0, o1[0]], [0.0, o1[1]]), depth_ratio_of={0: 0.65, 1: 0.65})
            return M.max_overlap(t)["max_depth"]
        self.assertEqual(pair(0.30, 0.0), 0.0)
        self.assertAlmostEqual(pair(0.0, 0.30), 0.10)
        self.assertAlmostEqual(pair(0.20, 0.0, (-1.0, 0.0)), 0.06)
        # Without depth ratios the same rows are discs.
        t = M.Trajectories([(0, 0, 0.0, 0.0), (1, 0, 0.30, 0.0)], 10.0, {0: 0.2, 1: 0.2}, {0: 0, 1: 0})
        self.assertAlmostEqual(M.max_overlap(t)["max_depth"], 0.10)

    def test_no_overlap_is_zero(self):
        rows = [(0, f, 0.0, 0.0) for f in range(5)] + [(1, f, 1.0, 0.0) for f in range(5)]
        self.assertEqual(M.max_overlap(traj(rows))["max_depth"], 0.0)

    def test_overlapping_pairs_in_one_frame(self):
        # Frame 0: a stacked pair (0.4 deep) and a touching one (0.0); frame 1: nobody overlaps.
        rows = [(0, 0, 0.0, 0.0), (1, 0, 0.0, 0.0), (2, 0, 5.0, 0.0), (3, 0, 5.4, 0.0),
                (0, 1, 0.0, 0.0), (1, 1, 1.0, 0.0), (2, 1, 5.0, 0.0), (3, 1, 6.0, 0.0)]
        t = traj(rows)
        self.assertEqual(M.overlapping_pairs(t, 0), 1)
        self.assertEqual(M.overlapping_pairs(t, 0, deeper_than=-0.01), 2)
        self.assertEqual(M.overlapping_pairs(t, 1), 0)

    def test_walk_back_from_a_door(self):
        # Door segment x = 10, y 4.5..5.5. Agent 0 at y = 5: x = 5, 6, 7, then back to 6.3, then 9:
        # walks back 0.7 m. Agent 1 approaches monotonically: 0.
        xs = [5, 6, 7, 6.3, 9]
        rows = [(0, f, x, 5.0) for f, x in enumerate(xs)] + [(1, f, 1.0 + f, 2.0) for f in range(5)]
        t = traj(rows)
        w = M.walk_back(t, S.ROOM_DOOR)
        self.assertAlmostEqual(w["max_walk_back"], 0.7)
        self.assertEqual(w["agent"], 0)
        self.assertEqual(w["agents_over_0_5m"], 1)
        # Only the rows before the step back: nothing.
        self.assertEqual(M.walk_back(t, S.ROOM_DOOR, t.frame < 3)["max_walk_back"], 0.0)


class Lanes(unittest.TestCase):
    def test_separated_lanes_give_one(self):
        xs = np.array([0, 1, 2, 3, 0, 1, 2, 3], float)
        ys = np.array([1, 1, 1, 1, 3, 3, 3, 3], float)
        lab = np.array([0, 0, 0, 0, 1, 1, 1, 1])
        s, n = M.lane_order(xs, ys, lab)
        self.assertEqual(n, 8)
        self.assertAlmostEqual(s / n, 1.0)

    def test_alternating_lane_gives_one_ninth(self):
        # One lane, labels 0 1 0 1: every agent sees 1 of its own and 2 of the other: (1/3)^2.
        s, n = M.lane_order(np.arange(4.0), np.zeros(4), np.array([0, 1, 0, 1]))
        self.assertAlmostEqual(s / n, 1.0 / 9.0)

    def test_series_and_shuffled_baseline(self):
        rows = []
        for pid in range(8):
            y = 1.0 if pid < 4 else 3.0
            rows += straight(pid, range(20), 6.0 + pid % 4, y, 1.0 if pid < 4 else -1.0, 0.0)
        t = traj(rows)
        labels = (t.id < 4).astype(int)
        m = M.lane_order_series(t, labels, (5.0, 25.0, 0.0, 4.0), 0.0, shuffles=20)
        self.assertAlmostEqual(m["lane_order"], 1.0)
        self.assertLess(m["lane_order_shuffled"], 0.8)


class References(unittest.TestCase):
    def test_weidmann_and_seyfried(self):
        self.assertAlmostEqual(float(M.weidmann(1.0)), 1.34 * (1 - math.exp(-1.913 * (1 - 1 / 5.4))))
        self.assertEqual(float(M.weidmann(6.0)), 0.0)
        self.assertAlmostEqual(float(M.seyfried_1d(1.0)), 0.60, places=2)
        self.assertAlmostEqual(float(M.seyfried_1d(1.5)), 0.29, places=2)
        self.assertAlmostEqual(float(M.seyfried_1d(2.0)), 0.13, places=2)

    def test_bottleneck_trend(self):
        self.assertAlmostEqual(E.bottleneck_trend(0.5), 1.15)
        self.assertAlmostEqual(E.bottleneck_trend(1.0), 1.9)


class Bands(unittest.TestCase):
    def test_status(self):
        t = E.Targets()
        t.add("x", "in", 1.0, 0.5, 1.5)
        t.add("x", "above", 2.0, 0.5, 1.5)
        t.add("x", "open top", 9.0, 0.2, None)
        t.add("x", "missing", None, 0.0, 1.0)
        t.add("x", "reported", 3.0)
        self.assertEqual([r["status"] for r in t.rows], ["PASS", "FAIL", "PASS", "FAIL", "INFO"])
        self.assertEqual(len(t.failed()), 2)


if __name__ == "__main__":
    unittest.main()
