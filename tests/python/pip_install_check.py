#!/usr/bin/python3
"""The pip_install test (tests/python/CMakeLists.txt): `pip install .` as a user runs it, then the
installed package used from outside the checkout.

  1. python3 -m venv --system-site-packages V (numpy and pandas from Debian, pip from ensurepip);
  2. V/bin/pip install --no-build-isolation --no-index <source> with THRONG_CMAKE_BUILD_DIR=<build>
     (setup.py builds the module in that configured build: quick when it is current);
  3. V/bin/python -I (no PYTHONPATH, no script directory) in an empty directory: the package comes
     from the venv, holds the extension, the stubs and py.typed, runs a 2-second scenario recorded
     to SQLite and read back, and ends on the CLI's state hash for the same scenario.

Fails (exit 1, saying which step) when any of that does not hold.
usage: pip_install_check.py SOURCE_DIR CMAKE_BUILD_DIR THRONG_CLI
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

SCENARIO = {"format": "throng/1", "name": "pip-check", "seed": 4, "duration": 2.0,
            "walkable": [[[0, 0], [12, 0], [12, 4], [0, 4]]],
            "points": [{"id": "exit", "kind": "exit", "polygon": [[11, 0], [12, 0], [12, 4], [11, 4]]}],
            "populations": [{"id": "walkers", "groups": 12, "size": 1, "radius": 0.2, "goals": ["exit"],
                             "spawn": {"polygon": [[0.5, 0.5], [5, 0.5], [5, 3.5], [0.5, 3.5]]}}]}

# Run by the venv's interpreter in isolated mode, from an empty directory.
CHECK = r'''
import json, os, sys
import throng
pkg = os.path.dirname(os.path.abspath(throng.__file__))
assert pkg.startswith(os.path.abspath(sys.prefix)), f"throng imported from {pkg}, not from the venv {sys.prefix}"
names = set(os.listdir(pkg))
missing = [n for n in ("__init__.py", "build.py", "recording.py", "analysis.py", "_throng.pyi", "py.typed") if n not in names]
assert not missing, f"the installed package lacks {missing}"
assert any(n.startswith("_throng.") and n.endswith(".so") for n in names), "the installed package lacks the _throng extension"
with throng.Simulation(throng.Scenario.load(sys.argv[1]), threads=2, record="run.sqlite") as sim:
    sim.run()
    view = sim.view()
    assert abs(sim.time - 2.0) < 1e-6 and len(view) == 12, (sim.time, len(view))
    state_hash = format(sim.state_hash, "016x")
rec = throng.read_recording("run.sqlite")
assert rec.trajectory["frame"].max() == 20 and rec.trajectory["id"].nunique() == 12, rec.trajectory.describe()
print(json.dumps({"state_hash": state_hash, "package": pkg}))
'''


def step(what, cmd, **kw):
    print(f"pip_install: {what}: {' '.join(cmd)}", flush=True)
    done = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if done.returncode != 0:
        print(done.stdout[-6000:], done.stderr[-6000:], sep="\n")
        sys.exit(f"pip_install: FAILED at: {what} (exit {done.returncode})")
    return done.stdout


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    source, build, cli = (os.path.abspath(a) for a in sys.argv[1:])
    work = tempfile.mkdtemp(prefix="throng-pip-")
    try:
        venv = os.path.join(work, "venv")
        step("create a venv", [sys.executable, "-m", "venv", "--system-site-packages", venv])
        env = {k: v for k, v in os.environ.items() if not k.startswith("PYTHON")}
        env.update(THRONG_CMAKE_BUILD_DIR=build, PIP_DISABLE_PIP_VERSION_CHECK="1", PIP_NO_CACHE_DIR="1")
        step("pip install the checkout", [os.path.join(venv, "bin", "pip"), "install", "--no-build-isolation", "--no-index",
                                          source], env=env, cwd=work)
        run_dir = os.path.join(work, "elsewhere")
        os.mkdir(run_dir)
        scenario = os.path.join(run_dir, "pip-check.json")
        with open(scenario, "w") as f:
            json.dump(SCENARIO, f)
        result = json.loads(step("use the installed package", [os.path.join(venv, "bin", "python"), "-I", "-c", CHECK, scenario],
                                 env=env, cwd=run_dir).strip().splitlines()[-1])
        summary = json.loads(step("the CLI on the same scenario", [cli, "run", scenario, "--json", "-q"], cwd=run_dir))
        if result["state_hash"] != summary["state_hash"]:
            sys.exit(f"pip_install: FAILED: the installed module ends on {result['state_hash']}, the CLI on {summary['state_hash']}")
        print(f"pip_install: ok: {result['package']} runs the scenario as the CLI does ({result['state_hash']})")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
