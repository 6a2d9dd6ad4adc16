"""Type stubs of throng's native module (python/src/module.cpp). Units: m, s, m/s."""
from typing import Any, Iterable, Optional

import numpy as np
import numpy.typing as npt

class ScenarioError(ValueError):
    """A scenario, crowd or recording path was refused. `diagnostics`: every problem as a dict with
    source, line, column, pointer (JSON pointer), what, expected, hint and text (formatted)."""
    diagnostics: list[dict[str, Any]]

class StaleViewError(RuntimeError):
    """An AgentView (Simulation.view()) was used after the simulation stepped, ran or closed."""

class Scenario:
    @staticmethod
    def load(path: str) -> Scenario:
        """Reads and validates a scenario file; ScenarioError lists every problem."""
    @staticmethod
    def from_json(text: str, source: str = "<string>") -> Scenario:
        """Validates scenario JSON text; `source` names it in diagnostics."""
    @staticmethod
    def from_dict(d: dict[str, Any], source: str = "<dict>") -> Scenario:
        """Validates a scenario document given as a dict."""
    @property
    def name(self) -> str: ...
    @property
    def seed(self) -> int: ...
    @property
    def duration(self) -> float:
        """simulated time [s]"""
    @property
    def dt(self) -> float:
        """tick length [s]"""
    @property
    def json(self) -> str: ...
    @property
    def populations(self) -> list[str]: ...
    @property
    def points(self) -> list[str]: ...
    @property
    def models(self) -> list[str]:
        """the operational model of each population ("orca", "avm", "cfsm")"""

class AgentState:
    """The agents present at one tick (Simulation.agents()): read-only numpy arrays sharing the memory
    of a frame the engine copied for this tick; a snapshot, valid after later steps."""
    @property
    def tick(self) -> int: ...
    @property
    def time(self) -> float:
        """[s]"""
    def __len__(self) -> int: ...
    @property
    def id(self) -> npt.NDArray[np.uint32]:
        """stable agent ids (spawn order), ascending"""
    @property
    def x(self) -> npt.NDArray[np.float32]:
        """[m]"""
    @property
    def y(self) -> npt.NDArray[np.float32]:
        """[m]"""
    @property
    def z(self) -> npt.NDArray[np.float32]:
        """height [m] (zeros on a flat world)"""
    @property
    def vx(self) -> npt.NDArray[np.float32]:
        """[m/s]"""
    @property
    def vy(self) -> npt.NDArray[np.float32]:
        """[m/s]"""
    @property
    def ori_x(self) -> npt.NDArray[np.float32]: ...
    @property
    def ori_y(self) -> npt.NDArray[np.float32]: ...
    @property
    def mode(self) -> npt.NDArray[np.uint8]:
        """0 walking, 1 waiting, 2 acting"""
    @property
    def clip(self) -> npt.NDArray[np.uint16]: ...
    @property
    def phase(self) -> npt.NDArray[np.float32]:
        """position in the clip, [0, 1)"""

class AgentView:
    """The agents present now (Simulation.view()), read in place from the engine's own columns:
    read-only numpy arrays, nothing copied. Valid until the simulation steps, runs or closes; after
    that every access raises StaleViewError (arrays taken before remain readable memory but no longer
    describe the agents)."""
    @property
    def valid(self) -> bool:
        """False once the simulation stepped, ran or closed"""
    @property
    def tick(self) -> int:
        """the tick the view was taken at"""
    @property
    def time(self) -> float:
        """[s]"""
    def __len__(self) -> int: ...
    @property
    def id(self) -> npt.NDArray[np.uint32]:
        """stable agent ids (spawn order), ascending"""
    @property
    def group(self) -> npt.NDArray[np.uint32]:
        """stable group ids"""
    @property
    def x(self) -> npt.NDArray[np.float32]:
        """[m]"""
    @property
    def y(self) -> npt.NDArray[np.float32]:
        """[m]"""
    @property
    def z(self) -> npt.NDArray[np.float32]:
        """height [m] (a new array of zeros on a flat world)"""
    @property
    def vx(self) -> npt.NDArray[np.float32]:
        """[m/s]"""
    @property
    def vy(self) -> npt.NDArray[np.float32]:
        """[m/s]"""
    @property
    def ori_x(self) -> npt.NDArray[np.float32]:
        """unit heading"""
    @property
    def ori_y(self) -> npt.NDArray[np.float32]:
        """unit heading"""
    @property
    def mode(self) -> npt.NDArray[np.uint8]:
        """0 walking, 1 waiting, 2 acting"""
    @property
    def clip(self) -> npt.NDArray[np.uint16]:
        """motion clip playing (index into the scenario's clips)"""
    @property
    def phase(self) -> npt.NDArray[np.float32]:
        """position in the clip, [0, 1)"""

class Simulation:
    def __init__(self, scenario: Scenario, *, seed: Optional[int] = None, threads: int = 1,
                 record: Optional[str] = None, fps: float = 10.0, force: bool = False,
                 duration: Optional[float] = None) -> None:
        """seed, duration [s] override the scenario's; record: a SQLite file written as `throng run --out`
        writes it, fps frames per second; threads 0 = every hardware thread (results do not depend on it)."""
    def step(self, n: int = 1) -> None:
        """Advances n ticks; ValueError once finished."""
    def run(self, until: Optional[float] = None) -> float:
        """Steps until `until` [s] (default: the duration) or until everyone has left; returns the time [s]."""
    def close(self) -> None:
        """Flushes and closes the recording."""
    def __enter__(self) -> Simulation: ...
    def __exit__(self, *exc: Any) -> None: ...
    def agents(self) -> AgentState:
        """The agents present now as a snapshot (a copy made by the engine; valid after later steps)."""
    def view(self) -> AgentView:
        """The agents present now, read in place (no copy); valid until the next step, run or close."""
    def events(self) -> list[dict[str, Any]]:
        """Events since the last call: tick, time [s], agent, kind, a, b."""
    def agent(self, id: int) -> dict[str, Any]: ...
    def group(self, population: str, index: int) -> int: ...
    def group_info(self, id: int) -> dict[str, Any]: ...
    def guide(self, group: int, x: float, y: float, height: Optional[float] = None) -> None:
        """The group follows (x, y) [m] until release(group)."""
    def release(self, group: int) -> None: ...
    def insert_crowd(self, text: str, source: str = "<crowd>") -> int:
        """Queues a throng-crowd/1 document for the next tick; returns its index."""
    def remove_crowd(self, id: str) -> None:
        """The crowd's agents leave at the next tick."""
    def set_exit_open(self, id: str, open: bool) -> None:
        """Closes (open=False) or opens the exit `id` from the next tick; KeyError if it is no exit."""
    def exit_is_wall(self, id: str) -> bool:
        """Whether closing the exit `id` makes its floor a wall (False for an exit of a crowd inserted at run
        time, and for an id that is no exit)."""
    def remove_agents(self, ids: Iterable[int] | int) -> None:
        """These agents (stable ids; a list, a numpy array or one int) leave at the next tick, each with an
        exit event (a = b = 4294967295); their groups go on without them. ValueError naming every id not
        present now, listed twice or already queued (nothing is removed then)."""
    def add_agents(self, positions: list[tuple[float, float]], goals: list[str] | str, speed: float = 1.34,
                   radius: Optional[float] = None, id: Optional[str] = None) -> str:
        """Agents at these positions [m] from the next tick, walking to `goals`; returns the crowd id."""
    @property
    def stats(self) -> dict[str, Any]: ...
    @property
    def time(self) -> float:
        """[s]"""
    @property
    def tick(self) -> int: ...
    @property
    def finished(self) -> bool: ...
    @property
    def state_hash(self) -> int: ...
    @property
    def seed(self) -> int: ...
    @property
    def dt(self) -> float: ...
    @property
    def duration(self) -> float: ...
    @property
    def frame_stride(self) -> int: ...

def simd_path() -> str:
    """The vector path of the engine's hot loops in this process: 'avx2' or 'portable' (THRONG_SIMD
    picks one before import); every path gives the same trajectories."""
    ...
