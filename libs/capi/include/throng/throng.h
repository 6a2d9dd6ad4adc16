/* throng.h — the stable C API of the throng crowd engine (docs/c-api.md).
 *
 * Plain C (C99 and C++), C ABI, opaque handles, no C++ type crosses it: for engines and languages
 * that reach native code through a C foreign-function interface (Unity and C# P/Invoke, Godot
 * GDExtension, Unreal, Rust, Python ctypes, ...). It loads scenarios with the same validator as
 * `throng check`, steps a world exactly as `throng run` does (same seed, same trajectories, for any
 * thread count), copies agent state and events into arrays the caller owns, steers groups, inserts
 * and removes crowds at run time, and records to SQLite with the recorder `throng run` uses.
 *
 * Conventions, for every function below:
 *  - Every function except the version queries, throng_status_name, throng_event_kind_name and
 *    throng_last_error returns a throng_status. THRONG_OK is 0; on any other value the function
 *    changed nothing the caller can see except what it documents, and throng_last_error() on the
 *    same thread says what went wrong. No C++ exception ever leaves the library.
 *  - Results come back through out-parameters, which are written only on THRONG_OK unless stated.
 *  - NULL where a handle or out-parameter is required gives THRONG_ERROR_NULL_ARGUMENT; a pointer
 *    that is not a live handle of this library (never returned, or already freed) gives
 *    THRONG_ERROR_BAD_HANDLE; a NaN or infinite number gives THRONG_ERROR_INVALID_ARGUMENT.
 *  - Units are SI: metres, seconds, metres per second. Time advances in ticks of dt seconds.
 *  - Agents are named by stable ids (0, 1, 2, ... in spawn order), groups by stable group ids;
 *    neither is ever reused within a world.
 *  - Ownership: each throng_*_create / _load function allocates one object that the caller frees
 *    with the matching throng_*_free exactly once; freeing NULL does nothing. Strings the library
 *    allocates (diagnostics) are freed with throng_string_free. Arrays passed in stay the
 *    caller's; the library never keeps a pointer to them after the call returns.
 *  - Threads: a scenario is immutable and may be used from any number of threads at once. A world
 *    is used by one thread at a time: a call on a world another thread is inside returns
 *    THRONG_ERROR_BUSY (nothing is corrupted); different worlds run in parallel freely. Each
 *    world runs its tick on its own worker threads (throng_world_options.threads).
 */
#ifndef THRONG_THRONG_H
#define THRONG_THRONG_H

#include <stddef.h>
#include <stdint.h>

/* THRONG_API marks the exported functions (everything else in the library is hidden). */
#if defined(_WIN32) || defined(__CYGWIN__)
#  if defined(THRONG_CAPI_BUILDING)
#    define THRONG_API __declspec(dllexport)
#  else
#    define THRONG_API __declspec(dllimport)
#  endif
#elif defined(__GNUC__) || defined(__clang__)
#  define THRONG_API __attribute__((visibility("default")))
#else
#  define THRONG_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------
 * Versions
 * ------------------------------------------------------------------------------------------- */

/* The throng release this header belongs to. */
#define THRONG_VERSION_MAJOR 0
#define THRONG_VERSION_MINOR 1
#define THRONG_VERSION_PATCH 0
#define THRONG_VERSION_STRING "0.1.0"
/* The C API level: raised when a function or structure is added; an existing function's signature
 * or meaning never changes within a major version. Compare with throng_api_version() at run time
 * to check that the library loaded is at least as new as this header. */
#define THRONG_API_VERSION 1

/* The library's release, "MAJOR.MINOR.PATCH" (static storage; thread-safe). */
THRONG_API const char* throng_version(void);
/* The library's THRONG_API_VERSION (thread-safe). */
THRONG_API uint32_t throng_api_version(void);

/* ---------------------------------------------------------------------------------------------
 * Errors
 * ------------------------------------------------------------------------------------------- */

typedef enum throng_status {
  THRONG_OK = 0,
  THRONG_ERROR_NULL_ARGUMENT = 1,    /* a required pointer was NULL */
  THRONG_ERROR_BAD_HANDLE = 2,       /* not a live throng_scenario / throng_world of this library */
  THRONG_ERROR_INVALID_ARGUMENT = 3, /* NaN, infinity, out of range, or not valid UTF-8 JSON text */
  THRONG_ERROR_INVALID_SCENARIO = 4, /* a scenario or crowd was refused: see the diagnostics */
  THRONG_ERROR_NOT_FOUND = 5,        /* no such group, population or crowd */
  THRONG_ERROR_BUFFER_TOO_SMALL = 6, /* capacity below the count needed: nothing copied, count set */
  THRONG_ERROR_WRONG_STATE = 7,      /* not now: e.g. record after the first step, step when finished */
  THRONG_ERROR_BUSY = 8,             /* another thread is inside a call on this world */
  THRONG_ERROR_IO = 9,               /* a file could not be written (the recording) */
  THRONG_ERROR_INTERNAL = 10         /* out of memory or an internal failure; the message says which */
} throng_status;

/* A static English name of a status ("THRONG_ERROR_BAD_HANDLE"; "unknown" for other values).
 * Thread-safe. */
THRONG_API const char* throng_status_name(throng_status status);

/* What the last call on this thread that failed went wrong with, as text (several lines for
 * scenario diagnostics); "" when the last call succeeded. The pointer stays valid until the next
 * throng_* call on the same thread; copy it to keep it. Thread-local: never NULL. */
THRONG_API const char* throng_last_error(void);

/* Frees a string the library allocated (the diagnostics of the load and insert functions).
 * NULL does nothing. Thread-safe. */
THRONG_API void throng_string_free(char* text);

/* ---------------------------------------------------------------------------------------------
 * Scenarios (docs/scenario-format.md)
 * ------------------------------------------------------------------------------------------- */

typedef struct throng_scenario throng_scenario;

/* Reads and validates a scenario file (JSON, or glTF with throng extras): the same checks as
 * `throng check` (every value, the navmesh built, spawns and goals reachable). On THRONG_OK,
 * *out_scenario receives a new scenario (free it with throng_scenario_free). A refused file
 * returns THRONG_ERROR_INVALID_SCENARIO and every problem, one per line, as `throng check` prints
 * them: "file:line:column /json/pointer: what; expected ...". `out_diagnostics` may be NULL; when
 * not, it receives that text (a string to free with throng_string_free) or NULL on success. The
 * same text is throng_last_error(). Thread-safe (may take a while: the navmesh is built). */
THRONG_API throng_status throng_scenario_load_file(const char* path, throng_scenario** out_scenario,
                                                   char** out_diagnostics);

/* The same for scenario JSON text (UTF-8, NUL-terminated). `source` names it in diagnostics and
 * is the path that relative clip paths are resolved against; NULL means "<string>" (the working
 * directory). Thread-safe. */
THRONG_API throng_status throng_scenario_load_json(const char* json, const char* source, throng_scenario** out_scenario,
                                                   char** out_diagnostics);

/* Frees a scenario. Worlds created from it stay valid (they keep what they need). NULL does
 * nothing; a pointer that is not a live scenario returns THRONG_ERROR_BAD_HANDLE. Call it once,
 * when no other thread uses the scenario. */
THRONG_API throng_status throng_scenario_free(throng_scenario* scenario);

typedef struct throng_scenario_info {
  uint64_t seed;            /* the scenario's random seed */
  double duration;          /* simulated time [s] */
  double dt;                /* tick length [s] */
  uint32_t populations;     /* number of populations */
  uint32_t points;          /* number of points (goals, exits, action points) */
  uint64_t agents_min;      /* agents the populations spawn, at least ... */
  uint64_t agents_max;      /* ... and at most (group sizes may be ranges) */
} throng_scenario_info;

/* Fills *out_info. Thread-safe. */
THRONG_API throng_status throng_scenario_info_get(const throng_scenario* scenario, throng_scenario_info* out_info);

/* ---------------------------------------------------------------------------------------------
 * Worlds
 * ------------------------------------------------------------------------------------------- */

typedef struct throng_world throng_world;

typedef struct throng_world_options {
  uint64_t seed;       /* used when use_seed is non-zero; otherwise the scenario's seed */
  int32_t use_seed;    /* non-zero: `seed` overrides the scenario's */
  int32_t threads;     /* worker threads for the tick, 0 = every hardware thread, at most 1024;
                          the trajectories do not depend on it */
  double duration;     /* simulated time [s] overriding the scenario's when > 0; 0 keeps it */
} throng_world_options;

/* The defaults: the scenario's seed and duration, one thread. Thread-safe. */
THRONG_API throng_world_options throng_world_options_default(void);

/* Builds a world from a scenario (frame 0: agents that spawn at t = 0 are present). `options` may
 * be NULL for the defaults. On THRONG_OK *out_world receives a new world, to free with
 * throng_world_free. The scenario may be freed afterwards. Thread-safe. */
THRONG_API throng_status throng_world_create(const throng_scenario* scenario, const throng_world_options* options,
                                             throng_world** out_world);

/* Closes the recording, if any (completed), and frees the world and its worker threads. NULL does
 * nothing; a pointer that is not a live world returns THRONG_ERROR_BAD_HANDLE; THRONG_ERROR_BUSY
 * while another thread is inside a call on it (nothing freed). A recording that failed to close
 * returns THRONG_ERROR_IO, and the world is freed anyway. */
THRONG_API throng_status throng_world_free(throng_world* world);

/* Advances up to `ticks` ticks of dt seconds; fewer when every agent has left (finished).
 * `out_stepped` (may be NULL) receives how many ticks ran. THRONG_ERROR_WRONG_STATE when the world
 * is already finished. While recording, every stride-th tick is written (throng_world_record) and
 * THRONG_ERROR_IO stops stepping at the first failed write. One thread at a time per world. */
THRONG_API throng_status throng_world_step(throng_world* world, uint64_t ticks, uint64_t* out_stepped);

/* Steps until `until_s` seconds of simulated time or until every agent has left, ending, like
 * `throng run`, on a recorded tick (so a recording holds the same frames as the CLI's). Pass the
 * world's duration (throng_world_stats.duration) to run as `throng run` does. `until_s` must be
 * finite and >= 0. One thread at a time per world. */
THRONG_API throng_status throng_world_run(throng_world* world, double until_s);

typedef struct throng_world_stats {
  uint64_t tick;            /* ticks stepped */
  double time;              /* tick * dt [s] */
  double dt;                /* [s] */
  double duration;          /* the world's duration (scenario or options) [s] */
  uint64_t seed;            /* the seed actually used */
  uint32_t spawned;         /* agents spawned so far */
  uint32_t exited;          /* agents that left through an exit */
  uint32_t removed;         /* agents that left because their crowd was removed */
  uint32_t active;          /* agents in the world now */
  uint32_t scheduled;       /* agents still to spawn */
  uint32_t groups;          /* groups so far (stable group ids are 0 .. groups - 1) */
  int32_t finished;         /* non-zero when every agent has left and none is scheduled */
  int32_t recording;        /* non-zero while a recording is open */
  double last_exit_time;    /* [s] when the last agent exited; < 0 when nobody has */
  double mean_walking_speed;/* over all agents and the time they walked [m/s] */
  uint64_t agent_steps;     /* sum over ticks of the agents present */
} throng_world_stats;

/* Fills *out_stats: time, counts, whether finished. One thread at a time per world. */
THRONG_API throng_status throng_world_stats_get(throng_world* world, throng_world_stats* out_stats);

/* A hash of every agent's id, position and velocity bits, in id order: the `state_hash` that
 * `throng run --json` prints (same seed, same hash, any thread count). */
THRONG_API throng_status throng_world_state_hash(throng_world* world, uint64_t* out_hash);

/* ---------------------------------------------------------------------------------------------
 * Agent state: the count/capacity protocol
 * ------------------------------------------------------------------------------------------- */

typedef enum throng_agent_mode {
  THRONG_MODE_WALKING = 0,
  THRONG_MODE_WAITING = 1, /* standing: no path yet, waiting for its group, or done */
  THRONG_MODE_ACTING = 2   /* stopped at an action point, playing its action */
} throng_agent_mode;

/* Arrays the caller owns, each of at least `capacity` elements, or NULL for a column not wanted.
 * Element i of every column describes the same agent; agents come in ascending id order. */
typedef struct throng_agent_arrays {
  size_t capacity;       /* elements each non-NULL array holds */
  uint32_t* ids;         /* stable agent ids */
  float* positions;      /* 2 floats per agent: x, y [m] */
  float* heights;        /* floor height [m] on a multi-level world, 0 on a flat one */
  float* velocities;     /* 2 floats per agent: vx, vy [m/s] */
  float* headings;       /* 2 floats per agent: unit heading x, y */
  uint32_t* groups;      /* stable group id of each agent */
  uint8_t* modes;        /* throng_agent_mode */
  uint16_t* clips;       /* motion clip playing (index into the scenario's clips) */
  float* phases;         /* position in that clip, [0, 1) */
} throng_agent_arrays;

/* Copies the state of the agents present now into the caller's arrays. *out_count receives the
 * number of agents present. When it exceeds arrays->capacity nothing is copied and the call
 * returns THRONG_ERROR_BUFFER_TOO_SMALL: grow the arrays to *out_count and call again (a capacity
 * of 0 with NULL arrays asks only for the count). Asking for `groups` costs a pass over the
 * groups; the other columns are one copy each. One thread at a time per world. */
THRONG_API throng_status throng_world_agents(throng_world* world, const throng_agent_arrays* arrays, size_t* out_count);

/* ---------------------------------------------------------------------------------------------
 * Groups: dynamic goals (guidance)
 * ------------------------------------------------------------------------------------------- */

/* The stable id of group `index` (0-based, in spawn order) of the population with id
 * `population` (UTF-8). THRONG_ERROR_NOT_FOUND when that group has not spawned or there is no such
 * population. One thread at a time per world. */
THRONG_API throng_status throng_world_group(throng_world* world, const char* population, uint32_t index,
                                            uint32_t* out_group);

/* From the next tick, group `group` follows the dynamic goal (x, y) [m] (an avatar, say) instead
 * of its own goals, until throng_world_release; call again to move the goal. THRONG_ERROR_NOT_FOUND
 * for an unknown group; THRONG_ERROR_INVALID_ARGUMENT for a coordinate that is not finite or
 * beyond float range (+-3.4e38). One thread at a time per world. */
THRONG_API throng_status throng_world_guide(throng_world* world, uint32_t group, double x, double y);

/* The same on a multi-level world: `height` [m] is the floor the goal stands on. */
THRONG_API throng_status throng_world_guide_at_height(throng_world* world, uint32_t group, double x, double y,
                                                      double height);

/* Guidance ends from the next tick; the group resumes its own goals where it left them.
 * THRONG_ERROR_NOT_FOUND for an unknown group. One thread at a time per world. */
THRONG_API throng_status throng_world_release(throng_world* world, uint32_t group);

/* ---------------------------------------------------------------------------------------------
 * Crowds inserted and removed at run time (docs/scenario-format.md, "throng-crowd/1")
 * ------------------------------------------------------------------------------------------- */

/* Validates a crowd (JSON text of a throng-crowd/1 file) against this world and queues it for the
 * next tick: its agents spawn from then on. `source` names it in diagnostics (NULL: "<crowd>").
 * On THRONG_OK *out_index (may be NULL) receives the crowd's index (insertion order). A refused
 * crowd returns THRONG_ERROR_INVALID_SCENARIO with its diagnostics, as for scenarios
 * (`out_diagnostics` may be NULL; free the text with throng_string_free). One thread at a time. */
THRONG_API throng_status throng_world_insert_crowd(throng_world* world, const char* json, const char* source,
                                                   uint32_t* out_index, char** out_diagnostics);

/* The same, reading the crowd from a file. */
THRONG_API throng_status throng_world_insert_crowd_file(throng_world* world, const char* path, uint32_t* out_index,
                                                        char** out_diagnostics);

/* At the next tick the agents of crowd `id` leave (an exit event each) and its populations spawn
 * nobody more. THRONG_ERROR_NOT_FOUND when no crowd has that id or it is already removed. */
THRONG_API throng_status throng_world_remove_crowd(throng_world* world, const char* id);

/* Closes (open = 0) or opens (open != 0) the exit point `id` from the next tick — a door on an
 * event the host sees, as the timeline's "close" / "open": nobody leaves through a closed exit,
 * groups choosing among exits re-route, a fixed goal at it waits at the door.
 * THRONG_ERROR_NOT_FOUND when no point of kind exit has that id. One thread at a time. */
THRONG_API throng_status throng_world_set_exit_open(throng_world* world, const char* id, int32_t open);

/* *out_is_wall receives 1 when closing the exit `id` makes its floor a wall: every exit with floor
 * in its region (an exit a crowd throng_world_insert_crowd brought is cut into the navmesh when it
 * first closes, which builds the mesh again); 0 for an exit with no floor in its region and for an
 * id that is no exit. */
THRONG_API throng_status throng_world_exit_is_wall(throng_world* world, const char* id, int32_t* out_is_wall);

/* ---------------------------------------------------------------------------------------------
 * Events
 * ------------------------------------------------------------------------------------------- */

/* What an event says happened; the values are those of the recordings' throng_events.kind
 * (docs/recording-format.md), fixed for good. a and b depend on the kind. */
typedef enum throng_event_kind {
  THRONG_EVENT_SPAWN = 0,              /* a = population index, b = group id */
  THRONG_EVENT_EXIT = 1,               /* a = exit point, or 0xffffffff when its crowd was removed (b = crowd) */
  THRONG_EVENT_GOAL_REACHED = 2,       /* a = point */
  THRONG_EVENT_ACTION_START = 3,       /* a = point */
  THRONG_EVENT_ACTION_END = 4,         /* a = point */
  THRONG_EVENT_PATH_PARTIAL = 5,       /* a = point it could not fully reach */
  THRONG_EVENT_GROUP_WAIT_START = 6,   /* a = point, b = group */
  THRONG_EVENT_GROUP_RELEASE = 7,      /* a = point, b = group */
  THRONG_EVENT_GROUP_TIMEOUT = 8,      /* a = point, b = members missing */
  THRONG_EVENT_FOLLOW_START = 9,       /* a = following group, b = followed group */
  THRONG_EVENT_FOLLOW_END = 10,        /* a = following group, b = followed group */
  THRONG_EVENT_GUIDE_START = 11,       /* agent = the group's leader; a = group */
  THRONG_EVENT_GUIDE_END = 12,         /* a = group */
  THRONG_EVENT_JOIN_GROUP = 13,        /* a = old group, b = new group */
  THRONG_EVENT_FOLLOW_AGENT = 14,      /* a = the agent followed */
  THRONG_EVENT_FOLLOW_AGENT_END = 15,  /* a = the agent it followed */
  THRONG_EVENT_LEADER_CHANGE = 16,     /* agent = new leader; a = group */
  THRONG_EVENT_PATH_FALLBACK = 17,     /* a = point */
  THRONG_EVENT_GOAL_GENERATED = 18,    /* a = point, b = trigger (0 need, 1 attraction) */
  THRONG_EVENT_COORDINATION_START = 19,/* a = coordination id, b = group */
  THRONG_EVENT_COORDINATION_END = 20,  /* a = coordination id, b = outcome */
  THRONG_EVENT_VISIT_START = 21,       /* a = point, b = coordination id */
  THRONG_EVENT_VISIT_END = 22,         /* a = point, b = coordination id */
  THRONG_EVENT_REUNITED = 23,          /* a = group, b = coordination id */
  THRONG_EVENT_EXIT_CHOSEN = 24,       /* exit choice; agent = the group's leader; a = exit point, b = the exit before (0xffffffff: first choice) */
  THRONG_EVENT_WAYPOINT_CHOSEN = 25,   /* waypoint choice; agent = the group's leader; a = the point chosen, b = the choice's slot in the population's goals */
  THRONG_EVENT_INCAPACITATED = 26      /* the agent's carbon monoxide dose reached its population's incapacitationDose: it stops for good; a = the dose (FED) in thousandths */
} throng_event_kind;

/* One thing that happened to an agent. */
typedef struct throng_event {
  uint64_t tick;     /* the tick it happened in */
  double time;       /* tick * dt [s] */
  uint32_t agent;    /* stable agent id */
  uint32_t kind;     /* a throng_event_kind */
  uint32_t a;
  uint32_t b;
} throng_event;

/* The recordings' name of an event kind ("spawn", "exit", "goal_reached", ...; "unknown" for
 * other values). Static storage; thread-safe. */
THRONG_API const char* throng_event_kind_name(uint32_t kind);

/* Moves the oldest pending events (since the world was created or the last call) into
 * events[0 .. capacity), oldest first; *out_count receives how many were copied. Call again until
 * it is 0 to read them all: no event is lost or repeated. Recordings are unaffected. capacity 0
 * (events may then be NULL) copies nothing and sets *out_count to 0; use
 * throng_world_pending_events for the number waiting. One thread at a time per world. */
THRONG_API throng_status throng_world_events(throng_world* world, throng_event* events, size_t capacity,
                                             size_t* out_count);

/* The number of events waiting for throng_world_events. One thread at a time per world. */
THRONG_API throng_status throng_world_pending_events(throng_world* world, size_t* out_count);

/* ---------------------------------------------------------------------------------------------
 * Recording (SQLite; docs/recording-format.md)
 * ------------------------------------------------------------------------------------------- */

/* Starts recording to the SQLite file `path` exactly as `throng run --out path --fps fps` does:
 * frame 0 is the state before the first tick, then every k-th tick (k = round(1 / (fps * dt)),
 * at least 1), with the events since. Only before the first tick (THRONG_ERROR_WRONG_STATE
 * otherwise, or when already recording). An existing file is kept and the call fails with
 * THRONG_ERROR_INVALID_SCENARIO (its diagnostic names the file) unless `force` is non-zero.
 * `fps` must be finite and > 0 (10 is the CLI's default). The file is complete once
 * throng_world_record_close or throng_world_free returns. One thread at a time per world. */
THRONG_API throng_status throng_world_record(throng_world* world, const char* path, double fps, int32_t force);

/* Flushes and closes the recording, marked completed; stepping may go on unrecorded.
 * THRONG_ERROR_WRONG_STATE when not recording; THRONG_ERROR_IO when a write failed (the file then
 * holds every frame written before the error, marked not completed). `out_frames` (may be NULL)
 * receives the frames written. One thread at a time per world. */
THRONG_API throng_status throng_world_record_close(throng_world* world, uint64_t* out_frames);

#ifdef __cplusplus
}
#endif

#endif /* THRONG_THRONG_H */
