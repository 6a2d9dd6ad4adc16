"""The machinery of scripts/verify.py: what a verification test is (Test, Run, Check), how its
status follows from its checks and its expectation, and the Runner that simulates the scenario
files with `throng run` (each (scenario, overrides, model) once, even when several tests or
suites share it).

A test's `xfail` is its one expectation field: None (it must pass), a reason string (expected to
fail with every model) or a dict model name -> reason ("*" for every other model). A test whose
checks all hold while it is expected to fail is an XPASS: the expectation must be updated.
"""
import concurrent.futures
import copy
import json
import os
import subprocess
import threading

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENARIOS = os.path.join(ROOT, "verification")

PASS, FAIL, XFAIL, XPASS = "PASS", "FAIL", "XFAIL", "XPASS"


class Run:
    """One simulation a test needs: a scenario file under verification/, optionally edited (a
    function scenario -> scenario, named by `edit_tag` so that the cache can tell edits apart)."""

    def __init__(self, key, file, edit=None, edit_tag="", seed=1, duration=None):
        self.key, self.file, self.edit, self.edit_tag = key, file, edit, edit_tag
        self.seed, self.duration = seed, duration


class Check:
    """One criterion of a test: what must hold, what was measured, whether it holds (None: reported
    only)."""

    def __init__(self, criterion, measured, ok, value=None, unit=""):
        self.criterion, self.measured, self.ok, self.value, self.unit = criterion, measured, ok, value, unit

    def as_dict(self):
        return {"criterion": self.criterion, "measured": self.measured, "ok": self.ok,
                "value": self.value, "unit": self.unit}


def band(criterion, value, lo=None, hi=None, unit="", fmt="{:.2f}"):
    """A check that value lies in [lo, hi] (either may be None)."""
    if value is None:
        return Check(criterion, "—", False, None, unit)
    ok = (lo is None or value >= lo) and (hi is None or value <= hi)
    return Check(criterion, (fmt.format(value) + (f" {unit}" if unit else "")), bool(ok), float(value), unit)


class Test:
    """A verification test. `measure(results, ctx)` returns (checks, data): `results` maps each
    Run's key to {"recording", "summary"}; `data` is JSON-able and goes to `plot(datas, path)` with
    datas = {model tag: data}. A test with no runs is not measured; it needs an `xfail` reason."""

    def __init__(self, tid, suite, title, criterion, source, doc, runs=(), measure=None, xfail=None, plot=None):
        self.id, self.suite, self.title, self.criterion, self.source = tid, suite, title, criterion, source
        self.doc, self.runs, self.measure, self.xfail, self.plot = doc, list(runs), measure, xfail, plot

    def expectation(self, model):
        """The reason this test is expected to fail with `model`, or None."""
        if self.xfail is None or isinstance(self.xfail, str):
            return self.xfail
        return self.xfail.get(model, self.xfail.get("*"))


def status_of(checks, reason):
    ok = all(c.ok is not False for c in checks) and bool(checks)
    if reason:
        return XPASS if ok else XFAIL
    return PASS if ok else FAIL


def with_model(scenario, model):
    s = copy.deepcopy(scenario)
    if model is not None:
        for p in s.get("populations", []):
            p["model"] = copy.deepcopy(model)
    return s


class Runner:
    """Runs `throng run` on verification scenarios (model applied) into `tmp`, `threads` runs in
    parallel (each single-threaded: results do not depend on the thread count). Results are cached
    by (file, edit, model, seed, duration)."""

    def __init__(self, binary, tmp, threads):
        self.binary, self.tmp, self.threads = binary, tmp, threads
        self.pool = concurrent.futures.ThreadPoolExecutor(max_workers=threads)
        self.lock = threading.Lock()
        self.cache = {}
        self.count = 0
        self.live = set()      # running `throng run` processes
        self.stopped = False

    def close(self):
        self.pool.shutdown(wait=True)

    def stop(self):
        """Interrupted: no new runs, the running ones terminated."""
        with self.lock:
            self.stopped = True
            for proc in list(self.live):
                proc.terminate()
        self.pool.shutdown(wait=True, cancel_futures=True)

    def _simulate(self, run, model, label):
        with open(os.path.join(SCENARIOS, run.file)) as f:
            scenario = json.load(f)
        if run.edit is not None:
            scenario = run.edit(scenario)
        scenario = with_model(scenario, model)
        path = os.path.join(self.tmp, f"{label}.json")
        with open(path, "w") as f:
            json.dump(scenario, f)
        rec = os.path.join(self.tmp, f"{label}.sqlite")
        cmd = [self.binary, "run", path, "--out", rec, "--force", "--seed", str(run.seed), "--quiet", "--json",
               "--threads", "1"]
        if run.duration is not None:
            cmd += ["--duration", str(run.duration)]
        with self.lock:
            if self.stopped:
                return {"error": "interrupted"}
            proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            self.live.add(proc)
        out, err = proc.communicate()
        with self.lock:
            self.live.discard(proc)
        res = subprocess.CompletedProcess(cmd, proc.returncode, out, err)
        if res.returncode != 0:
            lines = (res.stderr.strip() or res.stdout.strip()).splitlines()
            return {"error": f"throng run {run.file} exit {res.returncode}: " + (lines[0] if lines else "")}
        return {"recording": rec, "summary": json.loads(res.stdout.strip().splitlines()[-1]), "scenario": scenario}

    def submit(self, run, model, model_tag):
        """A future of the run's result (shared with every earlier request of the same run)."""
        key = (run.file, run.edit_tag, json.dumps(model, sort_keys=True), run.seed, run.duration)
        with self.lock:
            if key not in self.cache:
                self.count += 1
                stem = os.path.splitext(run.file)[0].replace("/", "-")
                label = f"{stem}{'-' + run.edit_tag if run.edit_tag else ''}-{model_tag}-s{run.seed}"
                self.cache[key] = self.pool.submit(self._simulate, run, model, label)
            return self.cache[key]
