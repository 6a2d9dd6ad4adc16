/* link_host.c — an example host application, in plain C99, for `throng link`: the crowd runs in
 * its own process and shares a POSIX shared-memory segment with us (include/throng/throng_link.h,
 * docs/integration.md). We
 *   1. find the segment: launch throng ourselves (--launch), attach by name (--shm), or ask a
 *      running throng over its UNIX socket (--socket);
 *   2. open it (the helper refuses a segment of another layout version) and announce ourselves;
 *   3. print what the crowd looks like: scenario, skeleton, clips, agents, a group's centroid;
 *   4. create an avatar far from group G, walk it slowly along a straight line, and ask group G to
 *      follow it, asking for the joint angles of one of its members on the way;
 *   5. check that the group came to the avatar: its centroid ends within 2 m of the avatar and at
 *      least 1 m nearer than had the group stayed where it was (exit 0), or say it did not (exit 1);
 *   6. insert a crowd (six visitors) and remove it again, see a bad crowd refused, release the group
 *      and detach.
 *
 * Usage:
 *   throng_link_example_host --shm NAME [options]
 *   throng_link_example_host --socket PATH [options]
 *   throng_link_example_host --launch THRONG SCENARIO [--shm NAME] [options] [-- THRONG-FLAGS...]
 * Options: --group G (default 0), --seconds S (how long the avatar walks, wall clock; default 4),
 *          --no-guide (a control: the avatar walks but never asks the group to follow, so a group
 *          that stands still must NOT come to it).
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "throng/throng_link.h"

extern char** environ;

/* Centroid of the agents of `group` in a frame copy; returns how many there are. */
static int group_centroid(const throng_link_header* h, throng_link_frame* frame, uint32_t group, double* cx,
                          double* cy) {
  const throng_link_agent* agents = throng_link_frame_agents(h, frame);
  uint32_t i;
  int n = 0;
  *cx = 0.0;
  *cy = 0.0;
  for (i = 0; i < frame->agent_count; ++i) {
    if (agents[i].group != group) continue;
    *cx += agents[i].x;
    *cy += agents[i].y;
    ++n;
  }
  if (n > 0) {
    *cx /= n;
    *cy /= n;
  }
  return n;
}

/* Starts `throng link --shm NAME SCENARIO [extra flags]` as a child process (start mode a). */
static pid_t launch_throng(const char* throng, const char* scenario, const char* name, char** extra, int extra_count) {
  char* argv[64];
  int argc = 0, i;
  pid_t pid;
  argv[argc++] = (char*)throng;
  argv[argc++] = (char*)"link";
  argv[argc++] = (char*)"--shm";
  argv[argc++] = (char*)name;
  argv[argc++] = (char*)scenario;
  for (i = 0; i < extra_count && argc < 63; ++i) argv[argc++] = extra[i];
  argv[argc] = NULL;
  if (posix_spawn(&pid, throng, NULL, NULL, argv, environ) != 0) return -1;
  return pid;
}

/* Waits up to `ms` milliseconds for the child to exit; returns its exit status or -1. */
static int wait_child(pid_t pid, uint32_t ms) {
  uint64_t start = throng_link_now_ms();
  int status = 0;
  while (throng_link_now_ms() - start < ms) {
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
    throng_link_sleep_ms(20);
  }
  kill(pid, SIGTERM);
  waitpid(pid, &status, 0);
  return -1;
}

/* Sends one request and waits (up to 2 s, keeping our heartbeat) for its reply. 1 answered. */
static int ask(throng_link* link, uint32_t kind, uint32_t id, uint32_t payload_kind, const char* payload,
               uint32_t target, throng_link_reply* reply) {
  uint64_t asked = throng_link_now_ms();
  if (throng_link_send_request(link, kind, id, payload_kind, payload, target) != 0) return 0;
  while (throng_link_now_ms() - asked < 2000) {
    throng_link_host_beat(link);
    if (throng_link_take_reply(link, reply)) return 1;
    throng_link_sleep_ms(10);
  }
  printf("host: request %u not answered\n", (unsigned)id);
  return 0;
}

/* Reads frames (up to 2 s) until the agent count reaches `count` (at least when `more`, at most
 * otherwise); returns the last count seen. */
static uint32_t count_after(throng_link* link, throng_link_frame* frame, uint32_t count, int more) {
  uint64_t start = throng_link_now_ms();
  while (throng_link_now_ms() - start < 2000) {
    if (throng_link_wait_frame(link, frame->tick, 500) < 0) break;
    if (throng_link_read_frame(link, frame) != 0) continue;
    if (more ? frame->agent_count >= count : frame->agent_count <= count) break;
  }
  return frame->agent_count;
}

int main(int argc, char** argv) {
  const char* shm = NULL;
  const char* socket_path = NULL;
  const char* throng = NULL;
  const char* scenario = NULL;
  char** extra = NULL;
  int extra_count = 0;
  uint32_t group = 0;
  double seconds = 4.0;
  int guiding = 1;
  char name[256];
  char error[512];
  pid_t child = -1;
  throng_link link;
  throng_link_header* h;
  throng_link_frame* frame;
  int i, ok = 0;

  /* ---- Command line ---------------------------------------------------------------------- */
  for (i = 1; i < argc; ++i) {
    if (strcmp(argv[i], "--shm") == 0 && i + 1 < argc) {
      shm = argv[++i];
    } else if (strcmp(argv[i], "--socket") == 0 && i + 1 < argc) {
      socket_path = argv[++i];
    } else if (strcmp(argv[i], "--launch") == 0 && i + 2 < argc) {
      throng = argv[++i];
      scenario = argv[++i];
    } else if (strcmp(argv[i], "--group") == 0 && i + 1 < argc) {
      group = (uint32_t)strtoul(argv[++i], NULL, 10);
    } else if (strcmp(argv[i], "--seconds") == 0 && i + 1 < argc) {
      seconds = atof(argv[++i]);
    } else if (strcmp(argv[i], "--no-guide") == 0) {
      guiding = 0;
    } else if (strcmp(argv[i], "--") == 0) {
      extra = argv + i + 1;
      extra_count = argc - i - 1;
      break;
    } else {
      fprintf(stderr,
              "usage: %s (--shm NAME | --socket PATH | --launch THRONG SCENARIO [--shm NAME]) [--group G] "
              "[--seconds S] [--no-guide] [-- THRONG-FLAGS...]\n",
              argv[0]);
      return 2;
    }
  }
  if (!shm && !socket_path && !throng) {
    fprintf(stderr, "%s: give --shm NAME, --socket PATH or --launch THRONG SCENARIO\n", argv[0]);
    return 2;
  }

  /* ---- 1. Find the segment ----------------------------------------------------------------- */
  if (throng) {
    /* Start mode (a): we start the crowd process and choose the segment's name. */
    if (shm) {
      snprintf(name, sizeof name, "%s", shm);
    } else {
      snprintf(name, sizeof name, "/throng-host-%ld", (long)getpid());
    }
    child = launch_throng(throng, scenario, name, extra, extra_count);
    if (child < 0) {
      fprintf(stderr, "host: cannot start %s\n", throng);
      return 1;
    }
    printf("host: started %s link --shm %s %s (pid %ld)\n", throng, name, scenario, (long)child);
  } else if (socket_path) {
    /* Start mode (c): the crowd tells us the name (and its version) over a UNIX socket. */
    if (throng_link_handshake(socket_path, name, sizeof name, error, sizeof error) != 0) {
      fprintf(stderr, "host: %s\n", error);
      return 1;
    }
    printf("host: %s says the segment is %s\n", socket_path, name);
  } else {
    /* Start mode (b): someone started `throng link --shm NAME` and told us NAME. */
    snprintf(name, sizeof name, "%s", shm);
  }

  /* ---- 2. Open it and say hello -------------------------------------------------------------- */
  /* throng_link_open waits (here up to 10 s) for the segment to exist and the crowd to run, then
   * checks magic, version and sizes: a crowd of another layout version is refused here. */
  if (throng_link_open(&link, name, 10000, error, sizeof error) != 0) {
    fprintf(stderr, "host: %s\n", error);
    if (child > 0) wait_child(child, 3000);
    return 1;
  }
  throng_link_attach(&link); /* host_version, host_pid, host_state = ATTACHED */
  h = link.header;
  frame = (throng_link_frame*)malloc((size_t)h->frame_size); /* our private copy of a frame */
  setvbuf(stdout, NULL, _IOLBF, 0);                          /* one line at a time, even into a pipe */
  if (!frame) return 1;

  /* ---- 3. What is in there ------------------------------------------------------------------- */
  printf("host: attached to %s: scenario \"%s\", layout version %u, %.1f ticks/s, dt %.3f s\n", name, h->scenario,
         (unsigned)h->version, h->tick_rate, h->dt);
  printf("host: room for %u agents, %u detailed, %u avatars, %u guides; skeleton of %u joints, %u clips\n",
         (unsigned)h->max_agents, (unsigned)h->max_detailed, (unsigned)h->max_avatars, (unsigned)h->max_guides,
         (unsigned)h->joint_count, (unsigned)h->clip_count);
  if (h->joint_count > 0) printf("host: root joint \"%s\"\n", throng_link_skeleton(h)[0].name);
  for (i = 0; i < (int)h->clip_count && i < 4; ++i) {
    printf("host: clip %d \"%s\" %.2f s%s\n", i, throng_link_clips(h)[i].name, throng_link_clips(h)[i].duration,
           throng_link_clips(h)[i].loops ? " (loops)" : "");
  }
  /* Wait for a frame in which group G is present. */
  {
    double cx = 0.0, cy = 0.0;
    uint64_t start = throng_link_now_ms();
    int members = 0;
    while (members == 0) {
      if (throng_link_wait_frame(&link, UINT64_MAX, 1000) < 0) {
        fprintf(stderr, "host: the crowd stopped: %s\n", h->message[0] ? h->message : "no heartbeat");
        goto done;
      }
      if (throng_link_read_frame(&link, frame) == 0) members = group_centroid(h, frame, group, &cx, &cy);
      if (members == 0 && throng_link_now_ms() - start > 5000) {
        fprintf(stderr, "host: group %u never appeared\n", (unsigned)group);
        goto done;
      }
      if (members == 0) throng_link_sleep_ms(20);
    }
    printf("host: tick %llu, t = %.2f s: %u agents in %u groups; group %u has %d members around (%.2f, %.2f)\n",
           (unsigned long long)frame->tick, frame->time, (unsigned)frame->total_agents, (unsigned)frame->group_count,
           (unsigned)group, members, cx, cy);
  }

  /* ---- 4. An avatar that group G follows ----------------------------------------------------- */
  {
    throng_link_agent* agents = throng_link_frame_agents(h, frame);
    throng_link_avatar avatar;
    throng_link_guide guide;
    uint32_t detail_id = 0xFFFFFFFFu;
    double cx0, cy0, cx, cy, sx = 0.0, sy = 0.0, far = -1.0, d0, d_end, d_from_start, ex, ey;
    uint64_t last_tick = frame->tick, start, last_print = 0;
    uint32_t k;
    group_centroid(h, frame, group, &cx0, &cy0);
    /* Start where the agent farthest from the group stands (a walkable spot). */
    for (k = 0; k < frame->agent_count; ++k) {
      double dx = agents[k].x - cx0, dy = agents[k].y - cy0;
      if (agents[k].group == group && detail_id == 0xFFFFFFFFu) detail_id = agents[k].id;
      if (dx * dx + dy * dy > far) {
        far = dx * dx + dy * dy;
        sx = agents[k].x;
        sy = agents[k].y;
      }
    }
    d0 = sqrt(far);
    printf("host: avatar 1 appears at (%.2f, %.2f), %.2f m from group %u; %s\n", sx, sy, d0, (unsigned)group,
           guiding ? "it asks the group to follow" : "it does not ask the group to follow (--no-guide)");
    avatar.id = 1;
    avatar.x = (float)sx;
    avatar.y = (float)sy;
    avatar.z = 0.0f; /* a flat world: the ground */
    guide.group = group;
    guide.avatar = 0; /* index into our avatar array */
    guide.active = guiding ? 1 : 0;
    guide.reserved = 0;
    start = throng_link_now_ms();
    while (throng_link_now_ms() - start < (uint64_t)(seconds * 1000.0)) {
      /* Walk slowly (0.3 m/s) along the straight line towards where the group was. */
      double walked = 0.3 * (double)(throng_link_now_ms() - start) / 1000.0;
      double ux = (cx0 - sx) / d0, uy = (cy0 - sy) / d0;
      avatar.x = (float)(sx + ux * walked);
      avatar.y = (float)(sy + uy * walked);
      avatar.yaw = (float)atan2(uy, ux);
      /* One consistent update: our avatar, the guide record, and the member whose joints we want. */
      throng_link_write_input(&link, &avatar, 1, &guide, 1, &detail_id, detail_id == 0xFFFFFFFFu ? 0u : 1u);
      /* Sleep until the crowd's next frame (it posts frame_ready after each tick). */
      if (throng_link_wait_frame(&link, last_tick, 1000) < 0) {
        fprintf(stderr, "host: the crowd stopped: %s\n", h->message[0] ? h->message : "no heartbeat");
        goto done;
      }
      if (throng_link_read_frame(&link, frame) != 0) continue;
      last_tick = frame->tick;
      if (throng_link_now_ms() - last_print >= 1000) {
        last_print = throng_link_now_ms();
        group_centroid(h, frame, group, &cx, &cy);
        printf("host: t = %5.2f s  avatar (%.2f, %.2f)  group centroid (%.2f, %.2f)  distance %.2f m", frame->time,
               avatar.x, avatar.y, cx, cy, hypot(cx - avatar.x, cy - avatar.y));
        if (frame->detailed_count > 0) {
          throng_link_detailed* d = throng_link_frame_detailed(h, frame, 0);
          float* angles = throng_link_detailed_angles(d);
          if (d->joint_count > 0) {
            printf("  agent %u root rotation (%.1f, %.1f, %.1f) deg", (unsigned)d->id, angles[0], angles[1],
                   angles[2]);
          }
        }
        printf("\n");
        fflush(stdout);
      }
    }

    /* ---- 5. Did the group follow? -------------------------------------------------------------- */
    group_centroid(h, frame, group, &cx, &cy);
    ex = avatar.x;
    ey = avatar.y;
    d_end = hypot(cx - ex, cy - ey);
    d_from_start = hypot(cx0 - ex, cy0 - ey); /* where the group would be had it not moved */
    printf("host: the group is %.2f m from the avatar; it would be %.2f m had it stayed (started %.2f m away)\n",
           d_end, d_from_start, d0);
    /* Near the avatar, and because the group moved: a group left where it stood stays d_from_start away. */
    ok = d_end < 2.0 && d_end <= d_from_start - 1.0;
    printf("host: %s\n", ok ? "the group follows the avatar" : "the group did NOT follow the avatar");

    /* ---- 6. Bring in a crowd, then take it away again ------------------------------------------ */
    /* A crowd is JSON in throng's crowd-file format (docs/scenario-format.md, "Crowd files"); here
     * six visitors in two groups who wander, spawning in a 2 m square around the avatar (a walkable
     * spot). One could also send the path of a crowd file (THRONG_LINK_PAYLOAD_PATH). throng
     * validates it against the running world and answers; the agents appear at its next tick. */
    {
      throng_link_reply reply;
      char crowd[1024];
      uint32_t before = frame->agent_count, inserted = 0xFFFFFFFFu;
      snprintf(crowd, sizeof crowd,
               "{\"format\": \"throng-crowd/1\", \"id\": \"visitors-from-host\", \"populations\": [{\"id\": "
               "\"visitors-from-host\", \"groups\": 2, \"size\": 3, \"wander\": true, \"spawn\": {\"polygon\": "
               "[[%.2f, %.2f], [%.2f, %.2f], [%.2f, %.2f], [%.2f, %.2f]]}}]}",
               avatar.x - 1.0, avatar.y - 1.0, avatar.x + 1.0, avatar.y - 1.0, avatar.x + 1.0, avatar.y + 1.0,
               avatar.x - 1.0, avatar.y + 1.0);
      if (ask(&link, THRONG_LINK_REQUEST_INSERT, 7, THRONG_LINK_PAYLOAD_JSON, crowd, 0, &reply)) {
        printf("host: insert request %u answered with status %u: %s\n", (unsigned)reply.request_id,
               (unsigned)reply.status, reply.message);
        if (reply.status == THRONG_LINK_STATUS_OK) inserted = reply.crowd;
      }
      if (inserted != 0xFFFFFFFFu && count_after(&link, frame, before + 6u, 1) >= before + 6u) {
        printf("host: crowd inserted: %u -> %u agents\n", (unsigned)before, (unsigned)frame->agent_count);
        if (ask(&link, THRONG_LINK_REQUEST_REMOVE, 8, THRONG_LINK_PAYLOAD_NONE, NULL, inserted, &reply) &&
            reply.status == THRONG_LINK_STATUS_OK && count_after(&link, frame, before, 0) <= before) {
          printf("host: crowd removed: %u agents again\n", (unsigned)frame->agent_count);
        }
      }
      /* A crowd with a mistake is refused, and nothing changes: the answer says where and why. */
      if (ask(&link, THRONG_LINK_REQUEST_INSERT, 9, THRONG_LINK_PAYLOAD_JSON,
              "{\"format\": \"throng-crowd/1\", \"id\": \"oops\", \"populations\": [{\"id\": \"oops\", "
              "\"grups\": 2}]}",
              0, &reply)) {
        printf("host: a bad crowd is refused with status %u: %s\n", (unsigned)reply.status, reply.message);
      }
    }
    guide.active = 0; /* release the group: it resumes its own goals */
    throng_link_write_input(&link, &avatar, 1, &guide, 1, NULL, 0);
  }

done:
  free(frame);
  throng_link_close(&link); /* host_state = DETACHED: the crowd releases our groups */
  if (child > 0) {
    /* The crowd process we started ends when its host detaches. */
    int status = wait_child(child, 5000);
    printf("host: throng link exited with status %d\n", status);
  }
  return ok ? 0 : 1;
}
