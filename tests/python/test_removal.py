"""sim.remove_agents(ids): single agents leave at the next tick as a removed crowd's agents do (the
recording the CLI writes for a crowd removed by the timeline), their groups go on without them, bad
ids are refused by name, and the same removals give the same trajectories at any thread count."""
import json
import sqlite3
import subprocess

import numpy as np
import pytest

import throng
from conftest import corridor

NO_POINT = 0xFFFFFFFF


def test_removed_agents_leave_at_the_next_tick_with_an_exit_event():
    sim = throng.Simulation(throng.scenario(corridor(n=10)), threads=1)
    sim.step(10)
    sim.events()
    sim.remove_agents([7, 2])
    assert len(sim.view()) == 10, "not before the next tick"
    sim.step(1)
    ids = sim.view().id
    assert len(ids) == 8 and 2 not in ids and 7 not in ids
    exits = [e for e in sim.events() if e["kind"] == "exit"]
    assert [(e["agent"], e["tick"], e["a"], e["b"]) for e in exits] == [(7, 10, NO_POINT, NO_POINT), (2, 10, NO_POINT, NO_POINT)]
    assert sim.stats["removed"] == 2 and sim.stats["exited"] == 0
    with pytest.raises(KeyError):
        sim.agent(2)
    sim.remove_agents(np.array([0, 1], dtype=np.uint32))  # numpy ids (from a view, say) and a single int
    sim.remove_agents(3)
    sim.step(1)
    assert len(sim.view()) == 5
    sim.run()
    assert sim.finished and sim.stats["exited"] == 5


def test_bad_ids_are_refused_by_name_and_nothing_is_removed():
    sim = throng.Simulation(throng.scenario(corridor(n=5)), threads=1)
    sim.step(2)
    with pytest.raises(ValueError, match=r"ids\[1\]: no agent with id 99.*ids\[2\]: agent 1 is listed twice"):
        sim.remove_agents([1, 99, 1])
    with pytest.raises(ValueError, match=r"-3 is not an agent id"):
        sim.remove_agents([-3])
    with pytest.raises(ValueError, match="4294967296"):
        sim.remove_agents([2**32])
    with pytest.raises(ValueError, match=r"ids\[1\]: 9223372036854775808 is not an agent id.*ids\[2\]: -"):
        sim.remove_agents([0, 2**63, -(2**70)])  # beyond 64 bits too
    with pytest.raises(TypeError, match="float"):
        sim.remove_agents([1.0])
    with pytest.raises(TypeError):
        sim.remove_agents("1")
    with pytest.raises(TypeError):
        sim.remove_agents(None)
    sim.remove_agents([4])
    with pytest.raises(ValueError, match="already queued"):
        sim.remove_agents([4])
    sim.step(1)
    assert list(sim.view().id) == [0, 1, 2, 3], "only the one accepted"
    with pytest.raises(ValueError, match="id 4"):
        sim.remove_agents(4)  # gone
    sim.remove_agents([])  # nothing to do
    sim.close()
    with pytest.raises(ValueError, match="closed"):
        sim.remove_agents([0])


def test_a_group_goes_on_without_its_removed_members_and_a_removed_leader_hands_over():
    d = corridor(n=3, duration=60)
    d["populations"][0]["size"] = 3
    sim = throng.Simulation(throng.scenario(d), threads=1)
    sim.step(20)
    g = sim.group("walkers", 1)
    info = sim.group_info(g)
    assert len(info["members"]) == 3
    leader = info["leader"]
    sim.remove_agents([leader])
    sim.step(1)
    after = sim.group_info(g)
    assert leader not in after["members"] and len(after["members"]) == 2
    assert after["leader"] == min(after["members"]), "the lowest id left leads, as after an exit"
    sim.remove_agents(after["members"])
    sim.step(1)
    assert sim.group_info(g)["members"] == [] and sim.group_info(g)["leader"] is None
    sim.run()
    assert sim.finished
    assert sim.stats["exited"] == 6 and sim.stats["removed"] == 3, "the other groups walked on to the exit"


def test_same_seed_and_removals_give_the_same_state_at_any_thread_count():
    sc = throng.scenario(corridor(n=300, duration=20.0, width=20.0))
    hashes = set()
    for threads in (1, 2, 4):
        sim = throng.Simulation(sc, threads=threads)
        sim.step(30)
        sim.remove_agents(sim.view().id[::7])
        sim.step(30)
        sim.remove_agents([int(sim.view().id[-1]), 3])
        sim.step(40)
        assert sim.stats["removed"] == 45
        hashes.add(sim.state_hash)
    assert len(hashes) == 1


def test_removal_is_recorded_as_the_cli_records_a_removed_crowd(tmp_path, cli):
    """The CLI removes a crowd with the scenario's timeline; Python removes the same agents by id at the
    same tick: the same trajectories, agents table and events (but b: the crowd's index there)."""
    crowd = {"format": "throng-crowd/1", "id": "late",
             "populations": [{"id": "late-walkers", "groups": 6, "size": 1, "radius": 0.2, "goals": ["exit"],
                              "spawn": {"polygon": [[1, 0.5], [5, 0.5], [5, 3.5], [1, 3.5]]}}]}
    (tmp_path / "late.json").write_text(json.dumps(crowd))
    base = corridor(n=8, duration=20.0)
    base["timeline"] = [{"time": 2.0, "insert": "late.json"}]
    cli_doc = dict(base, timeline=base["timeline"] + [{"time": 4.0, "remove": "late"}])
    (tmp_path / "cli.json").write_text(json.dumps(cli_doc))
    (tmp_path / "py.json").write_text(json.dumps(base))
    cli_out, py_out = tmp_path / "cli.sqlite", tmp_path / "py.sqlite"
    subprocess.run([cli, "run", str(tmp_path / "cli.json"), "--out", str(cli_out), "-q"], check=True)
    with throng.Simulation(throng.Scenario.load(str(tmp_path / "py.json")), record=str(py_out)) as sim:
        sim.run(until=4.0)  # the timeline's removal applies at the start of this tick
        late = [int(i) for i in sim.view().id if i >= 8]
        assert len(late) == 6
        sim.remove_agents(late)
        sim.run()
    a, b = sqlite3.connect(cli_out), sqlite3.connect(py_out)
    for q in ["SELECT frame, id, pos_x, pos_y, ori_x, ori_y FROM trajectory_data ORDER BY frame, id",
              "SELECT * FROM throng_agents ORDER BY id",
              "SELECT frame, tick, agent, kind, a FROM throng_events ORDER BY rowid"]:
        assert a.execute(q).fetchall() == b.execute(q).fetchall(), q
    removed = b.execute("SELECT agent, a, b FROM throng_events WHERE kind = 'exit' AND a = ?", (NO_POINT,)).fetchall()
    assert removed == [(i, NO_POINT, NO_POINT) for i in late]
    rec = throng.read_recording(str(py_out))
    assert rec.agents.set_index("id").loc[late, "exit_frame"].notna().all()
