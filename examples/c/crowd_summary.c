/* crowd_summary — a program in plain C that embeds throng through its C API (throng/throng.h,
 * docs/c-api.md): loads a scenario, builds a world, steps it, reads every agent's position into
 * arrays it owns (the count/capacity protocol), drains the events and prints a summary.
 *
 *   crowd_summary SCENARIO.json [SECONDS]      (SECONDS of simulated time, default 10)
 *
 * Exits 0 on success, 1 with throng's message on stderr otherwise. */
#include <stdio.h>
#include <stdlib.h>

#include "throng/throng.h"

/* Prints what failed and returns 1 when status is not THRONG_OK. */
static int failed(throng_status status, const char* what) {
  if (status == THRONG_OK) return 0;
  fprintf(stderr, "crowd_summary: %s: %s\n%s\n", what, throng_status_name(status), throng_last_error());
  return 1;
}

/* Reads every agent's position; *out_count agents; the caller frees the array. */
static float* read_positions(throng_world* world, size_t* out_count) {
  throng_agent_arrays arrays = {0};
  size_t count = 0;
  /* Capacity 0: asks for the count only. */
  throng_status status = throng_world_agents(world, &arrays, &count);
  if (status != THRONG_OK && status != THRONG_ERROR_BUFFER_TOO_SMALL) return NULL;
  arrays.capacity = count;
  arrays.positions = malloc(2 * (count > 0 ? count : 1) * sizeof(float));
  if (arrays.positions == NULL) return NULL;
  if (failed(throng_world_agents(world, &arrays, &count), "throng_world_agents")) {
    free(arrays.positions);
    return NULL;
  }
  *out_count = count;
  return arrays.positions;
}

/* Drains the events and counts spawns and exits. */
static int count_events(throng_world* world, size_t* spawns, size_t* exits) {
  throng_event batch[64];
  size_t n = 0;
  do {
    if (failed(throng_world_events(world, batch, 64, &n), "throng_world_events")) return 1;
    for (size_t i = 0; i < n; ++i) {
      if (batch[i].kind == THRONG_EVENT_SPAWN) ++*spawns;
      if (batch[i].kind == THRONG_EVENT_EXIT) ++*exits;
    }
  } while (n > 0);
  return 0;
}

static int summarize(throng_world* world) {
  throng_world_stats stats;
  if (failed(throng_world_stats_get(world, &stats), "throng_world_stats_get")) return 1;
  size_t count = 0;
  float* pos = read_positions(world, &count);
  if (pos == NULL) return 1;
  double cx = 0, cy = 0;
  for (size_t i = 0; i < count; ++i) {
    cx += pos[2 * i];
    cy += pos[2 * i + 1];
  }
  free(pos);
  size_t spawns = 0, exits = 0;
  if (count_events(world, &spawns, &exits)) return 1;
  printf("t = %.2f s (%llu ticks): %zu agents present, %u spawned, %u exited, %u groups\n", stats.time,
         (unsigned long long)stats.tick, count, stats.spawned, stats.exited, stats.groups);
  if (count > 0) printf("centre of the crowd: (%.2f, %.2f) m\n", cx / (double)count, cy / (double)count);
  printf("events: %zu spawns, %zu exits\n", spawns, exits);
  return 0;
}

int main(int argc, char** argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: crowd_summary SCENARIO.json [SECONDS]\n");
    return 2;
  }
  const double seconds = argc > 2 ? atof(argv[2]) : 10.0;
  printf("throng %s (C API %u)\n", throng_version(), throng_api_version());
  throng_scenario* scenario = NULL;
  char* diagnostics = NULL;
  if (throng_scenario_load_file(argv[1], &scenario, &diagnostics) != THRONG_OK) {
    fprintf(stderr, "%s\n", diagnostics != NULL ? diagnostics : throng_last_error());
    throng_string_free(diagnostics);
    return 1;
  }
  throng_world_options options = throng_world_options_default();
  options.threads = 2;
  throng_world* world = NULL;
  int rc = failed(throng_world_create(scenario, &options, &world), "throng_world_create");
  throng_scenario_free(scenario); /* the world keeps what it needs */
  if (rc == 0) rc = failed(throng_world_run(world, seconds), "throng_world_run");
  if (rc == 0) rc = summarize(world);
  if (failed(throng_world_free(world), "throng_world_free")) rc = 1;
  return rc;
}
