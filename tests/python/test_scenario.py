"""Scenarios from files, dicts, JSON text and the builder; every problem raised as ScenarioError."""
import json
import math
import os

import pytest

import throng
from conftest import corridor


def test_load_a_bundled_scenario(root):
    s = throng.Scenario.load(os.path.join(root, "scenarios", "bottleneck.json"))
    assert s.name == "bottleneck"
    assert s.populations == ["crowd"]
    assert s.points == ["gap", "exit"]
    assert s.models == ["avm"]
    assert s.dt == pytest.approx(0.05)
    assert json.loads(s.json)["name"] == "bottleneck"


def test_from_dict_and_from_json_agree():
    d = corridor()
    a = throng.Scenario.from_dict(d)
    b = throng.Scenario.from_json(json.dumps(d))
    assert a.name == b.name == "py-corridor"
    assert throng.scenario(d).populations == ["walkers"]


def test_every_problem_is_reported_with_its_pointer():
    d = corridor()
    d["populations"][0]["goals"] = ["nowhere"]
    d["walkable"] = [[[0, 0], [1, 0]]]
    with pytest.raises(throng.ScenarioError) as err:
        throng.Scenario.from_dict(d, source="study.json")
    pointers = {x["pointer"] for x in err.value.diagnostics}
    assert "/walkable/0" in pointers
    assert any(p.startswith("/populations/0/goals") for p in pointers)
    assert all(x["source"] == "study.json" for x in err.value.diagnostics)
    assert isinstance(err.value, ValueError)
    assert "expected" in str(err.value)


def test_a_missing_file_names_it(tmp_path):
    path = str(tmp_path / "absent.json")
    with pytest.raises(throng.ScenarioError) as err:
        throng.Scenario.load(path)
    assert "absent.json" in str(err.value)


def test_nan_is_refused_before_parsing():
    d = corridor()
    d["duration"] = math.nan
    with pytest.raises(throng.ScenarioError):
        throng.Scenario.from_dict(d)


def test_wrong_types_raise_type_error():
    with pytest.raises(TypeError):
        throng.Scenario.from_dict([1, 2])
    with pytest.raises(TypeError):
        throng.scenario(42)


def test_builder_builds_a_valid_scenario():
    b = (throng.ScenarioBuilder("built", seed=5, duration=20)
         .walkable([(0, 0), (10, 0), (10, 5), (0, 5)])
         .obstacle([(4, 0), (5, 0), (5, 2), (4, 2)])
         .exit("out", polygon=[(9, 0), (10, 0), (10, 5), (9, 5)])
         .action("look", position=(7, 4), radius=0.5, duration=2, orientation=(0, 1))
         .population("p", goals=["look", "out"], spawn=[(0.5, 0.5), (3, 0.5), (3, 4.5), (0.5, 4.5)], groups=3,
                     speed=1.2, model="avm"))
    s = throng.scenario(b)
    assert s.name == "built" and s.seed == 5
    assert s.points == ["out", "look"]
    assert s.models == ["avm"]


def test_builder_passes_waypoint_choices_through():
    choice = {"choose": ["a", "b"], "split": "leastTargeted"}
    b = (throng.ScenarioBuilder("stands", seed=2, duration=20)
         .walkable([(0, 0), (12, 0), (12, 6), (0, 6)])
         .interest("a", position=(6, 1.5), radius=1)
         .interest("b", position=(6, 4.5), radius=1)
         .exit("out", polygon=[(11.5, 0), (12, 0), (12, 6), (11.5, 6)])
         .population("p", goals=[choice, "out"], spawn=[(0.5, 0.5), (3, 0.5), (3, 5.5), (0.5, 5.5)], groups=4))
    assert b.to_dict()["populations"][0]["goals"] == [choice, "out"]
    assert throng.scenario(b).points == ["a", "b", "out"]
    # Each group's choice is an event: its leader, the point chosen (a), the goal's slot (b).
    with throng.Simulation(throng.scenario(b), threads=1) as sim:
        sim.step(1)
        chosen = [e for e in sim.events() if e["kind"] == "waypoint_chosen"]
    assert len(chosen) == 4
    assert all(e["a"] in (0, 1) and e["b"] == 0 for e in chosen)
    assert {e["a"] for e in chosen} == {0, 1}, "least targeted: both stands"


def test_builder_refuses_bad_coordinates():
    with pytest.raises(ValueError):
        throng.ScenarioBuilder().walkable([(0, 0), (1, math.inf), (1, 1)])
    with pytest.raises(TypeError):
        throng.ScenarioBuilder().walkable("square")


def test_builder_takes_shapely_polygons_and_recordings_give_them_back(tmp_path):
    # python3-shapely (scripts/deps.sh): a polygon with a hole becomes walkable + obstacle; the
    # recording's walkable area comes back as a shapely geometry with the hole cut out.
    from shapely.geometry import Polygon
    room = Polygon([(0, 0), (12, 0), (12, 6), (0, 6)], holes=[[(5, 2), (7, 2), (7, 4), (5, 4)]])
    b = (throng.ScenarioBuilder("shapely", seed=3, duration=15)
         .walkable(room)
         .exit("out", polygon=Polygon([(11.5, 0), (12, 0), (12, 6), (11.5, 6)]))
         .population("p", goals=["out"], spawn=Polygon([(0.5, 0.5), (3, 0.5), (3, 5.5), (0.5, 5.5)]), groups=10))
    doc = b.to_dict()
    assert doc["walkable"] == [[[0.0, 0.0], [12.0, 0.0], [12.0, 6.0], [0.0, 6.0], [0.0, 0.0]]]
    assert doc["obstacles"] == [[[5.0, 2.0], [7.0, 2.0], [7.0, 4.0], [5.0, 4.0], [5.0, 2.0]]]  # the hole
    out = str(tmp_path / "shapely.sqlite")
    sim = throng.Simulation(throng.scenario(b), record=out)
    sim.run()
    sim.close()
    area = throng.read_recording(out).walkable_polygon()
    assert area.area == pytest.approx(12 * 6 - 2 * 2, rel=0.02)  # the hole is cut out
    assert not area.contains(Polygon([(5.5, 2.5), (6.5, 2.5), (6.5, 3.5), (5.5, 3.5)]))
    assert area.contains(Polygon([(1, 1), (2, 1), (2, 2), (1, 2)]))


def test_builder_adds_escalators_and_lifts_that_carry_people():
    # Two rooms 4 m apart with nothing walkable between them: a moving walkway (an escalator on one
    # floor) carries five people from the west room to the east one, 8 m at 0.5 m/s; a lift would be
    # built the same way (.elevator).
    b = (throng.ScenarioBuilder("walkway", seed=3, duration=120)
         .walkable([(0, 0), (6, 0), (6, 6), (0, 6)])
         .walkable([(10, 0), (16, 0), (16, 6), (10, 6)])
         .interest("west", polygon=[(4, 2), (6, 2), (6, 4), (4, 4)])
         .interest("east", polygon=[(10, 2), (12, 2), (12, 4), (10, 4)])
         .exit("out", polygon=[(15, 0), (16, 0), (16, 6), (15, 6)])
         .escalator("walkway", "west", "east", speed=0.5, headway=1.0)
         .population("p", goals=["west", "out"], spawn=[(0.5, 0.5), (3, 0.5), (3, 5.5), (0.5, 5.5)], groups=5))
    assert b.to_dict()["transports"] == [{"id": "walkway", "kind": "escalator", "stops": ["west", "east"],
                                          "speed": 0.5, "headway": 1.0}]
    lift = throng.ScenarioBuilder().elevator("lift", ["a", "b"], capacity=4, transfer_time=1.0).to_dict()
    assert lift["transports"] == [{"id": "lift", "kind": "elevator", "stops": ["a", "b"], "capacity": 4,
                                   "transferTime": 1.0}]
    with throng.Simulation(throng.scenario(b), threads=1) as sim:
        events = []
        while not sim.finished and sim.time < 120:
            sim.step(10)
            events += sim.events()
    east = throng.scenario(b).points.index("east")
    arrived = sorted(e["tick"] for e in events if e["kind"] == "goal_reached" and e["a"] == east)
    assert len(arrived) == 5, "all five carried across"
    assert min(y - x for x, y in zip(arrived, arrived[1:])) >= 20, "one a headway (1 s = 20 ticks) at most"
    assert sum(1 for e in events if e["kind"] == "exit") == 5
