"""read_recording: a recording as pandas DataFrames in PedPy's names; refuses files that are not one."""
import numpy as np
import pytest

import throng
from throng import analysis as A
from conftest import corridor


def test_read_what_a_simulation_recorded(tmp_path):
    out = tmp_path / "r.sqlite"
    with throng.Simulation(throng.scenario(corridor(n=30, duration=25)), threads=2, record=str(out)) as sim:
        sim.run()
        exited = sim.stats["exited"]
    rec = throng.read_recording(out)
    assert list(rec.trajectory.columns) == ["frame", "id", "x", "y", "ori_x", "ori_y"]
    assert rec.fps == 10.0
    assert rec.trajectory["id"].nunique() == 30
    assert rec.walkable_area.startswith("POLYGON") or rec.walkable_area.startswith("MULTIPOLYGON")
    assert (rec.events["kind"] == "exit").sum() == exited
    assert rec.agents["exit_frame"].notna().sum() == exited
    assert rec.scenario["name"] == "py-corridor"
    assert rec.metadata["throng_completed"] == "1"
    # Free walkers at 1.3 m/s on average: the corridor's mean speed says so.
    traj = rec.trajectory
    speeds = A.individual_speed(traj, rec.fps)
    v = A.mean_speed(traj, speeds, [(8, 0), (14, 0), (14, 4), (8, 4)])
    walking = v[v["speed"] > 0]["speed"]
    assert 1.0 < walking.mean() < 1.6
    c = A.crossings(traj, ((10, 0), (10, 4)))
    assert len(c) == 30 and (c["direction"] == -1).all()


def test_not_a_recording(tmp_path):
    bad = tmp_path / "bad.sqlite"
    bad.write_text("hello")
    with pytest.raises(ValueError, match="not a throng recording"):
        throng.read_recording(bad)
    with pytest.raises(FileNotFoundError):
        throng.read_recording(tmp_path / "absent.sqlite")


def test_common_ground_tables(tmp_path, root):
    import json, os
    doc = json.load(open(os.path.join(root, "scenarios", "mall.json")))
    out = tmp_path / "mall.sqlite"
    with throng.Simulation(throng.Scenario.from_dict(doc, os.path.join(root, "scenarios", "mall.json")), threads=2,
                           duration=60, record=str(out)) as sim:
        sim.run()
    rec = throng.read_recording(out)
    starts = (rec.events["kind"] == "coordination_start").sum()
    assert starts > 0, "the mall starts Common Ground coordinations in its first minute"
    ended = rec.coordinations
    assert {"initiator", "plan", "outcome", "start"} <= set(ended.columns)
    assert len(ended) <= starts
    assert len(rec.scripts) > 0 and {"coordination", "agent", "seq", "step", "motion", "behaviour"} <= set(rec.scripts.columns)
    assert set(rec.scripts["agent"]) <= set(rec.agents["id"]), "every script belongs to an agent of the recording"
    assert list(rec.points["id"]) == [p["id"] for p in doc["points"]]
