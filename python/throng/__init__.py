"""throng — a crowd engine for shared virtual worlds, from Python (docs/python.md).

Scenarios:   Scenario.load(path), Scenario.from_json(text), Scenario.from_dict(d), scenario(x)
             ScenarioBuilder: a scenario built in code (walkable area, obstacles, points, populations)
Simulation:  Simulation(scenario, seed=..., threads=..., record=...): step(n), run(until), agents()
             (snapshots), view() (the live columns, no copy, until the next step), events(),
             guide/release groups, insert_crowd/remove_crowd, remove_agents(ids), state_hash
Recordings:  read_recording(path) -> Recording (pandas DataFrames in PedPy's column names)
Analysis:    throng.analysis — classic density, speeds, passing times, flow, fundamental diagram
             (PedPy's definitions)
Errors:      ScenarioError (a ValueError) carries .diagnostics: every problem, located;
             StaleViewError (a RuntimeError): an AgentView used after a step.

Units are SI throughout: metres, seconds, metres per second.
"""
import json as _json
import os as _os

from ._throng import AgentState, AgentView, Scenario, ScenarioError, Simulation, StaleViewError, simd_path  # noqa: F401
from .build import ScenarioBuilder  # noqa: F401
from .recording import Recording, read_recording  # noqa: F401
from . import analysis  # noqa: F401

__all__ = ["AgentState", "AgentView", "Scenario", "ScenarioError", "Simulation", "StaleViewError", "ScenarioBuilder", "Recording",
           "read_recording", "analysis", "scenario", "simd_path"]


def _from_dict(d, source="<dict>"):
    """Validates a scenario given as a dict (the JSON document of docs/scenario-format.md)."""
    if not isinstance(d, dict):
        raise TypeError(f"Scenario.from_dict expects a dict, got {type(d).__name__}")
    try:
        text = _json.dumps(d, allow_nan=False)
    except ValueError as e:
        raise ScenarioError(f"{source}: the scenario holds a NaN or infinite number ({e}); expected finite numbers") from None
    return Scenario.from_json(text, source)


Scenario.from_dict = staticmethod(_from_dict)


def _add_agents(self, positions, goals, speed=1.34, radius=None, id=None):
    """Adds one agent at each (x, y) position [m] from the next tick, each walking its own way to
    `goals` (point ids): one throng-crowd/1 insertion of single-agent groups, each spawned as a
    `{"position": [x, y]}` spawn is (docs/scenario-format.md): on a free spot of the navmesh near the
    position — a group anchor within sqrt(2)·r + r of it, the agent within 0.9 m of the anchor, so
    at most about 1.4 m away at the default body (JuPedSim's add_agent places exactly; throng keeps
    its spawn rule so that a crowd and these agents spawn alike). `speed` [m/s]; `radius` [m] defaults to the scenario's
    default body. Returns the crowd id (remove_crowd(id) takes them out again)."""
    positions = [(float(x), float(y)) for x, y in positions]
    if isinstance(goals, str):
        goals = [goals]
    self._added = getattr(self, "_added", 0) + 1
    crowd_id = id or f"python-agents-{self._added}"
    populations = []
    for k, (x, y) in enumerate(positions):
        pop = {"id": f"{crowd_id}-{k}", "groups": 1, "size": 1, "spawn": {"position": [x, y]},
               "goals": list(goals), "speed": float(speed)}
        if radius is not None:
            pop["radius"] = float(radius)
        populations.append(pop)
    doc = {"format": "throng-crowd/1", "id": crowd_id, "populations": populations}
    try:
        text = _json.dumps(doc, allow_nan=False)
    except ValueError:
        raise ValueError("add_agents: positions, speed and radius must be finite numbers") from None
    self.insert_crowd(text, crowd_id)
    return crowd_id


Simulation.add_agents = _add_agents


def scenario(x, source=None):
    """A Scenario from a path (str or os.PathLike), a dict, JSON text or a ScenarioBuilder."""
    if isinstance(x, Scenario):
        return x
    if isinstance(x, ScenarioBuilder):
        return _from_dict(x.to_dict(), source or "<builder>")
    if isinstance(x, dict):
        return _from_dict(x, source or "<dict>")
    if isinstance(x, _os.PathLike):
        return Scenario.load(_os.fspath(x))
    if isinstance(x, str):
        if x.lstrip().startswith("{"):
            return Scenario.from_json(x, source or "<string>")
        return Scenario.load(x)
    raise TypeError(f"throng.scenario expects a path, dict, JSON text or ScenarioBuilder, got {type(x).__name__}")
