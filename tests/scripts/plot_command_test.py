#!/usr/bin/python3
"""End-to-end test of `throng plot` (ctest: plot_command): records scenarios/bottleneck.json for 20 s
and plots it. Fails when a figure is missing, blank or the wrong size, when the numbers --json prints
are out of their plausible bands (the flow through the 1 m door, the default line in front of the
exit, the density and speed heatmaps, the fundamental diagram's area), when --help misses a flag, or
when a scenario's own measurement line and area are not the defaults (or flags do not override them),
when bad input does not give one clear message and exit 1 (bad flags: exit 2).

usage: plot_command_test.py THRONG_BINARY SOURCE_DIR"""
import json
import os
import sqlite3
import struct
import subprocess
import sys
import tempfile

FLAGS = ["--out", "--what", "--line", "--area", "--cell", "--density", "--speed", "--json"]
FIGURES = ["trajectories", "density", "speed", "flow", "fd"]


def fail(msg):
    print(f"plot_command_test: FAIL: {msg}")
    sys.exit(1)


def plot(binary, *args):
    return subprocess.run([binary, "plot", *args], capture_output=True, text=True, timeout=120)


def png_size(path):
    """(width, height) from the PNG's IHDR chunk; fails unless the file is a PNG."""
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        fail(f"{path} is not a PNG")
    return struct.unpack(">II", head[16:24])


def check_png(path, min_bytes=15000):
    if not os.path.isfile(path):
        fail(f"{path} was not written")
    w, h = png_size(path)
    size = os.path.getsize(path)
    if w < 500 or h < 350 or size < min_bytes:
        fail(f"{path}: {w}x{h} pixels, {size} bytes; expected a real figure (>= 500x350, >= {min_bytes} bytes)")
    return w, h


def record(binary, src, tmp):
    rec = os.path.join(tmp, "bottleneck.sqlite")
    res = subprocess.run([binary, "run", os.path.join(src, "scenarios", "bottleneck.json"), "--duration", "20",
                          "--out", rec, "--quiet"], capture_output=True, text=True, timeout=120)
    if res.returncode != 0:
        fail(f"throng run bottleneck.json exited {res.returncode}: {res.stderr}")
    return rec


def check_defaults(binary, rec, tmp):
    """Every figure with the default line (in front of the exit) and area (behind it)."""
    out = os.path.join(tmp, "all")
    res = plot(binary, rec, "--out", out, "--json")
    if res.returncode != 0:
        fail(f"throng plot exited {res.returncode}: {res.stderr}")
    s = json.loads(res.stdout)
    if sorted(s["files"]) != sorted(FIGURES):
        fail(f"--json files {sorted(s['files'])}, expected {FIGURES}")
    sizes = {what: check_png(path) for what, path in s["files"].items()}
    # The world is 20 m x 10 m: the plan views are wider than high.
    for what in ("trajectories", "density", "speed"):
        if sizes[what][0] <= sizes[what][1] * 1.3:
            fail(f"{what}.png is {sizes[what]}: expected the 2:1 world's landscape shape")
    if s["agents"] != 100 or s["frames"] != 201 or s["fps"] != 10:
        fail(f"agents {s['agents']}, frames {s['frames']}, fps {s['fps']}: expected 100, 201, 10")
    (line,) = s["lines"]
    # The exit is x 19..20, y 4..6: the default line lies 1 m in front of it, across the room.
    if line["name"] != "exit" or sorted(line["line"]) != [0.0, 10.0, 18.0, 18.0]:
        fail(f"default line {line}: expected x = 18 from y = 0 to 10 (1 m in front of the exit)")
    # At most one passing per agent seen beyond the line (some of them have not reached the exit yet).
    beyond = sqlite3.connect(rec).execute(
        "SELECT COUNT(DISTINCT id) FROM trajectory_data WHERE pos_x >= 18.0").fetchone()[0]
    if not 10 <= line["passings"] <= beyond:
        fail(f"{line['passings']} passings toward the exit; expected 10 .. the {beyond} agents seen beyond the line")
    if s["density"]["max"] < 1.0 or not 0.05 < s["density"]["mean"] < 2.0:
        fail(f"density heatmap {s['density']}: expected a queue at the door (max >= 1/m²) and a low mean")
    if not 0.2 < s["speed"]["mean"] < 1.6 or s["speed"]["samples"] < 5000:
        fail(f"speed heatmap {s['speed']}: expected a mean speed of 0.2 .. 1.6 m/s over >= 5000 samples")
    area = s["area"]
    if area["frames"] < 20 or not 0.25 <= area["max_density"] <= 4 or not 0.5 < area["mean_speed"] < 1.8:
        fail(f"default area {area}: expected free walking behind the exit's line")
    return s


def check_voronoi(binary, rec, tmp, classic):
    """--density voronoi: a real figure, the same persons spread by Voronoi shares (mean within 15 %
    of the classic mean over the same cells), still a queue at the door; --speed voronoi."""
    res = plot(binary, rec, "--what", "density", "--density", "voronoi", "--out", os.path.join(tmp, "voronoi"), "--json")
    if res.returncode != 0:
        fail(f"throng plot --density voronoi exited {res.returncode}: {res.stderr}")
    s = json.loads(res.stdout)
    check_png(s["files"]["density"])
    d = s["density"]
    if d.get("definition") != "voronoi" or classic["density"].get("definition") != "classic":
        fail(f"definitions {d.get('definition')}, {classic['density'].get('definition')}: expected voronoi, classic")
    if abs(d["mean"] - classic["density"]["mean"]) > 0.15 * classic["density"]["mean"] or d["max"] < 1.0:
        fail(f"Voronoi density {d} against classic {classic['density']}: expected about the same mean, a queue (max >= 1/m²)")
    # --speed voronoi: each agent's speed spread over its Voronoi cell gives speeds to more cells than
    # the agents stood in, within walking speeds.
    res = plot(binary, rec, "--what", "speed", "--speed", "voronoi", "--out", os.path.join(tmp, "voronoi"), "--json")
    if res.returncode != 0:
        fail(f"throng plot --speed voronoi exited {res.returncode}: {res.stderr}")
    s = json.loads(res.stdout)
    check_png(s["files"]["speed"])
    v, c = s["speed"], classic["speed"]
    if v.get("definition") != "voronoi" or c.get("definition") != "classic":
        fail(f"speed definitions {v.get('definition')}, {c.get('definition')}: expected voronoi, classic")
    if not c["cells"] < v["cells"] or not 0.2 < v["max"] <= 3.0:
        fail(f"Voronoi speed {v} against classic {c}: expected more cells with a speed, walking speeds")


def check_door(binary, rec, tmp):
    """The door line and a measurement area in the queue before it."""
    res = plot(binary, rec, "--out", os.path.join(tmp, "door"), "--line", "10,4.5,10,5.5", "--area", "7,3.5,9,6.5",
               "--what", "flow,fd", "--json")
    if res.returncode != 0:
        fail(f"throng plot --line exited {res.returncode}: {res.stderr}")
    s = json.loads(res.stdout)
    if sorted(s["files"]) != ["fd", "flow"]:
        fail(f"--what flow,fd wrote {sorted(s['files'])}")
    (line,) = s["lines"]
    # A 1 m door: specific flows of 1 .. 2.5 /(m s) are measured (Seyfried et al. 2009, Kretz et al. 2006).
    if line["counted"] != "both directions" or not 20 <= line["passings"] <= 100 or not 0.8 <= line["flow"] <= 3.0:
        fail(f"door line {line}: expected 20 .. 100 passings at 0.8 .. 3 /s")
    if not 2.0 <= s["area"]["mean_density"] <= 7.0 or not s["area"]["mean_speed"] < 0.9:
        fail(f"area before the door {s['area']}: expected a dense, slow queue")
    plain = plot(binary, rec, "--out", os.path.join(tmp, "door"), "--line", "10,4.5,10,5.5", "--what", "flow")
    if plain.returncode != 0 or f"line line: {line['passings']} passings" not in plain.stdout:
        fail(f"the text summary does not give the passings: {plain.stdout}{plain.stderr}")


def check_scenario_measurements(binary, src, tmp):
    """A scenario's own "measurements" are the defaults (the door line, the queue area); flags override them."""
    with open(os.path.join(src, "scenarios", "bottleneck.json")) as f:
        scenario = json.load(f)
    scenario["measurements"] = [{"id": "door", "line": [[10, 4.5], [10, 5.5]]},
                                {"id": "queue", "polygon": [[7, 3.5], [9, 3.5], [9, 6.5], [7, 6.5]]}]
    path = os.path.join(tmp, "measured.json")
    with open(path, "w") as f:
        json.dump(scenario, f)
    rec = os.path.join(tmp, "measured.sqlite")
    res = subprocess.run([binary, "run", path, "--duration", "20", "--out", rec, "--quiet"], capture_output=True,
                         text=True, timeout=120)
    if res.returncode != 0:
        fail(f"throng run measured.json exited {res.returncode}: {res.stderr}")
    res = plot(binary, rec, "--out", os.path.join(tmp, "measured"), "--what", "flow,fd", "--json")
    if res.returncode != 0:
        fail(f"throng plot of measured.sqlite exited {res.returncode}: {res.stderr}")
    s = json.loads(res.stdout)
    (line,) = s["lines"]
    if line["name"] != "door" or line["line"] != [10, 4.5, 10, 5.5] or line["counted"] != "both directions":
        fail(f"scenario line {line}: expected the door line named 'door', counted both ways")
    if s["area"]["polygon"] != [[7, 3.5], [9, 3.5], [9, 6.5], [7, 6.5]] or not 2.0 <= s["area"]["mean_density"] <= 7.0:
        fail(f"scenario area {s['area']}: expected the queue before the door")
    res = plot(binary, rec, "--out", os.path.join(tmp, "measured"), "--what", "flow,fd", "--json",
               "--line", "12,0,12,10", "--area", "1,1,3,3")
    s = json.loads(res.stdout) if res.returncode == 0 else fail(f"throng plot --line exited {res.returncode}: {res.stderr}")
    if [l["name"] for l in s["lines"]] != ["line"] or s["area"]["polygon"] != [[1, 1], [3, 1], [3, 3], [1, 3]]:
        fail(f"--line/--area did not override the scenario's measurements: {s['lines']}, {s['area']}")


def check_errors(binary, rec, tmp):
    with open(os.path.join(tmp, "text.sqlite"), "w") as f:
        f.write("not a database\n")
    empty = os.path.join(tmp, "empty.sqlite")
    sqlite3.connect(empty).execute("CREATE TABLE t(x)").connection.commit()
    cases = [([os.path.join(tmp, "missing.sqlite")], 1, "not found"),
             ([os.path.join(tmp, "text.sqlite")], 1, "not a throng recording"),
             ([empty], 1, "not a throng recording"),
             ([rec, "--line", "3,3,3,3"], 1, "has no length"),
             ([rec, "--line", "100,100,101,101"], 1, "lies outside the walkable area"),
             ([rec, "--area", "1,1,1,5"], 1, "has no area"),
             ([rec, "--line", "1,2,3"], 2, "--line"),
             ([rec, "--line", "a,b,c,d"], 2, "--line"),
             ([rec, "--what", "heat"], 2, "--what"),
             ([rec, "--cell", "0"], 2, "--cell"),
             ([rec, "--density", "kde"], 2, "--density"),
             ([rec, "--speed", "fast"], 2, "--speed"),
             ([rec, "--bogus"], 2, "--bogus")]
    for args, code, text in cases:
        res = plot(binary, *args, "--out", os.path.join(tmp, "bad"))
        if res.returncode != code or text not in res.stderr:
            fail(f"throng plot {' '.join(args[1:]) or args[0]} exited {res.returncode}, expected {code} with "
                 f"'{text}': {res.stderr}")
        if code == 1 and len(res.stderr.strip().splitlines()) != 1:
            fail(f"throng plot {' '.join(args)}: expected one line on stderr: {res.stderr}")
    res = plot(binary, "--help")
    missing = [f for f in FLAGS if f not in res.stdout]
    if res.returncode != 0 or missing:
        fail(f"throng plot --help exited {res.returncode} or does not list {missing}")


def main():
    binary, src = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory(prefix="throng-plot-") as tmp:
        rec = record(binary, src, tmp)
        classic = check_defaults(binary, rec, tmp)
        check_voronoi(binary, rec, tmp, classic)
        check_door(binary, rec, tmp)
        check_scenario_measurements(binary, src, tmp)
        check_errors(binary, rec, tmp)
    print("plot_command_test: ok")


if __name__ == "__main__":
    main()
