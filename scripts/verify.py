#!/usr/bin/python3
"""Verification of throng against the standard tests of evacuation simulators (issue 18).

Runs the bundled verification scenarios (verification/<suite>/, each beside a text of the test,
its criterion and its source), measures the recordings with scripts/validation/measures.py and
prints one row per test: criterion, measured, PASS / FAIL / XFAIL (expected to fail, with the
reason) / XPASS (expected to fail but passed: update the expectation). Suites:
  rimea  RiMEA guideline 4.1.1 tests 1-16
  nist   NIST Technical Note 1822 (Ronchi et al. 2013) tests 1.1, 2.1-2.10, 3.1-3.3, 4.1, 5.1-5.2
  iso    ISO 20414:2020 tests 7, 12, 13, 17 and 21, those that differ from RiMEA's and NIST's
         (verification/iso/README.md maps the other ISO tests to the RiMEA and NIST tests that cover them)

usage: /usr/bin/python3 scripts/verify.py [--suite rimea|nist|iso|all] [--test ID[,ID]]... [--model NAME[,NAME]]
           [--threads N] [--json FILE] [--report DIR] [--keep DIR] [--list] [--throng PATH]

Exit status: 0 when every test is PASS or XFAIL; 1 when one FAILs or XPASSes (or a run fails);
2 for bad flags (an unknown suite, test or model, a missing binary); 130 when interrupted.
`throng verify ...` runs this script with the same flags. Needs numpy and matplotlib from Debian
(python3-numpy, python3-matplotlib), hence /usr/bin/python3. docs/verification.md has the results.
"""
import argparse
import contextlib
import datetime
import difflib
import json
import os
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from verification import core as C  # noqa: E402
from verification import iso as I  # noqa: E402
from verification import nist as N  # noqa: E402
from verification import rimea as R  # noqa: E402
from validation import measures as M  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SUITES = ("rimea", "nist", "iso")
MODELS = ("orca", "avm", "cfsm")


def all_tests():
    return R.tests() + N.tests() + I.tests()


def progress(text):
    print(f"verify: {text}", file=sys.stderr, flush=True)


class UsageError(Exception):
    pass


class Parser(argparse.ArgumentParser):
    def error(self, message):
        raise UsageError(message)


def parse_args(argv):
    ap = Parser(prog="verify.py", description=__doc__.split("\n\n")[0],
                formatter_class=argparse.RawDescriptionHelpFormatter,
                epilog="\n\n".join(p for p in __doc__.split("\n\n")[1:] if not p.startswith("usage")))
    ap.add_argument("--suite", default="all", metavar="NAME", help="rimea, nist, iso or all (default all)")
    ap.add_argument("--test", action="append", default=[], metavar="ID[,ID]",
                    help="run only these tests (repeatable; e.g. rimea-1,nist-2.1); --list shows the ids")
    ap.add_argument("--model", metavar="NAME[,NAME]",
                    help=f"run every test with each of these operational models, side by side ({', '.join(MODELS)}, or all; "
                         "default: the scenarios' own, i.e. the engine default)")
    ap.add_argument("--threads", type=int, default=2, metavar="N",
                    help="throng runs at a time, one thread each (default 2; results do not depend on it)")
    ap.add_argument("--json", metavar="FILE", help="write the results as JSON to FILE ('-' = stdout, the table then "
                                                   "goes to stderr)")
    ap.add_argument("--report", metavar="DIR", help="write DIR/verification.md, its PNG plots and DIR/verification.json")
    ap.add_argument("--keep", metavar="DIR", help="keep the scenarios (model applied) and recordings in DIR")
    ap.add_argument("--list", action="store_true", help="list the selected tests and their expectations; run nothing")
    ap.add_argument("--throng", default=os.path.join(ROOT, "build", "apps", "throng", "throng"), metavar="PATH",
                    help="the throng binary (default: build/apps/throng/throng)")
    args = ap.parse_args(argv)
    if args.suite not in SUITES + ("all",):
        ap.error(f"--suite: unknown suite '{args.suite}'; expected rimea, nist, iso or all")
    if args.threads < 1:
        ap.error("--threads: at least 1")
    tests = [t for t in all_tests() if args.suite == "all" or t.suite == args.suite]
    wanted = [w.strip().lower() for spec in args.test for w in spec.split(",") if w.strip()]
    if args.test and not wanted:
        ap.error("--test: no test id given")
    if wanted:
        ids = {t.id for t in tests}
        bad = [w for w in wanted if w not in ids]
        if bad:
            # Suggest the ids nearest the first bad one (its own suite's first), not the first in order.
            near = difflib.get_close_matches(bad[0], sorted(ids), n=4, cutoff=0.5) or \
                sorted(i for i in ids if i.split("-")[0] == bad[0].split("-")[0])[:4] or sorted(ids)[:4]
            ap.error(f"--test: unknown test {', '.join(bad)} in suite {args.suite}; expected ids like "
                     f"{', '.join(near)} (--list shows all)")
        tests = [t for t in tests if t.id in wanted]
    args.tests = tests
    args.models = [None]
    if args.model is not None:
        names = [m.strip() for m in args.model.split(",") if m.strip()]
        names = [n for m in names for n in (MODELS if m == "all" else (m,))]
        bad = [m for m in names if m not in MODELS]
        if bad or not names:
            ap.error(f"--model: unknown model {', '.join(bad) or '(none)'}; expected some of {', '.join(MODELS)}")
        args.models = list(dict.fromkeys(names))
    if not args.list and not os.access(args.throng, os.X_OK):
        ap.error(f"throng binary {args.throng} not found or not executable (use --throng)")
    return args


def default_model(binary, tmp):
    """The name of the model the engine gives a population that names none (from a 0.1 s run)."""
    probe = {"format": "throng/1", "walkable": [[[0, 0], [6, 0], [6, 6], [0, 6]]], "populations": [
        {"id": "probe", "groups": 1, "spawn": {"polygon": [[1, 1], [5, 1], [5, 5], [1, 5]]}}]}
    path, rec = os.path.join(tmp, "model-probe.json"), os.path.join(tmp, "model-probe.sqlite")
    with open(path, "w") as f:
        json.dump(probe, f)
    res = subprocess.run([args_binary(binary), "run", path, "--out", rec, "--force", "--quiet", "--duration", "0.1"],
                         capture_output=True)
    if res.returncode != 0 or not os.path.exists(rec):
        return "default"  # the tests' own runs will fail and say why
    return M.recording_models(rec).get("probe", "default")


def args_binary(binary):
    return os.path.abspath(binary)


def evaluate(test, futures, model, model_name):
    """(status, reason, checks, data, error) of one test with one model."""
    reason = test.expectation(model_name)
    if not test.runs:
        return C.XFAIL, reason, [], None, None
    results = {}
    for run, fut in zip(test.runs, futures):
        res = fut.result()
        if res.get("error"):
            return C.FAIL, reason, [C.Check("the scenario runs", res["error"], False)], None, res["error"]
        results[run.key] = res
    try:
        checks, data = test.measure(results, {"model": model_name})
    except Exception as e:  # a measurement that breaks is a failed test, said plainly
        return C.FAIL, reason, [C.Check("the measurement runs", f"{type(e).__name__}: {e}", False)], None, str(e)
    return C.status_of(checks, reason), reason, checks, data, None


def run_all(args, tmp):
    runner = C.Runner(args_binary(args.throng), tmp, args.threads)
    try:
        return _run_all(args, tmp, runner)
    except KeyboardInterrupt:
        runner.stop()
        raise


def _run_all(args, tmp, runner):
    engine_default = default_model(args.throng, tmp)
    jobs = []
    for test in args.tests:
        for model in args.models:
            futures = [runner.submit(run, model, model or "default") for run in test.runs]
            jobs.append((test, model, futures))
    rows = []
    for k, (test, model, futures) in enumerate(jobs, 1):
        started = time.time()
        name = model or engine_default
        tag = model or f"{engine_default} (default)"
        status, reason, checks, data, error = evaluate(test, futures, model, name)
        rows.append({"id": test.id, "suite": test.suite, "title": test.title, "criterion": test.criterion,
                     "source": test.source, "doc": test.doc, "model": name, "model_tag": tag, "status": status,
                     "reason": reason, "checks": [c.as_dict() for c in checks], "error": error, "_data": data,
                     "_test": test})
        loud = "  <-- expected to fail but PASSED: update its expectation" if status == C.XPASS else ""
        progress(f"[{k}/{len(jobs)}] {test.id} ({tag}): {status}{loud} ({time.time() - started:.1f} s)")
    runner.close()
    return rows, runner.count, engine_default


def print_table(rows, out=sys.stdout):
    wc = max([len(c["criterion"]) for r in rows for c in r["checks"]] + [len(r["criterion"]) for r in rows] + [9])
    wc = min(wc, 80)
    print(f"{'test':<10} {'model':<16} {'result':<6}  {'criterion':<{wc}}  measured", file=out)
    for r in rows:
        checks = r["checks"] or [{"criterion": r["criterion"], "measured": "not measured", "ok": False}]
        for i, c in enumerate(checks):
            mark = "" if c["ok"] is None else ("ok " if c["ok"] else "NO ")
            head = f"{r['id']:<10} {r['model_tag']:<16} {r['status']:<6}" if i == 0 else " " * 34
            print(f"{head}  {c['criterion'][:wc]:<{wc}}  {mark}{c['measured']}", file=out)
        if r["reason"]:
            label = "XPASS: expected to fail because" if r["status"] == C.XPASS else "expected to fail:"
            print(f"{'':<34}  {label} {r['reason']}", file=out)
    counts = {s: sum(r["status"] == s for r in rows) for s in (C.PASS, C.FAIL, C.XFAIL, C.XPASS)}
    print(", ".join(f"{n} {s}" for s, n in counts.items()), file=out)
    if counts[C.XPASS]:
        print(f"XPASS: {', '.join(r['id'] + ' (' + r['model_tag'] + ')' for r in rows if r['status'] == C.XPASS)} "
              "passed although expected to fail: update their expectation (xfail) in scripts/verification/", file=out)
    return counts


def write_report(rows, directory, command, wall):
    os.makedirs(directory, exist_ok=True)
    lines = ["# throng verification results", "",
             f"`{command}` on {datetime.date.today().isoformat()}, {wall:.0f} s.", "",
             "| test | model | result | criterion | measured |", "|---|---|---|---|---|"]
    for r in rows:
        checks = r["checks"] or [{"criterion": r["criterion"], "measured": "not measured", "ok": None}]
        for i, c in enumerate(checks):
            mark = "" if c["ok"] is None else ("✓ " if c["ok"] else "✗ ")
            first = i == 0
            link = f"[{r['id']}](../../{r['doc']})" if first else ""
            lines.append(f"| {link} | "
                         f"{r['model_tag'] if first else ''} | {r['status'] if first else ''} | {c['criterion']} | "
                         f"{mark}{c['measured']} |")
        if r["reason"]:
            lines.append(f"| | | | *expected to fail:* {r['reason']} | |")
    plots = {}
    for r in rows:
        if r["_test"].plot and r["_data"] is not None:
            plots.setdefault(r["id"], (r["_test"], {}))[1][r["model_tag"]] = r["_data"]
    lines.append("")
    for tid, (test, datas) in plots.items():
        name = f"verification-{tid}.png"
        test.plot(datas, os.path.join(directory, name), f"{tid}: {test.title}")
        lines += [f"![{tid}]({name})", ""]
    with open(os.path.join(directory, "verification.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def list_tests(tests, models):
    for t in tests:
        for m in models:
            reason = t.expectation(m) if m else t.xfail
            exp = "must pass" if not reason else (f"expected to fail: {reason}" if isinstance(reason, str) else
                                                  "expected to fail with " + ", ".join(
                                                      f"{k}: {v}" for k, v in reason.items()))
            print(f"{t.id:<10} {(m or ''):<5} {t.title} — {t.criterion} [{t.source}; {t.doc}] {exp}")


def display_command(args):
    """The run as a `throng verify` command line (defaults and paths to the binary left out)."""
    words = ["throng verify", f"--suite {args.suite}"]
    words += [f"--test {','.join(t.id for t in args.tests)}"] if args.test else []
    words += [f"--model {','.join(args.models)}"] if args.models != [None] else []
    words += [f"--threads {args.threads}"] if args.threads != 2 else []
    words += [f"--report {args.report}"] if args.report else []
    words += [f"--json {args.json}"] if args.json else []
    return " ".join(words)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    try:
        args = parse_args(argv)
    except UsageError as e:
        print(f"verify.py: error: {e}\nRun 'verify.py --help' for the flags.", file=sys.stderr)
        return 2
    if args.list:
        list_tests(args.tests, args.models)
        return 0
    started = time.time()
    if args.keep:
        os.makedirs(args.keep, exist_ok=True)
    with (contextlib.nullcontext(args.keep) if args.keep else tempfile.TemporaryDirectory(prefix="throng-verify-")) as tmp:
        rows, runs, engine_default = run_all(args, tmp)
        wall = time.time() - started
        table_out = sys.stderr if args.json == "-" else sys.stdout  # stdout is the JSON's then
        counts = print_table(rows, table_out)
        print(f"({len(rows)} tests, {runs} throng runs, {wall:.1f} s)", file=table_out)
        command = display_command(args)
    summary = {"command": command, "date": datetime.date.today().isoformat(), "engine_default_model": engine_default,
               "threads": args.threads, "wall_time_s": wall, "runs": runs, "counts": counts,
               "tests": [{k: v for k, v in r.items() if not k.startswith("_")} for r in rows]}
    text = json.dumps(summary, indent=1, allow_nan=False, default=float)
    if args.report:
        write_report(rows, args.report, command, wall)
        with open(os.path.join(args.report, "verification.json"), "w") as f:
            f.write(text + "\n")
    if args.json == "-":
        print(text)
    elif args.json:
        with open(args.json, "w") as f:
            f.write(text + "\n")
    return 1 if counts[C.FAIL] or counts[C.XPASS] else 0


def _terminate(signum, frame):
    raise KeyboardInterrupt


if __name__ == "__main__":
    signal.signal(signal.SIGTERM, _terminate)
    try:
        sys.exit(main())
    except KeyboardInterrupt:  # Ctrl-C: the throng runs stop too (same process group)
        print("verify.py: interrupted", file=sys.stderr)
        sys.exit(130)
