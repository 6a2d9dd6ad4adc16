/* throng_link.h — the shared-memory link between a throng crowd process and a host application
 * (a game engine, a virtual-world client, a robot simulator), after Musse et al. §5: the crowd runs
 * as an external process; the host reads the crowd from, and writes its avatars and guides into, a
 * POSIX shared-memory segment, without going through a network.
 *
 * Plain C99 (C ABI, no C++ types), usable from C and C++. Needs POSIX (shm_open, mmap, process-
 * shared semaphores; link with -lrt -pthread on older glibc) and GCC or Clang (the __atomic
 * builtins). In C, define _POSIX_C_SOURCE 200809L (or _GNU_SOURCE) before including any header.
 *
 * Layout (docs/integration.md, "The shared-memory link", has the table):
 *
 *   offset 0            throng_link_header           magic, version, capacities, region offsets,
 *                                                    heartbeats, pids, state, two semaphores
 *   frame_offset[0]     crowd frame buffer 0         throng_link_frame, then max_agents
 *   frame_offset[1]     crowd frame buffer 1           throng_link_agent, then max_detailed
 *                                                      detailed records (stride detailed_size)
 *   skeleton_offset     max_joints throng_link_joint (written once, before state RUNNING)
 *   clips_offset        max_clips throng_link_clip   (written once, before state RUNNING)
 *   host_offset         throng_link_input, then max_avatars throng_link_avatar, max_guides
 *                                                    throng_link_guide, max_detailed uint32 ids
 *   requests_offset     max_requests throng_link_request (ring, the host produces)
 *   replies_offset      max_requests throng_link_reply   (ring, the crowd produces)
 *
 * Every offset and size is in the header: a host computes addresses from it, never from its own
 * idea of the capacities. All numbers are little-endian native (host and crowd share one machine).
 *
 * Consistency: each frame buffer and the host input carry a sequence counter (a seqlock): the
 * writer makes it odd, writes, makes it even again; a reader copies, and retries while the counter
 * was odd or changed meanwhile. The crowd also alternates between the two frame buffers and
 * publishes the index of the newest complete one (latest_frame), so a reader copying the newest
 * buffer has a whole tick before the crowd writes into it again: retries are rare.
 *
 * Wake-ups: two process-shared semaphores in the header. The crowd posts frame_ready after each
 * tick; the host posts input_written after it wrote its input. Liveness: each side bumps its
 * heartbeat counter (the crowd every tick, the host at least every 100 ms); no change for
 * heartbeat_timeout_ms means the peer is gone.
 */
#ifndef THRONG_THRONG_LINK_H
#define THRONG_THRONG_LINK_H

#include <errno.h>
#include <fcntl.h>
#include <semaphore.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/time.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------------- */
/* Constants                                                                                       */

/** First four bytes of the segment: 'T' 'H' 'R' 'L' in memory order. */
#define THRONG_LINK_MAGIC 0x4C524854u
/** Layout version. Any change to a structure below bumps it; both sides refuse a mismatch. */
#define THRONG_LINK_VERSION 2u
/** First word of the UNIX-socket handshake line: "THRONG-LINK <version> <segment name>\n". */
#define THRONG_LINK_HANDSHAKE "THRONG-LINK"
/** The host's answer: "THRONG-LINK-HOST <version>\n"; the crowd replies "OK\n" or "REFUSED <why>\n". */
#define THRONG_LINK_HANDSHAKE_HOST "THRONG-LINK-HOST"
/** latest_frame before the first frame was written. */
#define THRONG_LINK_NO_FRAME 0xFFFFFFFFu
/** Bytes of payload in one request (a path or inline JSON, NUL-terminated). */
#define THRONG_LINK_REQUEST_PAYLOAD 4064u
/** Bytes of text in one reply (NUL-terminated). */
#define THRONG_LINK_REPLY_MESSAGE 256u
/** Bytes of a joint or clip name (NUL-terminated, truncated when longer). */
#define THRONG_LINK_NAME 32u
/** How often the host should bump host_heartbeat at least [ms]. */
#define THRONG_LINK_HOST_BEAT_MS 100u

/* throng_link_header.crowd_state */
#define THRONG_LINK_CROWD_STARTING 0u /**< segment being filled; do not read yet */
#define THRONG_LINK_CROWD_RUNNING 1u  /**< frames are being written */
#define THRONG_LINK_CROWD_STOPPED 2u  /**< the crowd process ended; `message` says why */

/* throng_link_header.host_state (written by the host, except REFUSED) */
#define THRONG_LINK_HOST_NONE 0u     /**< no host attached yet */
#define THRONG_LINK_HOST_ATTACHED 1u /**< a host announced itself (host_version, host_pid) */
#define THRONG_LINK_HOST_DETACHED 2u /**< the host left cleanly */
#define THRONG_LINK_HOST_REFUSED 3u  /**< written by the crowd: host_version did not match; `message` says why */

/* throng_link_header.flags */
#define THRONG_LINK_FLAG_LOCKSTEP 1u /**< the crowd steps only after the host posts input_written */

/* throng_link_frame.flags */
#define THRONG_LINK_FRAME_TRUNCATED 1u /**< more agents in the world than max_agents: raise --max-agents */

/* throng_link_agent.mode (sim::AgentMode) */
#define THRONG_LINK_MODE_WALKING 0u
#define THRONG_LINK_MODE_WAITING 1u
#define THRONG_LINK_MODE_ACTING 2u

/* throng_link_request.kind */
#define THRONG_LINK_REQUEST_INSERT 1u /**< add a crowd (populations, groups, points) */
#define THRONG_LINK_REQUEST_REMOVE 2u /**< remove a crowd inserted earlier (target = its crowd id) */

/* throng_link_request.payload_kind */
#define THRONG_LINK_PAYLOAD_NONE 0u
#define THRONG_LINK_PAYLOAD_PATH 1u /**< payload is a file path the crowd process can read */
#define THRONG_LINK_PAYLOAD_JSON 2u /**< payload is the crowd JSON itself */

/* throng_link_reply.status */
#define THRONG_LINK_STATUS_OK 0u
#define THRONG_LINK_STATUS_NOT_SUPPORTED 1u /**< this crowd process cannot do it (yet) */
#define THRONG_LINK_STATUS_INVALID 2u       /**< malformed request or crowd file; message says what */
#define THRONG_LINK_STATUS_TOO_LARGE 3u     /**< more agents than one request may add */
#define THRONG_LINK_STATUS_UNKNOWN 4u       /**< remove: no crowd with that id */

/* ---------------------------------------------------------------------------------------------- */
/* Structures                                                                                      */

/** A process-shared POSIX semaphore in a fixed 64-byte slot (sem_t's size differs by platform). */
typedef union throng_link_sem {
  sem_t sem;
  unsigned char bytes[64];
} throng_link_sem;

/** The segment's first bytes. Written by the crowd before crowd_state becomes RUNNING, except the
 *  fields marked "host" (the host writes them) and the counters (atomics, see each). */
typedef struct throng_link_header {
  uint32_t magic;       /**< THRONG_LINK_MAGIC */
  uint32_t version;     /**< THRONG_LINK_VERSION of the crowd process that made the segment */
  uint32_t header_size; /**< sizeof(throng_link_header) [bytes] */
  uint32_t flags;       /**< THRONG_LINK_FLAG_* */
  uint64_t total_size;  /**< the whole segment [bytes] */

  /* Capacities (limits: each >= 1 except max_clips and max_joints, which may be 0). */
  uint32_t max_agents;    /**< agent records per frame buffer */
  uint32_t max_detailed;  /**< agents with joint angles per frame (and ids the host may ask for) */
  uint32_t max_joints;    /**< joints per detailed record (= joint_count) */
  uint32_t max_avatars;   /**< avatar records in the host input */
  uint32_t max_guides;    /**< guide records in the host input */
  uint32_t max_requests;  /**< slots in the request ring and in the reply ring */
  uint32_t max_clips;     /**< clip records */
  uint32_t request_size;  /**< sizeof(throng_link_request) [bytes] */

  /* Regions: offsets from the segment's start and sizes [bytes]. */
  uint64_t frame_offset[2]; /**< the two crowd frame buffers */
  uint64_t frame_size;      /**< one frame buffer: frame header, agents, detailed records */
  uint32_t agent_size;      /**< sizeof(throng_link_agent) [bytes] */
  uint32_t detailed_size;   /**< one detailed record: sizeof(throng_link_detailed) + 12 * max_joints */
  uint64_t skeleton_offset; /**< max_joints throng_link_joint */
  uint64_t clips_offset;    /**< max_clips throng_link_clip */
  uint64_t host_offset;     /**< throng_link_input and its arrays */
  uint64_t host_size;
  uint64_t requests_offset; /**< max_requests throng_link_request */
  uint64_t replies_offset;  /**< max_requests throng_link_reply */

  /* The run. */
  double dt;                     /**< simulated time per tick [s] */
  double tick_rate;              /**< ticks per wall-clock second [Hz] (real time when 1/dt) */
  uint32_t heartbeat_timeout_ms; /**< a peer whose heartbeat stays still this long is gone [ms] */
  uint32_t joint_count;          /**< joints in the skeleton (<= max_joints) */
  uint32_t clip_count;           /**< clips in the clip table (<= max_clips) */
  uint32_t crowd_state;          /**< THRONG_LINK_CROWD_* (atomic) */
  int32_t crowd_pid;             /**< process id of the crowd process */
  int32_t host_pid;              /**< host: its process id (0 before attaching) */
  uint32_t host_version;         /**< host: the THRONG_LINK_VERSION it was built with */
  uint32_t host_state;           /**< host: THRONG_LINK_HOST_* (atomic) */
  uint64_t crowd_heartbeat;      /**< bumped by the crowd every tick and every 100 ms while idle (atomic) */
  uint64_t host_heartbeat;       /**< host: bumped at least every THRONG_LINK_HOST_BEAT_MS (atomic) */
  uint32_t latest_frame;         /**< 0 or 1: newest complete frame buffer; THRONG_LINK_NO_FRAME before (atomic) */
  uint32_t reserved0;

  /* Request and reply rings (single producer, single consumer; counters only grow; atomics). */
  uint64_t requests_written; /**< host: requests put in the ring (slot = count % max_requests) */
  uint64_t requests_read;    /**< requests the crowd took */
  uint64_t replies_written;  /**< replies the crowd put in its ring */
  uint64_t replies_read;     /**< host: replies it took */

  char scenario[128]; /**< the scenario's name (NUL-terminated) */
  char message[256];  /**< why the crowd stopped or refused the host (NUL-terminated; set with the state) */
  uint32_t reserved1[4];

  throng_link_sem frame_ready;   /**< the crowd posts after each tick (at most one pending post) */
  throng_link_sem input_written; /**< the host posts after writing its input */
} throng_link_header;

/** Head of one crowd frame buffer; max_agents throng_link_agent follow, then max_detailed
 *  detailed records of detailed_size bytes each. */
typedef struct throng_link_frame {
  uint64_t seq;            /**< seqlock: odd while the crowd writes this buffer (atomic) */
  uint64_t tick;           /**< simulation tick */
  double time;             /**< simulated time, tick * dt [s] */
  uint32_t agent_count;    /**< agent records filled (<= max_agents) */
  uint32_t total_agents;   /**< agents in the world (> agent_count when truncated) */
  uint32_t detailed_count; /**< detailed records filled (<= max_detailed) */
  uint32_t group_count;    /**< groups in the world (ids 0 .. group_count - 1) */
  uint32_t flags;          /**< THRONG_LINK_FRAME_* */
  uint32_t reserved0;
  uint64_t reserved[2];
} throng_link_frame;

/** One agent in a frame. The crowd's ground plane is (x, y), z is up (metres, right-handed). */
typedef struct throng_link_agent {
  uint32_t id;    /**< stable id (spawn order), never reused */
  uint32_t group; /**< stable group id (0 .. group_count - 1) */
  float x, y, z;  /**< position [m]; z = 0 in 2D scenarios */
  float yaw;      /**< heading: angle from +x towards +y [rad], in (-pi, pi] */
  float phase;    /**< position in the clip, [0, 1) */
  uint16_t clip;  /**< clip playing: index into the clip table */
  uint8_t mode;   /**< THRONG_LINK_MODE_* */
  uint8_t reserved;
} throng_link_agent;

/** Joint angles of one agent the host asked for (throng_link_input's detail ids); followed by
 *  3 * max_joints floats: X, Y and Z rotation of each skeleton joint [degrees], skeleton order. */
typedef struct throng_link_detailed {
  uint32_t id;          /**< stable agent id */
  uint32_t joint_count; /**< joints filled (= header joint_count) */
  uint16_t clip;        /**< clip sampled */
  uint16_t reserved0;
  float phase;          /**< phase sampled, [0, 1) */
} throng_link_detailed;

/** One joint of the skeleton every clip animates (H-Anim names in the bundled library). */
typedef struct throng_link_joint {
  char name[THRONG_LINK_NAME]; /**< NUL-terminated */
  int32_t parent;              /**< index of the parent joint, -1 for the root */
  float offset[3];             /**< from the parent joint [m] */
} throng_link_joint;

/** One motion clip; throng_link_agent.clip indexes this table. */
typedef struct throng_link_clip {
  char name[THRONG_LINK_NAME]; /**< "idle", "walk" or an action's name (NUL-terminated) */
  float duration;              /**< one cycle or the whole action [s] */
  uint32_t loops;              /**< 1: loops (idle, walk); 0: plays once */
} throng_link_clip;

/** Head of the host's input; max_avatars throng_link_avatar follow, then max_guides
 *  throng_link_guide, then max_detailed uint32_t agent ids. Written by the host only. */
typedef struct throng_link_input {
  uint64_t seq;          /**< seqlock: odd while the host writes (atomic) */
  uint32_t avatar_count; /**< avatar records filled (<= max_avatars) */
  uint32_t guide_count;  /**< guide records filled (<= max_guides) */
  uint32_t detail_count; /**< agent ids filled (<= max_detailed): their joint angles are wanted */
  uint32_t reserved0;
  uint64_t reserved[1];
} throng_link_input;

/** An avatar of the host (a user, a robot): steers the crowd's level of detail and guides groups. */
typedef struct throng_link_avatar {
  uint32_t id;  /**< the host's id for it (free to choose) */
  float x, y;   /**< position on the crowd's ground plane [m] */
  float z;      /**< height of the floor it stands on [m] (multi-level worlds; 0 in 2D scenarios). Since version 2 */
  float yaw;    /**< heading from +x towards +y [rad] */
} throng_link_avatar;

/** "Group `group` follows avatar `avatar`": its dynamic goal is that avatar's position, as long as
 *  the record is present and active. A group whose record disappears or turns inactive is released
 *  and resumes its own goals. */
typedef struct throng_link_guide {
  uint32_t group;  /**< stable group id */
  uint32_t avatar; /**< index into the avatar array (not the avatar's id) */
  uint32_t active; /**< 1 guide, 0 release */
  uint32_t reserved;
} throng_link_guide;

/** A request to insert or remove a crowd while the simulation runs. */
typedef struct throng_link_request {
  uint32_t kind;         /**< THRONG_LINK_REQUEST_* */
  uint32_t request_id;   /**< the host's number for it; the reply carries it back */
  uint32_t payload_kind; /**< THRONG_LINK_PAYLOAD_* */
  uint32_t payload_size; /**< bytes of payload used, without the NUL (< THRONG_LINK_REQUEST_PAYLOAD) */
  uint32_t target;       /**< remove: the crowd id an insert reply gave */
  uint32_t reserved[3];
  char payload[THRONG_LINK_REQUEST_PAYLOAD]; /**< path or JSON, NUL-terminated */
} throng_link_request;

/** The crowd's answer to one request. */
typedef struct throng_link_reply {
  uint32_t request_id; /**< as in the request */
  uint32_t status;     /**< THRONG_LINK_STATUS_* */
  uint32_t crowd;      /**< insert: id of the new crowd (for remove); 0 otherwise */
  uint32_t reserved;
  char message[THRONG_LINK_REPLY_MESSAGE]; /**< what happened, for people (NUL-terminated) */
} throng_link_reply;

/* Sizes are part of the contract (a change bumps THRONG_LINK_VERSION). */
#ifdef __cplusplus
#define THRONG_LINK_STATIC_ASSERT(cond, name) static_assert(cond, #name)
#else
#define THRONG_LINK_STATIC_ASSERT(cond, name) typedef char throng_link_assert_##name[(cond) ? 1 : -1]
#endif
THRONG_LINK_STATIC_ASSERT(sizeof(sem_t) <= 64, sem_fits);
THRONG_LINK_STATIC_ASSERT(sizeof(throng_link_sem) == 64, sem_size);
THRONG_LINK_STATIC_ASSERT(sizeof(throng_link_header) == 768, header_size);
THRONG_LINK_STATIC_ASSERT(offsetof(throng_link_header, frame_ready) == 640, header_sem_offset);
THRONG_LINK_STATIC_ASSERT(sizeof(throng_link_frame) == 64, frame_size);
THRONG_LINK_STATIC_ASSERT(sizeof(throng_link_agent) == 32, agent_size);
THRONG_LINK_STATIC_ASSERT(sizeof(throng_link_detailed) == 16, detailed_size);
THRONG_LINK_STATIC_ASSERT(sizeof(throng_link_joint) == 48, joint_size);
THRONG_LINK_STATIC_ASSERT(sizeof(throng_link_clip) == 40, clip_size);
THRONG_LINK_STATIC_ASSERT(sizeof(throng_link_input) == 32, input_size);
THRONG_LINK_STATIC_ASSERT(sizeof(throng_link_avatar) == 20, avatar_size);
THRONG_LINK_STATIC_ASSERT(sizeof(throng_link_guide) == 16, guide_size);
THRONG_LINK_STATIC_ASSERT(sizeof(throng_link_request) == 4096, request_size);
THRONG_LINK_STATIC_ASSERT(sizeof(throng_link_reply) == 272, reply_size);

/* ---------------------------------------------------------------------------------------------- */
/* Region access (pointer arithmetic from the header's offsets)                                     */

static inline throng_link_frame* throng_link_frame_at(throng_link_header* h, uint32_t index) {
  return (throng_link_frame*)((unsigned char*)h + h->frame_offset[index & 1u]);
}
/** Agent records of a frame (in the segment or in a copy of frame_size bytes). */
static inline throng_link_agent* throng_link_frame_agents(const throng_link_header* h, throng_link_frame* f) {
  (void)h;
  return (throng_link_agent*)((unsigned char*)f + sizeof(throng_link_frame));
}
/** Detailed record `i` of a frame; its angles follow at throng_link_detailed_angles. */
static inline throng_link_detailed* throng_link_frame_detailed(const throng_link_header* h, throng_link_frame* f,
                                                               uint32_t i) {
  return (throng_link_detailed*)((unsigned char*)f + sizeof(throng_link_frame) +
                                 (size_t)h->max_agents * h->agent_size + (size_t)i * h->detailed_size);
}
/** 3 * joint_count floats: X, Y, Z rotation per joint [degrees]. */
static inline float* throng_link_detailed_angles(throng_link_detailed* d) {
  return (float*)((unsigned char*)d + sizeof(throng_link_detailed));
}
static inline throng_link_joint* throng_link_skeleton(throng_link_header* h) {
  return (throng_link_joint*)((unsigned char*)h + h->skeleton_offset);
}
static inline throng_link_clip* throng_link_clips(throng_link_header* h) {
  return (throng_link_clip*)((unsigned char*)h + h->clips_offset);
}
static inline throng_link_input* throng_link_input_of(throng_link_header* h) {
  return (throng_link_input*)((unsigned char*)h + h->host_offset);
}
static inline throng_link_avatar* throng_link_input_avatars(throng_link_header* h) {
  return (throng_link_avatar*)((unsigned char*)throng_link_input_of(h) + sizeof(throng_link_input));
}
static inline throng_link_guide* throng_link_input_guides(throng_link_header* h) {
  return (throng_link_guide*)(throng_link_input_avatars(h) + h->max_avatars);
}
static inline uint32_t* throng_link_input_detail_ids(throng_link_header* h) {
  return (uint32_t*)(throng_link_input_guides(h) + h->max_guides);
}
static inline throng_link_request* throng_link_requests(throng_link_header* h) {
  return (throng_link_request*)((unsigned char*)h + h->requests_offset);
}
static inline throng_link_reply* throng_link_replies(throng_link_header* h) {
  return (throng_link_reply*)((unsigned char*)h + h->replies_offset);
}

/* ---------------------------------------------------------------------------------------------- */
/* Atomics and time                                                                                */

#define THRONG_LINK_LOAD(p) __atomic_load_n((p), __ATOMIC_ACQUIRE)
#define THRONG_LINK_STORE(p, v) __atomic_store_n((p), (v), __ATOMIC_RELEASE)

/** Monotonic clock [ms]. */
static inline uint64_t throng_link_now_ms(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (uint64_t)ts.tv_sec * 1000u + (uint64_t)ts.tv_nsec / 1000000u;
}

/** Sleeps `ms` milliseconds. */
static inline void throng_link_sleep_ms(uint32_t ms) {
  struct timespec ts;
  ts.tv_sec = (time_t)(ms / 1000u);
  ts.tv_nsec = (long)(ms % 1000u) * 1000000L;
  while (nanosleep(&ts, &ts) != 0 && errno == EINTR) {
  }
}

/** Waits on a process-shared semaphore for at most `timeout_ms`. 1 posted, 0 timed out. */
static inline int throng_link_sem_wait(throng_link_sem* s, uint32_t timeout_ms) {
  struct timespec deadline;
  clock_gettime(CLOCK_REALTIME, &deadline); /* sem_timedwait measures against CLOCK_REALTIME */
  deadline.tv_sec += (time_t)(timeout_ms / 1000u);
  deadline.tv_nsec += (long)(timeout_ms % 1000u) * 1000000L;
  if (deadline.tv_nsec >= 1000000000L) {
    deadline.tv_sec += 1;
    deadline.tv_nsec -= 1000000000L;
  }
  for (;;) {
    if (sem_timedwait(&s->sem, &deadline) == 0) return 1;
    if (errno == EINTR) continue;
    return 0;
  }
}

/** Posts unless a post is already pending (the waiter reads the newest state anyway). */
static inline void throng_link_sem_post_once(throng_link_sem* s) {
  int value = 0;
  if (sem_getvalue(&s->sem, &value) == 0 && value > 0) return;
  sem_post(&s->sem);
}

/* ---------------------------------------------------------------------------------------------- */
/* Host side: open, read frames, write input, requests                                             */

/** An open link, as the host holds it. */
typedef struct throng_link {
  throng_link_header* header; /**< the mapped segment (NULL when closed) */
  size_t size;                /**< mapped bytes */
  uint64_t last_crowd_beat;   /**< crowd heartbeat seen last (throng_link_crowd_alive) */
  uint64_t last_crowd_change; /**< when it last changed [ms, monotonic] */
} throng_link;

/** Opens the segment `name` ("/throng-1234") and checks its magic, version and sizes. Waits up to
 *  `timeout_ms` for it to appear and for the crowd to reach RUNNING. 0 on success; -1 with a
 *  sentence in `error` (a version mismatch is refused here). */
static inline int throng_link_open(throng_link* link, const char* name, uint32_t timeout_ms, char* error,
                                   size_t error_size) {
  const uint64_t start = throng_link_now_ms();
  int fd = -1;
  struct stat st;
  throng_link_header* h = NULL;
  memset(link, 0, sizeof *link);
  for (;;) {
    fd = shm_open(name, O_RDWR, 0);
    if (fd >= 0 && fstat(fd, &st) == 0 && (size_t)st.st_size >= sizeof(throng_link_header)) break;
    if (fd >= 0) close(fd);
    fd = -1;
    if (throng_link_now_ms() - start >= timeout_ms) {
      snprintf(error, error_size, "no throng link segment %s (is `throng link --shm %s` running?)", name, name);
      return -1;
    }
    throng_link_sleep_ms(10);
  }
  h = (throng_link_header*)mmap(NULL, (size_t)st.st_size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  close(fd);
  if (h == MAP_FAILED) {
    snprintf(error, error_size, "cannot map %s: %s", name, strerror(errno));
    return -1;
  }
  /* The crowd fills the header before RUNNING; wait for it. */
  while (THRONG_LINK_LOAD(&h->crowd_state) == THRONG_LINK_CROWD_STARTING &&
         throng_link_now_ms() - start < timeout_ms) {
    throng_link_sleep_ms(5);
  }
  if (h->magic != THRONG_LINK_MAGIC) {
    snprintf(error, error_size, "%s is not a throng link segment (magic %08x, expected %08x)", name,
             (unsigned)h->magic, THRONG_LINK_MAGIC);
  } else if (h->version != THRONG_LINK_VERSION) {
    snprintf(error, error_size,
             "%s has layout version %u but this host was built for version %u: refused (rebuild the host "
             "with the throng_link.h of that throng)",
             name, (unsigned)h->version, THRONG_LINK_VERSION);
  } else if (h->header_size != sizeof(throng_link_header) || h->total_size > (uint64_t)st.st_size ||
             h->agent_size != sizeof(throng_link_agent) || h->request_size != sizeof(throng_link_request)) {
    snprintf(error, error_size, "%s: sizes in the header do not match this header file", name);
  } else if (THRONG_LINK_LOAD(&h->crowd_state) == THRONG_LINK_CROWD_STARTING) {
    snprintf(error, error_size, "%s: the crowd process did not finish starting", name);
  } else {
    link->header = h;
    link->size = (size_t)st.st_size;
    link->last_crowd_beat = THRONG_LINK_LOAD(&h->crowd_heartbeat);
    link->last_crowd_change = throng_link_now_ms();
    return 0;
  }
  munmap(h, (size_t)st.st_size);
  return -1;
}

/** Announces this host to the crowd (host_version, host_pid, state ATTACHED). */
static inline void throng_link_attach(throng_link* link) {
  throng_link_header* h = link->header;
  h->host_version = THRONG_LINK_VERSION;
  h->host_pid = (int32_t)getpid();
  __atomic_add_fetch(&h->host_heartbeat, 1, __ATOMIC_RELEASE);
  THRONG_LINK_STORE(&h->host_state, THRONG_LINK_HOST_ATTACHED);
}

/** Tells the crowd this host leaves (it releases the guided groups) and unmaps the segment. */
static inline void throng_link_close(throng_link* link) {
  if (!link->header) return;
  if (THRONG_LINK_LOAD(&link->header->host_state) == THRONG_LINK_HOST_ATTACHED) {
    THRONG_LINK_STORE(&link->header->host_state, THRONG_LINK_HOST_DETACHED);
    sem_post(&link->header->input_written.sem);
  }
  munmap(link->header, link->size);
  link->header = NULL;
}

/** Bumps the host heartbeat; call at least every THRONG_LINK_HOST_BEAT_MS (writing input does it). */
static inline void throng_link_host_beat(throng_link* link) {
  __atomic_add_fetch(&link->header->host_heartbeat, 1, __ATOMIC_RELEASE);
}

/** 1 while the crowd runs and its heartbeat moved within heartbeat_timeout_ms; 0 when it stopped
 *  (header message says why) or went silent (crashed). */
static inline int throng_link_crowd_alive(throng_link* link) {
  throng_link_header* h = link->header;
  const uint64_t beat = THRONG_LINK_LOAD(&h->crowd_heartbeat);
  const uint64_t now = throng_link_now_ms();
  if (THRONG_LINK_LOAD(&h->crowd_state) == THRONG_LINK_CROWD_STOPPED) return 0;
  if (THRONG_LINK_LOAD(&h->host_state) == THRONG_LINK_HOST_REFUSED) return 0;
  if (beat != link->last_crowd_beat) {
    link->last_crowd_beat = beat;
    link->last_crowd_change = now;
    return 1;
  }
  return now - link->last_crowd_change < h->heartbeat_timeout_ms;
}

/** Copies the newest complete frame into `out` (frame_size bytes, e.g. malloc(header->frame_size)).
 *  Never torn: retries while the crowd writes that buffer. 0 on success; -1 before the first frame
 *  or when the crowd kept the buffer busy for 1000 tries. */
static inline int throng_link_read_frame(throng_link* link, void* out) {
  throng_link_header* h = link->header;
  int attempt;
  for (attempt = 0; attempt < 1000; ++attempt) {
    const uint32_t index = THRONG_LINK_LOAD(&h->latest_frame);
    throng_link_frame* f;
    uint64_t before, after;
    if (index == THRONG_LINK_NO_FRAME) return -1;
    f = throng_link_frame_at(h, index);
    before = THRONG_LINK_LOAD(&f->seq);
    if (before & 1u) continue; /* being written: the crowd moved on already; look again */
    memcpy(out, f, (size_t)h->frame_size);
    __atomic_thread_fence(__ATOMIC_ACQUIRE);
    after = __atomic_load_n(&f->seq, __ATOMIC_RELAXED);
    if (before == after) {
      ((throng_link_frame*)out)->seq = before;
      return 0;
    }
  }
  return -1;
}

/** Waits until a frame newer than `after_tick` is available or `timeout_ms` passed (it bumps the
 *  host heartbeat meanwhile). 1 new frame, 0 timeout, -1 the crowd stopped or went silent. Pass
 *  UINT64_MAX as `after_tick` to accept any frame. */
static inline int throng_link_wait_frame(throng_link* link, uint64_t after_tick, uint32_t timeout_ms) {
  throng_link_header* h = link->header;
  const uint64_t start = throng_link_now_ms();
  for (;;) {
    const uint32_t index = THRONG_LINK_LOAD(&h->latest_frame);
    uint64_t elapsed;
    if (index != THRONG_LINK_NO_FRAME) {
      const uint64_t tick = __atomic_load_n(&throng_link_frame_at(h, index)->tick, __ATOMIC_ACQUIRE);
      if (after_tick == UINT64_MAX || tick > after_tick) return 1;
    }
    if (!throng_link_crowd_alive(link)) return -1;
    elapsed = throng_link_now_ms() - start;
    if (elapsed >= timeout_ms) return 0;
    throng_link_host_beat(link);
    {
      uint32_t wait = (uint32_t)(timeout_ms - elapsed);
      throng_link_sem_wait(&h->frame_ready, wait < THRONG_LINK_HOST_BEAT_MS ? wait : THRONG_LINK_HOST_BEAT_MS);
    }
  }
}

/** Writes the host input in one consistent update: avatars, guides and the agents whose joint
 *  angles are wanted (counts are clamped to the capacities). Bumps the heartbeat and wakes the
 *  crowd. Returns the number of records dropped for lack of room (0 when everything fit). */
static inline uint32_t throng_link_write_input(throng_link* link, const throng_link_avatar* avatars,
                                               uint32_t avatar_count, const throng_link_guide* guides,
                                               uint32_t guide_count, const uint32_t* detail_ids,
                                               uint32_t detail_count) {
  throng_link_header* h = link->header;
  throng_link_input* in = throng_link_input_of(h);
  const uint32_t na = avatar_count < h->max_avatars ? avatar_count : h->max_avatars;
  const uint32_t ng = guide_count < h->max_guides ? guide_count : h->max_guides;
  const uint32_t nd = detail_count < h->max_detailed ? detail_count : h->max_detailed;
  const uint64_t seq = __atomic_load_n(&in->seq, __ATOMIC_RELAXED);
  __atomic_store_n(&in->seq, seq + 1, __ATOMIC_RELAXED); /* odd: writing */
  __atomic_thread_fence(__ATOMIC_RELEASE);
  if (na) memcpy(throng_link_input_avatars(h), avatars, na * sizeof *avatars);
  if (ng) memcpy(throng_link_input_guides(h), guides, ng * sizeof *guides);
  if (nd) memcpy(throng_link_input_detail_ids(h), detail_ids, nd * sizeof *detail_ids);
  in->avatar_count = na;
  in->guide_count = ng;
  in->detail_count = nd;
  __atomic_store_n(&in->seq, seq + 2, __ATOMIC_RELEASE); /* even: consistent */
  throng_link_host_beat(link);
  throng_link_sem_post_once(&h->input_written);
  return (avatar_count - na) + (guide_count - ng) + (detail_count - nd);
}

/** Queues an insert or remove request. 0 queued; -1 the ring is full (take replies first) or the
 *  payload does not fit (use a path). */
static inline int throng_link_send_request(throng_link* link, uint32_t kind, uint32_t request_id,
                                           uint32_t payload_kind, const char* payload, uint32_t target) {
  throng_link_header* h = link->header;
  const uint64_t written = __atomic_load_n(&h->requests_written, __ATOMIC_RELAXED);
  const size_t length = payload ? strlen(payload) : 0;
  throng_link_request* r;
  if (written - THRONG_LINK_LOAD(&h->requests_read) >= h->max_requests) return -1;
  if (length >= THRONG_LINK_REQUEST_PAYLOAD) return -1;
  r = throng_link_requests(h) + (written % h->max_requests);
  memset(r, 0, sizeof *r);
  r->kind = kind;
  r->request_id = request_id;
  r->payload_kind = payload_kind;
  r->payload_size = (uint32_t)length;
  r->target = target;
  if (length) memcpy(r->payload, payload, length);
  THRONG_LINK_STORE(&h->requests_written, written + 1);
  throng_link_sem_post_once(&h->input_written);
  return 0;
}

/** Takes the oldest reply not yet taken. 1 one copied into `out`, 0 none waiting. */
static inline int throng_link_take_reply(throng_link* link, throng_link_reply* out) {
  throng_link_header* h = link->header;
  const uint64_t read = __atomic_load_n(&h->replies_read, __ATOMIC_RELAXED);
  if (read == THRONG_LINK_LOAD(&h->replies_written)) return 0;
  memcpy(out, throng_link_replies(h) + (read % h->max_requests), sizeof *out);
  out->message[THRONG_LINK_REPLY_MESSAGE - 1] = '\0';
  THRONG_LINK_STORE(&h->replies_read, read + 1);
  return 1;
}

/** The UNIX-socket handshake (start mode c): connects to `socket_path`, reads
 *  "THRONG-LINK <version> <name>\n", refuses another version, answers "THRONG-LINK-HOST <version>\n"
 *  and reads the crowd's "OK" (or "REFUSED <why>"). The segment's name lands in `name`.
 *  0 on success; -1 with a sentence in `error`. */
static inline int throng_link_handshake(const char* socket_path, char* name, size_t name_size, char* error,
                                        size_t error_size) {
  struct sockaddr_un address;
  char line[512];
  size_t used = 0;
  int lines = 0;
  unsigned version = 0;
  char segment[256];
  int fd = socket(AF_UNIX, SOCK_STREAM, 0);
  if (fd < 0) {
    snprintf(error, error_size, "socket: %s", strerror(errno));
    return -1;
  }
  memset(&address, 0, sizeof address);
  address.sun_family = AF_UNIX;
  if (strlen(socket_path) >= sizeof address.sun_path) {
    snprintf(error, error_size, "socket path %s is too long (at most %u bytes)", socket_path,
             (unsigned)sizeof address.sun_path - 1u);
    close(fd);
    return -1;
  }
  strcpy(address.sun_path, socket_path);
  if (connect(fd, (struct sockaddr*)&address, sizeof address) != 0) {
    snprintf(error, error_size, "cannot connect to %s: %s (is `throng link --socket %s` running?)", socket_path,
             strerror(errno), socket_path);
    close(fd);
    return -1;
  }
  /* Read two lines at most: the crowd's greeting, then its verdict on our version. */
  while (lines < 2) {
    char* newline;
    ssize_t got = read(fd, line + used, sizeof line - 1 - used);
    if (got <= 0) {
      snprintf(error, error_size, "%s closed the handshake early", socket_path);
      close(fd);
      return -1;
    }
    used += (size_t)got;
    line[used] = '\0';
    while ((newline = strchr(line, '\n')) != NULL && lines < 2) {
      *newline = '\0';
      if (lines == 0) {
        char reply[64];
        if (sscanf(line, THRONG_LINK_HANDSHAKE " %u %255s", &version, segment) != 2) {
          snprintf(error, error_size, "%s: unexpected greeting \"%.100s\" (expected \"%s <version> <name>\")",
                   socket_path, line, THRONG_LINK_HANDSHAKE);
          close(fd);
          return -1;
        }
        if (version != THRONG_LINK_VERSION) {
          snprintf(error, error_size,
                   "%s speaks link version %u but this host was built for version %u: refused", socket_path,
                   version, THRONG_LINK_VERSION);
          close(fd);
          return -1;
        }
        snprintf(reply, sizeof reply, THRONG_LINK_HANDSHAKE_HOST " %u\n", THRONG_LINK_VERSION);
        if (write(fd, reply, strlen(reply)) < 0) {
          snprintf(error, error_size, "%s: %s", socket_path, strerror(errno));
          close(fd);
          return -1;
        }
      } else if (strncmp(line, "OK", 2) != 0) {
        snprintf(error, error_size, "%s refused this host: %.200s", socket_path, line);
        close(fd);
        return -1;
      }
      ++lines;
      used -= (size_t)(newline + 1 - line);
      memmove(line, newline + 1, used + 1);
    }
  }
  close(fd);
  if (strlen(segment) >= name_size) {
    snprintf(error, error_size, "segment name too long");
    return -1;
  }
  strcpy(name, segment);
  return 0;
}

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* THRONG_THRONG_LINK_H */
