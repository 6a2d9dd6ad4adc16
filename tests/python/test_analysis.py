"""PedPy-style measurements on hand-made trajectories whose answers are computed by hand."""
import numpy as np
import pandas as pd
import pytest

from throng import analysis as A


def walkers(n_frames=21, fps=10.0):
    """Agent 0 walks along y = 1 at 1 m/s from x = 0; agent 1 along y = 3 at 0.5 m/s from x = 0;
    agent 2 stands at (5, 1)."""
    rows = []
    for f in range(n_frames):
        t = f / fps
        rows += [(f, 0, 1.0 * t, 1.0), (f, 1, 0.5 * t, 3.0), (f, 2, 5.0, 1.0)]
    return pd.DataFrame(rows, columns=["frame", "id", "x", "y"])


def test_polygon_area_and_inside():
    square = [(0, 0), (2, 0), (2, 2), (0, 2)]
    assert A.polygon_area(square) == pytest.approx(4.0)
    assert A.polygon_area([(0, 0), (2, 0), (2, 2), (0, 2), (0, 0)]) == pytest.approx(4.0)
    assert A.inside([1, 3, 1.5, -0.1], [1, 1, 1.9, 1], square).tolist() == [True, False, True, False]
    concave = [(0, 0), (4, 0), (4, 4), (2, 1), (0, 4)]
    assert A.inside([2, 2], [0.5, 3], concave).tolist() == [True, False]


def test_classic_density_counts_who_is_inside():
    traj = walkers()
    area = [(0, 0), (1.5, 0), (1.5, 4), (0, 4)]  # 6 m²
    d = A.classic_density(traj, area)
    # frame 0: agents 0 and 1 inside (x = 0 is on the edge: count it? x=0 < cross) -> use frame 5
    assert d.loc[5, "density"] == pytest.approx(2 / 6)    # x0 = 0.5, x1 = 0.25
    assert d.loc[20, "density"] == pytest.approx(1 / 6)   # x0 = 2.0 left, x1 = 1.0 inside
    assert len(d) == 21


def test_individual_speed_is_the_central_difference():
    s = A.individual_speed(walkers(), fps=10.0, frame_step=2)
    by = s.set_index(["id", "frame"])["speed"]
    assert by[(0, 10)] == pytest.approx(1.0)
    assert by[(1, 10)] == pytest.approx(0.5)
    assert by[(2, 10)] == pytest.approx(0.0)
    assert set(s["frame"]) == set(range(2, 19)), "the borders are left out"


def test_mean_speed_averages_those_inside():
    traj = walkers()
    speeds = A.individual_speed(traj, fps=10.0, frame_step=2)
    area = [(0, 0), (6, 0), (6, 4), (0, 4)]
    v = A.mean_speed(traj, speeds, area)
    assert v.loc[10, "speed"] == pytest.approx((1.0 + 0.5 + 0.0) / 3)
    assert v.loc[0, "speed"] == 0.0  # no speed at the border frames


def test_crossings_and_n_t():
    traj = walkers()
    line = ((1.0, 0.0), (1.0, 4.0))  # pointing +y: walking +x crosses to its right
    c = A.crossings(traj, line)
    # agent 0 reaches x = 1 at t = 1.0 s (frame 10, on the line) and is past it at frame 11
    assert c.set_index("id").loc[0, "frame"] == 11
    assert c.set_index("id").loc[0, "direction"] == -1
    assert 1 not in set(c["id"]), "agent 1 reaches x = 1.0 only at frame 20, on the line"
    nt = A.n_t(traj, line, fps=10.0)
    assert nt.loc[10, "cumulative_pedestrians"] == 0 and nt.loc[11, "cumulative_pedestrians"] == 1
    assert nt.loc[20, "time"] == pytest.approx(2.0)
    assert len(A.crossings(traj, ((1.0, 2.0), (1.0, 4.0)))) == 0, "agent 0 passes below the segment"


def test_flow_in_windows():
    crossings = pd.DataFrame({"frame": [10, 12, 14, 30, 31]})
    f = A.flow(crossings, fps=10.0, window=1.0)
    assert f["crossings"].tolist() == [3, 0, 2]
    assert f["flow"].tolist() == [3.0, 0.0, 2.0]
    assert f["start"].tolist() == [1.0, 2.0, 3.0]


def test_fundamental_diagram_pairs_density_and_speed():
    traj = walkers()
    area = [(0, 0), (6, 0), (6, 4), (0, 4)]
    fd = A.fundamental_diagram(traj, area, fps=10.0, frame_step=2)
    assert fd.loc[10, "density"] == pytest.approx(3 / 24)
    assert fd.loc[10, "speed"] == pytest.approx(0.5)


def test_bad_input_is_refused():
    with pytest.raises(ValueError):
        A.classic_density(pd.DataFrame({"frame": [0], "x": [0.0]}), [(0, 0), (1, 0), (1, 1)])
    with pytest.raises(ValueError):
        A.polygon_area([(0, 0), (1, 1)])
    with pytest.raises(ValueError):
        A.crossings(walkers(), ((1, 1), (1, 1)))
    with pytest.raises(ValueError):
        A.individual_speed(walkers(), fps=0)
