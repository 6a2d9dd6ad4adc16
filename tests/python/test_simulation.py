"""Stepping, agent state as zero-copy views, events, control, recording; same trajectories as the CLI."""
import json
import os
import sqlite3
import subprocess
import sys

import numpy as np
import pytest

import throng
from conftest import corridor


def test_steps_advance_time_and_agents_walk():
    sim = throng.Simulation(throng.scenario(corridor()), threads=1)
    assert sim.tick == 0 and sim.time == 0.0
    start = sim.agents()
    assert len(start) == 20
    sim.step(40)
    assert sim.tick == 40
    assert sim.time == pytest.approx(2.0, abs=1e-5)
    later = sim.agents()
    assert np.array_equal(start.id, later.id)
    moved = later.x - start.x
    assert (moved > 1.0).all(), "every agent walked at least 1 m towards the exit in 2 s"
    assert ((later.mode == 0)).all()


def test_views_share_memory_are_read_only_and_survive_steps():
    sim = throng.Simulation(throng.scenario(corridor()), threads=1)
    sim.step(5)
    a = sim.agents()
    x = a.x
    assert x.dtype == np.float32 and a.id.dtype == np.uint32
    assert not x.flags.writeable and not x.flags.owndata
    with pytest.raises(ValueError):
        x[0] = 1.0
    # Two views of the same frame share one buffer: nothing was copied.
    assert np.shares_memory(a.x, a.x)
    assert a.x.__array_interface__["data"][0] == a.x.__array_interface__["data"][0]
    snapshot = x.copy()
    sim.step(20)
    assert np.array_equal(x, snapshot), "a view is a snapshot of its tick"
    del a, sim
    assert float(x.sum()) == float(snapshot.sum())  # still valid after the simulation is gone


def test_events_are_drained_in_order():
    sim = throng.Simulation(throng.scenario(corridor(n=5)), threads=1)
    ev = sim.events()
    assert [e["kind"] for e in ev] == ["spawn"] * 5
    assert sim.events() == []
    sim.run()
    kinds = [e["kind"] for e in sim.events()]
    assert kinds.count("exit") == 5
    assert sim.finished


def test_stepping_a_finished_simulation_raises():
    sim = throng.Simulation(throng.scenario(corridor(n=3)), threads=1)
    sim.run()
    assert sim.finished
    with pytest.raises(ValueError, match="finished"):
        sim.step()


def test_bad_arguments_raise_clear_errors():
    sc = throng.scenario(corridor(n=3))
    with pytest.raises(ValueError):
        throng.Simulation(sc, threads=-1)
    with pytest.raises(ValueError):
        throng.Simulation(sc, fps=0)
    with pytest.raises(ValueError):
        throng.Simulation(sc, duration=float("nan"))
    sim = throng.Simulation(sc)
    with pytest.raises(ValueError):
        sim.step(-1)
    with pytest.raises(KeyError):
        sim.agent(10_000)
    with pytest.raises(KeyError):
        sim.release(999)
    g = sim.group("walkers", 0)
    with pytest.raises(ValueError):
        sim.guide(g, float("nan"), 1.0)
    with pytest.raises(TypeError):
        sim.step("ten")
    sim.close()
    with pytest.raises(ValueError, match="closed"):
        sim.step()


def test_guided_group_follows_the_guide_and_is_released():
    sim = throng.Simulation(throng.scenario(corridor(n=3, duration=60)), threads=1)
    g = sim.group("walkers", 1)
    member = sim.group_info(g)["members"][0]
    sim.guide(g, 3.0, 2.0)
    sim.step(200)
    x, y = sim.agent(member)["position"]
    assert abs(x - 3.0) < 1.5 and abs(y - 2.0) < 1.5, "the guided group stayed with its guide"
    assert sim.group_info(g)["guided"]
    sim.release(g)
    sim.step(1)
    assert not sim.group_info(g)["guided"]
    sim.run()
    assert sim.finished, "released, the group went on to the exit"


def test_crowds_are_inserted_and_removed_while_stepping():
    sim = throng.Simulation(throng.scenario(corridor(n=2, duration=60)), threads=1)
    crowd = {"format": "throng-crowd/1", "id": "late",
             "populations": [{"id": "late-walkers", "groups": 4, "size": 1,
                              "spawn": {"polygon": [[1, 1], [4, 1], [4, 3], [1, 3]]}, "goals": ["exit"], "radius": 0.2}]}
    sim.step(10)
    assert sim.insert_crowd(json.dumps(crowd)) == 0
    sim.step(1)
    assert len(sim.agents()) == 6
    with pytest.raises(throng.ScenarioError):
        sim.insert_crowd(json.dumps(crowd))  # the id is taken
    bad = dict(crowd, id="bad")
    bad["populations"] = [dict(crowd["populations"][0], id="b", goals=["nowhere"])]
    with pytest.raises(throng.ScenarioError) as err:
        sim.insert_crowd(json.dumps(bad), "bad.json")
    assert any("goals" in d["pointer"] for d in err.value.diagnostics)
    sim.remove_crowd("late")
    sim.step(1)
    assert len(sim.agents()) == 2
    with pytest.raises(KeyError):
        sim.remove_crowd("late")


def test_same_seed_same_trajectories_for_any_thread_count():
    sc = throng.scenario(corridor(n=400, duration=10.0, width=20.0))
    hashes = set()
    for threads in (1, 2, 4):
        sim = throng.Simulation(sc, threads=threads)
        sim.step(100)
        assert len(sim.agents()) > 300, "enough agents that the work is split"
        hashes.add(sim.state_hash)
    assert len(hashes) == 1
    other = throng.Simulation(sc, seed=99, threads=1)
    other.step(100)
    assert other.state_hash not in hashes


def test_recording_is_what_the_cli_writes(tmp_path, cli):
    d = corridor(n=60, duration=20.0)
    path = tmp_path / "study.json"
    path.write_text(json.dumps(d))
    cli_out = tmp_path / "cli.sqlite"
    run = subprocess.run([cli, "run", str(path), "--out", str(cli_out), "--json", "-q", "--threads", "2"],
                         capture_output=True, text=True, check=True)
    summary = json.loads(run.stdout)
    py_out = tmp_path / "py.sqlite"
    with throng.Simulation(throng.Scenario.load(str(path)), threads=3, record=str(py_out)) as sim:
        # Looks between recorded ticks (every 3rd tick; frames every 2nd) must not take events from the recording.
        seen = 0
        while sim.time < 15.0:
            sim.step(1)
            if sim.tick % 3 == 0:
                sim.agents()
                seen += sum(e["kind"] == "exit" for e in sim.events())
        assert seen > 0, "exits happened between recorded frames"
        sim.run()
        assert format(sim.state_hash, "016x") == summary["state_hash"]
    queries = ["SELECT frame, id, pos_x, pos_y, ori_x, ori_y FROM trajectory_data ORDER BY frame, id",
               "SELECT frame, tick, agent, kind, a, b FROM throng_events ORDER BY rowid",
               "SELECT * FROM throng_agents ORDER BY id"]
    a, b = sqlite3.connect(cli_out), sqlite3.connect(py_out)
    for q in queries:
        assert a.execute(q).fetchall() == b.execute(q).fetchall(), q
    meta = dict(b.execute("SELECT key, value FROM metadata").fetchall())
    assert meta["throng_completed"] == "1"


def test_existing_recording_is_not_overwritten(tmp_path):
    out = tmp_path / "r.sqlite"
    out.write_bytes(b"keep me")
    with pytest.raises(throng.ScenarioError):
        throng.Simulation(throng.scenario(corridor(n=2)), record=str(out))
    assert out.read_bytes() == b"keep me"
    with throng.Simulation(throng.scenario(corridor(n=2)), record=str(out), force=True) as sim:
        sim.run()
    assert out.read_bytes()[:15] == b"SQLite format 3"


def test_agents_added_at_positions_walk_to_their_goal():
    sim = throng.Simulation(throng.scenario(corridor(n=2, duration=60)), threads=1)
    crowd = sim.add_agents([(2.0, 1.0), (2.0, 3.0)], goals="exit", speed=1.0)
    sim.step(1)
    a = sim.agents()
    assert len(a) == 4
    new = a.id >= 2
    spots = sorted(zip(a.x[new], a.y[new]), key=lambda p: p[1])
    for (x, y), (wx, wy) in zip(spots, [(2.0, 1.0), (2.0, 3.0)]):
        assert np.hypot(x - wx, y - wy) < 1.4 + 0.1, "spawned near the position asked for (one tick walked)"
    with pytest.raises(ValueError):
        sim.add_agents([(float("nan"), 1.0)], goals="exit")
    with pytest.raises(throng.ScenarioError):
        sim.add_agents([(50.0, 1.0)], goals="exit")  # outside the walkable area
    sim.run()
    assert sim.stats["exited"] == 4
    assert crowd.startswith("python-agents")


def test_simd_path_names_the_vector_path_and_THRONG_SIMD_picks_it():
    # Every path gives the same trajectories (docs/architecture.md, "SIMD paths"); the module says
    # which one runs, and THRONG_SIMD=portable forces the portable one in a fresh interpreter.
    assert throng.simd_path() in ("avx2", "portable")
    env = dict(os.environ, THRONG_SIMD="portable")
    out = subprocess.run([sys.executable, "-c", "import throng; print(throng.simd_path())"], env=env,
                         capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "portable", out.stderr
