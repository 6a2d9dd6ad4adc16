"""Property tests (Debian's python3-hypothesis): whatever a script passes, the API answers with a
Python exception or a result, never a crash, and the simulation stays usable."""
import math

from hypothesis import HealthCheck, given, settings, strategies as st

import throng
from conftest import corridor

SCENARIO = throng.scenario(corridor(n=6, duration=20))
numbers = st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10**12, 10**12))
anything = st.one_of(numbers, st.text(max_size=8), st.none(), st.lists(st.integers(), max_size=3))

EXPECTED = (ValueError, TypeError, KeyError, OverflowError, throng.ScenarioError, throng.StaleViewError)


@settings(max_examples=150, deadline=None, database=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.tuples(st.sampled_from(["step", "guide", "release", "agent", "group", "run", "insert", "remove",
                                           "remove_agents", "view"]),
                          anything, anything, anything), max_size=8))
def test_random_calls_never_crash(calls):
    sim = throng.Simulation(SCENARIO, threads=1)
    for name, a, b, c in calls:
        try:
            if name == "step":
                sim.step(a if isinstance(a, int) and 0 <= a <= 50 else a)
            elif name == "guide":
                sim.guide(a, b, c)
            elif name == "release":
                sim.release(a)
            elif name == "agent":
                sim.agent(a)
            elif name == "group":
                sim.group(a, b)
            elif name == "run":
                sim.run(a if not isinstance(a, (int, float)) or (isinstance(a, float) and not math.isfinite(a)) or abs(a) < 30 else 1.0)
            elif name == "insert":
                sim.insert_crowd(a if isinstance(a, str) else str(a))
            elif name == "remove":
                sim.remove_crowd(a)
            elif name == "remove_agents":
                sim.remove_agents(a)
            elif name == "view":
                v = sim.view()
                assert len(v.x) == len(v) and (b is None or v.valid)
        except EXPECTED:
            pass
    state = sim.agents()
    assert len(state.x) == len(state.id)
    assert all(math.isfinite(v) for v in state.x)


@settings(max_examples=100, deadline=None, database=None)
@given(st.dictionaries(st.sampled_from(["format", "walkable", "populations", "duration", "dt", "seed", "points"]),
                       anything, max_size=6))
def test_random_scenarios_are_refused_cleanly(doc):
    try:
        throng.Scenario.from_dict(doc)
    except EXPECTED:
        pass
