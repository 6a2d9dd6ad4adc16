"""pytest set-up for `import throng` (tests/python/CMakeLists.txt sets PYTHONPATH to build/python and
THRONG_BIN to the CLI)."""
import os

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


@pytest.fixture
def root():
    return ROOT


@pytest.fixture
def cli():
    path = os.environ.get("THRONG_BIN")
    if not path or not os.path.exists(path):
        pytest.fail("THRONG_BIN must name the throng CLI (ctest sets it)")
    return path


def corridor(n=20, duration=30.0, seed=3, width=4.0):
    """A 20 m long corridor `width` m wide with n agents walking to its far end (dict)."""
    w = width
    return {"format": "throng/1", "name": "py-corridor", "seed": seed, "duration": duration,
            "walkable": [[[0, 0], [20, 0], [20, w], [0, w]]],
            "points": [{"id": "exit", "kind": "exit", "polygon": [[19, 0], [20, 0], [20, w], [19, w]]}],
            "populations": [{"id": "walkers", "groups": n, "size": 1,
                             "spawn": {"polygon": [[0.5, 0.5], [6, 0.5], [6, w - 0.5], [0.5, w - 0.5]]},
                             "goals": ["exit"], "speed": {"mean": 1.3, "sd": 0.2}, "radius": 0.2}]}
