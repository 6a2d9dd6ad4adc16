"""sim.view(): the live agent columns without a copy — equal to the agents() snapshot, refused once
stale, never a crash or a read of freed memory while arrays are held across steps, insertions and
removals of crowds and agents (random sequences under hypothesis)."""
import gc
import json

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

import throng
from conftest import corridor

COLUMNS = ("id", "x", "y", "z", "vx", "vy", "ori_x", "ori_y", "mode", "clip", "phase")


def crowd(cid, groups, size=1):
    return json.dumps({"format": "throng-crowd/1", "id": cid,
                       "populations": [{"id": f"{cid}-walkers", "groups": groups, "size": size, "radius": 0.2,
                                        "spawn": {"polygon": [[1, 0.5], [15, 0.5], [15, 3.5], [1, 3.5]]},
                                        "goals": ["exit"]}]})


def assert_view_equals_snapshot(sim):
    v, a = sim.view(), sim.agents()
    assert v.tick == a.tick == sim.tick and len(v) == len(a)
    for name in COLUMNS:
        live, copied = getattr(v, name), getattr(a, name)
        assert live.dtype == copied.dtype, name
        assert np.array_equal(live, copied), name
    groups = v.group
    assert groups.dtype == np.uint32
    for i, g in zip(v.id[:5], groups[:5]):
        assert sim.agent(int(i))["group"] == g


def test_view_equals_the_snapshot_as_the_world_runs():
    sim = throng.Simulation(throng.scenario(corridor(n=30, duration=60)), threads=2)
    for _ in range(12):
        assert_view_equals_snapshot(sim)
        sim.step(15)
    assert sim.stats["exited"] > 0, "rows were removed meanwhile"
    assert_view_equals_snapshot(sim)


def test_view_copies_nothing_and_is_read_only():
    sim = throng.Simulation(throng.scenario(corridor()), threads=1)
    sim.step(3)
    v = sim.view()
    x = v.x
    assert not x.flags.writeable and not x.flags.owndata
    with pytest.raises(ValueError):
        x[0] = 1.0
    with pytest.raises(ValueError):
        x.setflags(write=True)
    address = x.__array_interface__["data"][0]
    assert v.x.__array_interface__["data"][0] == address, "the same memory each time"
    sim.step(1)
    # The next tick's view reads the same columns in place: no new buffer, nothing copied.
    assert sim.view().x.__array_interface__["data"][0] == address


def test_a_stale_view_is_refused_with_a_clear_error():
    sim = throng.Simulation(throng.scenario(corridor()), threads=1)
    v = sim.view()
    assert v.valid and len(v) == 20
    sim.step(0)
    assert v.valid, "no tick, no change"
    sim.step(1)
    assert not v.valid and "stale" in repr(v)
    for name in COLUMNS + ("group",):
        with pytest.raises(throng.StaleViewError, match="tick 0 is stale.*sim.view"):
            getattr(v, name)
    with pytest.raises(throng.StaleViewError):
        len(v)
    assert v.tick == 0 and v.time == 0.0, "what it was taken at stays readable"
    w = sim.view()
    sim.run(2.0)
    with pytest.raises(throng.StaleViewError):
        w.x
    u = sim.view()
    sim.close()
    with pytest.raises(throng.StaleViewError, match="closed"):
        u.y
    with pytest.raises(ValueError, match="closed"):
        sim.view()
    assert issubclass(throng.StaleViewError, RuntimeError)


def test_arrays_outlive_growth_removal_and_the_simulation():
    sim = throng.Simulation(throng.scenario(corridor(n=4, duration=60)), threads=1)
    sim.step(5)
    v = sim.view()
    held = {name: getattr(v, name) for name in COLUMNS}
    snapshot = {name: a.copy() for name, a in held.items()}
    sim.insert_crowd(crowd("many", 150))  # beyond the capacity reserved for the scenario: the columns move
    sim.step(1)
    assert len(sim.view()) == 154
    for name, a in held.items():
        assert np.array_equal(a, snapshot[name]), f"{name}: its old buffer is kept, not freed"
    sim.remove_crowd("many")
    sim.step(2)
    assert len(sim.view()) == 4
    assert_view_equals_snapshot(sim)
    x = sim.view().x
    del v, sim
    gc.collect()
    assert np.isfinite(x).all() and len(x) == 4, "the arrays keep the world's memory alive"
    assert all(np.isfinite(a).all() for a in held.values())


OPS = st.one_of(st.tuples(st.just("step"), st.integers(0, 30)),
                st.tuples(st.just("insert"), st.integers(1, 60)),
                st.tuples(st.just("remove"), st.integers(0, 5)),
                st.tuples(st.just("remove_agents"), st.integers(0, 40)),
                st.tuples(st.just("view"), st.integers(0, 0)),
                st.tuples(st.just("read_old"), st.integers(0, 10)))


@settings(max_examples=60, deadline=None, database=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(OPS, max_size=14))
def test_random_step_insert_remove_view_sequences(ops):
    sim = throng.Simulation(throng.scenario(corridor(n=5, duration=120)), threads=1)
    views, arrays, inserted = [], [], []
    for op, k in ops:
        if op == "step":
            if not sim.finished:
                sim.step(k)
        elif op == "insert":
            cid = f"c{len(inserted)}"
            sim.insert_crowd(crowd(cid, k))
            inserted.append(cid)
        elif op == "remove" and inserted:
            try:
                sim.remove_crowd(inserted[k % len(inserted)])
            except KeyError:
                pass  # removed already
        elif op == "remove_agents":
            ids = [int(i) for i in sim.view().id[k % 7::k % 5 + 2]]
            try:
                sim.remove_agents(ids + ([k + 10_000] if k % 3 == 0 else []))
                assert k % 3 != 0, "an unknown id is refused"
            except ValueError as e:
                assert "already queued" in str(e) or str(k + 10_000) in str(e)
        elif op == "view":
            v = sim.view()
            views.append(v)
            arrays.extend([v.x, v.id, v.mode, v.phase])
            assert_view_equals_snapshot(sim)
        elif op == "read_old" and views:
            v = views[k % len(views)]
            if v.valid:
                assert v.tick == sim.tick
                len(v)
            else:
                with pytest.raises(throng.StaleViewError):
                    v.x
        for a in arrays:  # held arrays stay readable memory, whatever happened since
            a.sum()
    assert_view_equals_snapshot(sim)
