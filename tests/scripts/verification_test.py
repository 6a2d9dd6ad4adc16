#!/usr/bin/python3
"""Unit test of the verification harness (ctest: verification_unit): the status rule (PASS, FAIL,
XFAIL, XPASS; reported-only checks ignored), per-model expectations, the measurements verify.py
adds to scripts/validation/measures.py (RiMEA's detours, ISO's line crossings, zone speeds and
positions with floor heights) on hand-made trajectories with known answers, ISO 17's two-floor layout
(the exit below nearer as the crow flies from every start), and that the
committed scenario files under verification/ are what scripts/verification/make_scenarios.py
writes."""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.join(HERE, "..", "..", "scripts")
sys.path.insert(0, SCRIPTS)

import numpy as np  # noqa: E402

from validation import measures as M  # noqa: E402
from verification import core as C  # noqa: E402
from verification import iso as I  # noqa: E402
from verification import rimea as R  # noqa: E402

FAILURES = []


def expect(cond, what):
    if not cond:
        FAILURES.append(what)


def test_status():
    ok, bad, info = C.Check("a", "1", True), C.Check("b", "2", False), C.Check("c", "3", None)
    expect(C.status_of([ok, info], None) == C.PASS, "all ok -> PASS")
    expect(C.status_of([ok, bad], None) == C.FAIL, "one failing check -> FAIL")
    expect(C.status_of([ok, bad], "why") == C.XFAIL, "expected failure -> XFAIL")
    expect(C.status_of([ok, info], "why") == C.XPASS, "expected failure that passes -> XPASS")
    expect(C.status_of([], None) == C.FAIL, "no checks -> FAIL")
    expect(C.band("x", 1.5, 1.0, 2.0).ok and not C.band("x", 2.5, 1.0, 2.0).ok, "band inside / outside")
    expect(C.band("x", None, 1.0, 2.0).ok is False, "nothing measured -> not ok")
    t = C.Test("t", "s", "title", "crit", "src", "doc", xfail={"orca": "slow", "*": "other"})
    expect(t.expectation("orca") == "slow" and t.expectation("avm") == "other", "per-model expectation")
    expect(C.Test("t", "s", "", "", "", "", xfail="always").expectation("avm") == "always", "one reason for all")
    expect(C.Test("t", "s", "", "", "", "").expectation("avm") is None, "no expectation")


def test_geometry_measures():
    square = [[0, 0], [2, 0], [2, 2], [0, 2]]
    inside = M.inside_polygon(np.array([1.0, 3.0, 2.0, -0.5]), np.array([1.0, 1.0, 1.0, 1.0]), square)
    expect(inside.tolist() == [True, False, True, False], f"inside_polygon {inside}")
    ell = [[0, 0], [4, 0], [4, 4], [3, 4], [3, 1], [0, 1]]  # L: the inner corner is (3, 1)
    expect(not M.inside_polygon(np.array([1.0]), np.array([3.0]), ell)[0], "inside the L's notch is outside")
    d = M.distance_to_edges(np.array([1.0]), np.array([0.5]), [ell])
    expect(abs(d[0] - 0.5) < 1e-9, f"distance_to_edges {d}")
    # Agent 1 cuts the inner corner of the L between two frames; agent 2 stays in the first leg.
    traj = M.Trajectories([(1, 0, 2.5, 0.8), (1, 1, 3.5, 1.5), (2, 0, 0.5, 0.5), (2, 1, 1.0, 0.5)], 10.0)
    expect(M.steps_crossing_edges(traj, [ell]) == 2, "a step through the corner crosses two edges")


def test_motion_measures():
    # Agent 1 stands 2 s then walks +x at 1 m/s (more than 0.1 m away at 2.2 s); agent 2 walks at 0.5 m/s.
    rows = [(1, f, (0.0 if f < 20 else (f - 20) / 10.0), 0.0) for f in range(60)]
    rows += [(2, f, f * 0.05, 1.0) for f in range(60)]
    traj = M.Trajectories(rows, 10.0)
    moves = M.first_moves(traj, 0.1)
    expect(abs(moves[1] - 2.2) < 1e-9 and abs(moves[2] - 0.3) < 1e-9, f"first_moves {moves}")
    speeds = M.region_speeds(traj, (1.0, 2.0))
    expect(abs(speeds[1] - 1.0) < 1e-6 and abs(speeds[2] - 0.5) < 1e-6, f"region_speeds {speeds}")
    # Two members 0.8 m apart walk side by side: each is 0.4 m from their centre.
    pair = [(a, f, f * 0.1, 0.8 * (a - 1)) for a in (1, 2) for f in range(20)]
    spread = M.group_spread(M.Trajectories(pair, 10.0), {1: 7, 2: 7})
    expect(abs(spread["median"] - 0.4) < 1e-9 and spread["samples"] == 20, f"group_spread {spread}")


def test_sideways_detours():
    # Towards a strip at x = 10: agent 1 walks straight ahead from (2, 3); agent 2 from (4, 0) ends
    # 8 m along it, a straight walk of 10 m for 6 m ahead (+2/3).
    rows = [(1, 0, 2.0, 3.0), (1, 1, 6.0, 3.0), (1, 2, 10.0, 3.0), (2, 0, 4.0, 0.0), (2, 1, 10.0, 8.0)]
    side, excess = R.sideways_detours(M.Trajectories(rows, 1.0), 10.0)
    expect(np.allclose(side, [0.0, 8.0]) and np.allclose(excess, [0.0, 4.0 / 6.0]), f"sideways_detours {side} {excess}")


def test_iso_crossings():
    # Agent 1 walks +x at 1 m/s from x = 0, agent 2 at 0.5 m/s from x = 1 (10 frames a second); agent 3
    # walks back (-x) and never crosses +x.
    rows = [(1, f, f * 0.1, 0.0) for f in range(100)] + [(2, f, 1.0 + f * 0.05, 1.0) for f in range(100)]
    rows += [(3, f, 5.0 - f * 0.1, 1.5) for f in range(50)]
    traj = M.Trajectories(rows, 10.0)
    t = I.crossing_times(traj, 2.05)
    expect(sorted(t) == [1, 2] and abs(t[1] - 2.05) < 1e-9 and abs(t[2] - 2.1) < 1e-9, f"crossing_times {t}")
    v = I.zone_speeds(traj, 2.0, 4.0)
    expect(sorted(v) == [1, 2] and abs(v[1] - 1.0) < 1e-9 and abs(v[2] - 0.5) < 1e-9, f"zone_speeds {v}")


def test_iso_positions_3d():
    # Agent 1 stays on a floor 3 m up; agent 2 walks down from it to the ground (throng_heights).
    import sqlite3
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "r.sqlite")
        db = sqlite3.connect(path)
        db.execute("CREATE TABLE trajectory_data (frame INTEGER, id INTEGER, pos_x REAL, pos_y REAL)")
        db.execute("CREATE TABLE throng_heights (frame INTEGER, id INTEGER, z REAL)")
        for f in range(4):
            db.execute("INSERT INTO trajectory_data VALUES (?, 1, ?, 0)", (f, 1.0 + f))
            db.execute("INSERT INTO throng_heights VALUES (?, 1, 3.0)", (f,))
            db.execute("INSERT INTO trajectory_data VALUES (?, 2, 5, ?)", (f, 2.0 - f))
            db.execute("INSERT INTO throng_heights VALUES (?, 2, ?)", (f, 3.0 - f))
        db.commit()
        db.close()
        first, lowest = I.positions_3d(path)
    expect(first == {1: (1.0, 0.0, 3.0), 2: (5.0, 2.0, 3.0)}, f"positions_3d first {first}")
    expect(lowest == {1: 3.0, 2: 0.0}, f"positions_3d lowest {lowest}")


def test_iso_route_layout():
    # Every corner of the spawn (on the upper floor) is nearer the exit below than the east one as the
    # crow flies, and the spawn lies on the upper floor's walkable quad.
    from verification import geometry as G
    s = G.route_layout("t")
    h, at = G.layout_height(), G.layout_exits()
    spawn = s["populations"][0]["spawn"]
    expect(spawn["height"] == h, f"spawn height {spawn['height']}")
    for x, y in spawn["polygon"]:
        p = (x, y, h)
        expect(np.linalg.norm(np.subtract(p, at["below"])) < np.linalg.norm(np.subtract(p, at["east"])),
               f"iso-17: exit below not nearer as the crow flies from {p}")
    heights = sorted({v[2] for v in s["terrain"]["vertices"]})
    expect(heights[0] == 0.0 and heights[-1] == h, f"iso-17 floors {heights[0]} .. {heights[-1]}")


def test_committed_scenarios():
    res = subprocess.run([sys.executable, os.path.join(SCRIPTS, "verification", "make_scenarios.py"), "--check"],
                         capture_output=True, text=True)
    expect(res.returncode == 0, f"verification/ scenarios out of date: {res.stdout}{res.stderr}")


def main():
    test_status()
    test_geometry_measures()
    test_motion_measures()
    test_sideways_detours()
    test_iso_crossings()
    test_iso_positions_3d()
    test_iso_route_layout()
    test_committed_scenarios()
    for f in FAILURES:
        print("verification_test: FAIL:", f)
    if FAILURES:
        sys.exit(1)
    print("verification_test: ok")


if __name__ == "__main__":
    main()
