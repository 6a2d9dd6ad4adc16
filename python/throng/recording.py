"""read_recording: a throng recording (SQLite, JuPedSim trajectory format v2 plus throng_* tables,
docs/recording-format.md) as pandas DataFrames in PedPy's column names."""
import json
import os
import sqlite3

import pandas as pd


class Recording:
    """What read_recording returns.

    trajectory   DataFrame: frame, id, x, y, ori_x, ori_y (one row per agent and frame; PedPy's names)
    fps          frames per second [Hz]
    frame_time   DataFrame: frame, tick, time [s], agents
    walkable_area  the walkable area as WKT (one per geometry change: `geometries`); .walkable_polygon()
                 gives a shapely Polygon where shapely is installed
    agents       DataFrame: id, population, population_id, group_id, spawn_frame, exit_frame (None: still there)
    populations  DataFrame of throng_populations
    events       DataFrame: frame, tick, agent, kind, a, b
    points       DataFrame of throng_points (id, kind, position, region, action ...)
    coordinations  Common Ground interactions: group, initiator, respondents, plan, outcome, times [s]
    scripts      Common Ground action scripts: one row per entry of a character's script (step, plan,
                 motion, behaviour, target, planned and actual start and duration [s])
    metadata     dict of the metadata table (fps, seed, scenario text, models, completed ...)
    scenario     the scenario document (dict) the recording was made from
    """

    def __init__(self, path):
        if not os.path.isfile(path):
            raise FileNotFoundError(f"{path}: no such recording")
        uri = "file:" + os.path.abspath(path) + "?mode=ro"
        try:
            db = sqlite3.connect(uri, uri=True)
            tables = {r[0] for r in db.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
        except sqlite3.DatabaseError as e:
            raise ValueError(f"{path}: not a throng recording ({e}); expected an SQLite file written by throng run") from None
        try:
            missing = {"metadata", "trajectory_data", "geometry"} - tables
            if missing:
                raise ValueError(f"{path}: not a throng recording: tables {sorted(missing)} are missing; expected "
                                 "JuPedSim trajectory format version 2 (docs/recording-format.md)")
            self.metadata = dict(db.execute("SELECT key, value FROM metadata").fetchall())
            self.fps = float(self.metadata.get("fps", 10.0))
            self.trajectory = pd.read_sql_query(
                "SELECT frame, id, pos_x AS x, pos_y AS y, ori_x, ori_y FROM trajectory_data ORDER BY frame, id", db)
            self.geometries = [r[0] for r in db.execute("SELECT wkt FROM geometry ORDER BY rowid")]
            self.walkable_area = self.geometries[0] if self.geometries else ""
            self.frame_time = (pd.read_sql_query("SELECT frame, tick, time, agents FROM throng_frames ORDER BY frame", db)
                               if "throng_frames" in tables else pd.DataFrame(columns=["frame", "tick", "time", "agents"]))
            self.agents = (pd.read_sql_query("SELECT id, population, population_id, group_id, spawn_frame, exit_frame "
                                             "FROM throng_agents ORDER BY id", db)
                           if "throng_agents" in tables else pd.DataFrame())
            self.populations = (pd.read_sql_query("SELECT * FROM throng_populations ORDER BY idx", db)
                                if "throng_populations" in tables else pd.DataFrame())
            self.events = (pd.read_sql_query("SELECT frame, tick, agent, kind, a, b FROM throng_events ORDER BY rowid", db)
                           if "throng_events" in tables else pd.DataFrame(columns=["frame", "tick", "agent", "kind", "a", "b"]))
            self.points = (pd.read_sql_query("SELECT * FROM throng_points ORDER BY idx", db)
                           if "throng_points" in tables else pd.DataFrame())
            # Common Ground (Park et al.; docs/social-model.md): interactions and each character's action script.
            self.coordinations = (pd.read_sql_query("SELECT * FROM throng_coordinations ORDER BY id", db)
                                  if "throng_coordinations" in tables else pd.DataFrame())
            self.scripts = (pd.read_sql_query("SELECT * FROM throng_script ORDER BY coordination, agent, seq", db)
                            if "throng_script" in tables else pd.DataFrame())
        finally:
            db.close()
        text = self.metadata.get("throng_scenario")
        self.scenario = json.loads(text) if text else None
        self.path = path

    def walkable_polygon(self):
        """The walkable area as a shapely geometry (needs python3-shapely)."""
        from shapely import wkt  # optional dependency
        return wkt.loads(self.walkable_area)

    def __repr__(self):
        frames = int(self.trajectory["frame"].max()) + 1 if len(self.trajectory) else 0
        return (f"<throng.Recording {self.path!r}: {self.trajectory['id'].nunique()} agents, {frames} frames "
                f"at {self.fps:g} fps>")


def read_recording(path):
    """Reads a recording (read-only; never changes the file). ValueError for a file that is not one."""
    return Recording(os.fspath(path))
