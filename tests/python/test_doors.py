"""sim.set_exit_open(id, open): a door closed on an event the script sees (here: once 15 people have
left by it) lets nobody through from the next tick, the crowd re-routes to the other exit, and it
opens again; ids that are no exit are refused by name."""
import pytest

import throng

SOUTH, NORTH = 0, 1  # point indices: an exit event's `a`


def room(n=80):
    """A 20 x 10 m room with two 1 m doors in its east wall (south at y 2, north at y 8) into a 2 m
    hall; the crowd starts in the southern half and takes the nearest open exit."""
    def door(id, y):
        return {"id": id, "kind": "exit", "polygon": [[20.6, y - 0.5], [21.6, y - 0.5], [21.6, y + 0.5], [20.6, y + 0.5]]}
    return {"format": "throng/1", "name": "py-doors", "seed": 5, "duration": 300,
            "walkable": [[[0, 0], [20, 0], [20, 10], [0, 10]], [[20.2, 0], [22.2, 0], [22.2, 10], [20.2, 10]],
                         [[20, 1.5], [20.2, 1.5], [20.2, 2.5], [20, 2.5]], [[20, 7.5], [20.2, 7.5], [20.2, 8.5], [20, 8.5]]],
            "points": [door("south", 2), door("north", 8), {"id": "hall", "kind": "interest", "position": [10, 5]}],
            "populations": [{"id": "crowd", "groups": n, "size": 1,
                             "spawn": {"polygon": [[5, 0.3], [19.7, 0.3], [19.7, 4.5], [5, 4.5]]},
                             "exits": ["south", "north"], "exitChoice": {"rule": "nearest"},
                             "speed": {"mean": 1.34, "sd": 0.26}}]}


def exits_by(events):
    return [e["a"] for e in events if e["kind"] == "exit"]


def test_nobody_leaves_by_an_exit_after_it_closed_and_the_crowd_takes_the_other():
    sim = throng.Simulation(throng.scenario(room()), threads=1)
    south = 0
    while south < 15:
        sim.step(1)
        south += exits_by(sim.events()).count(SOUTH)
    sim.set_exit_open("south", False)
    before = len(sim.view())
    sim.run()
    after = exits_by(sim.events())
    assert sim.finished and len(after) == before
    assert SOUTH not in after, "nobody leaves by the closed south exit"
    assert after.count(NORTH) == before


def test_a_closed_exit_opens_again():
    sim = throng.Simulation(throng.scenario(room(n=20)), threads=1)
    sim.set_exit_open("south", False)
    sim.set_exit_open("north", False)
    sim.step(200)  # 20 s with both doors shut: everyone waits inside
    assert exits_by(sim.events()) == [] and len(sim.view()) == 20
    sim.set_exit_open("south", True)
    sim.run()
    assert sim.finished and exits_by(sim.events()) == [SOUTH] * 20


def test_ids_that_are_no_exit_are_refused_by_name():
    sim = throng.Simulation(throng.scenario(room(n=5)), threads=1)
    with pytest.raises(KeyError, match="nowhere"):
        sim.set_exit_open("nowhere", False)
    with pytest.raises(KeyError, match="hall"):
        sim.set_exit_open("hall", False)  # a point, but not an exit
    with pytest.raises(TypeError):
        sim.set_exit_open("south")
    sim.close()
    with pytest.raises(ValueError, match="closed"):
        sim.set_exit_open("south", False)


def test_the_scenarios_exits_close_as_walls_and_other_ids_do_not():
    sim = throng.Simulation(throng.scenario(room(n=5)), threads=1)
    assert sim.exit_is_wall("south") and sim.exit_is_wall("north")
    assert not sim.exit_is_wall("hall"), "an interest point is no exit"
    assert not sim.exit_is_wall("nowhere")
