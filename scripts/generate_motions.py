#!/usr/bin/env python3
"""Generates the bundled motion clips scenarios/motions/*.bvh procedurally (the motion library).

Authored for throng (no captured data): an H-Anim-like skeleton in metres, Y up, facing +Z (the
figure's left is +X), rest pose standing with arms hanging. Rotations are in degrees, channel
order Zrotation Xrotation Yrotation; a positive X rotation swings a hanging limb backwards.

    look.bvh  4.00 s  stand, turn torso and head to the left, look slightly up, turn back
    idle.bvh  2.00 s  stand and breathe, small weight shift (loops)
    walk.bvh  1.12 s  one walk cycle (two steps) in place; the viewer moves the root (loops)

The Common Ground gestures (docs/motion-library.md) start and end in the rest pose unless noted:

    turn.bvh          1.00 s  turn in place 90 degrees to the left (root ends at Y rotation +90)
    wave.bvh          1.60 s  right arm raised to the side, forearm up, hand waves twice
    call_out.bvh      1.20 s  both hands cupped at the mouth, head and chest forward
    look_at.bvh       1.20 s  head (and a little torso) turns to the left and holds (ends turned)
    nod.bvh           0.80 s  one nod: head down, up, back to neutral
    point_toward.bvh  1.40 s  right arm extended forward at shoulder height, held, lowered
    point_down.bvh    1.20 s  right arm points down in front, torso and head lean to look
    talk.bvh          2.00 s  forearms raised, small hand beats, head nods and turns (loops)

Run from the repository root:  python3 scripts/generate_motions.py
The output is deterministic; rerunning it reproduces the committed files byte for byte.
"""
import math
import os

FRAME_TIME = 0.04  # 25 frames per second

# (name, parent, offset [m]); End Sites: name -> offset.
SKELETON = [
    ("HumanoidRoot", None, (0.0, 0.95, 0.0)),
    ("sacroiliac", "HumanoidRoot", (0.0, 0.0, 0.0)),
    ("l_hip", "sacroiliac", (0.09, -0.05, 0.0)),
    ("l_knee", "l_hip", (0.0, -0.42, 0.0)),
    ("l_ankle", "l_knee", (0.0, -0.41, 0.0)),
    ("r_hip", "sacroiliac", (-0.09, -0.05, 0.0)),
    ("r_knee", "r_hip", (0.0, -0.42, 0.0)),
    ("r_ankle", "r_knee", (0.0, -0.41, 0.0)),
    ("vl5", "HumanoidRoot", (0.0, 0.10, 0.0)),
    ("skullbase", "vl5", (0.0, 0.52, 0.0)),
    ("l_shoulder", "vl5", (0.19, 0.42, 0.0)),
    ("l_elbow", "l_shoulder", (0.0, -0.29, 0.0)),
    ("l_wrist", "l_elbow", (0.0, -0.26, 0.0)),
    ("r_shoulder", "vl5", (-0.19, 0.42, 0.0)),
    ("r_elbow", "r_shoulder", (0.0, -0.29, 0.0)),
    ("r_wrist", "r_elbow", (0.0, -0.26, 0.0)),
]
END_SITES = {
    "l_ankle": (0.0, -0.07, 0.14),
    "r_ankle": (0.0, -0.07, 0.14),
    "skullbase": (0.0, 0.22, 0.0),
    "l_wrist": (0.0, -0.08, 0.0),
    "r_wrist": (0.0, -0.08, 0.0),
}
JOINTS = [j[0] for j in SKELETON]
ROOT_HEIGHT = SKELETON[0][2][1]


def hierarchy():
    lines = ["HIERARCHY"]

    def emit(name, depth):
        pad = "  " * depth
        parent = next(j for j in SKELETON if j[0] == name)
        lines.append(f"{pad}{'ROOT' if parent[1] is None else 'JOINT'} {name}")
        lines.append(f"{pad}{{")
        lines.append(f"{pad}  OFFSET {' '.join(f'{v:.2f}' for v in parent[2])}")
        if parent[1] is None:
            lines.append(f"{pad}  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation")
        else:
            lines.append(f"{pad}  CHANNELS 3 Zrotation Xrotation Yrotation")
        for child in (j[0] for j in SKELETON if j[1] == name):
            emit(child, depth + 1)
        if name in END_SITES:
            lines.append(f"{pad}  End Site")
            lines.append(f"{pad}  {{")
            lines.append(f"{pad}    OFFSET {' '.join(f'{v:.2f}' for v in END_SITES[name])}")
            lines.append(f"{pad}  }}")
        lines.append(f"{pad}}}")

    emit("HumanoidRoot", 0)
    return lines


def channel_order():
    """Joint names in the order their channels appear in a frame row (depth-first file order)."""
    order = []

    def visit(name):
        order.append(name)
        for child in (j[0] for j in SKELETON if j[1] == name):
            visit(child)

    visit("HumanoidRoot")
    return order


def smoothstep(x):
    x = min(1.0, max(0.0, x))
    return x * x * (3.0 - 2.0 * x)


def rest():
    """A pose: root position [m] and per-joint (z, x, y) rotations [deg]."""
    pose = {name: [0.0, 0.0, 0.0] for name in JOINTS}
    pose["root_pos"] = [0.0, ROOT_HEIGHT, 0.0]
    # Relaxed stance: elbows slightly bent, arms a little away from the body.
    pose["l_shoulder"][0] = 4.0
    pose["r_shoulder"][0] = -4.0
    pose["l_elbow"][1] = -8.0
    pose["r_elbow"][1] = -8.0
    return pose


def breathe(pose, t, period):
    s = math.sin(2.0 * math.pi * t / period)
    pose["vl5"][1] += -1.2 * s  # chest rises, a slight extension
    pose["skullbase"][1] += 0.8 * s
    pose["l_shoulder"][0] += 0.6 * s
    pose["r_shoulder"][0] -= 0.6 * s


def look(t):
    duration = 4.0
    pose = rest()
    breathe(pose, t, duration)
    turn = smoothstep(t / 1.3) - smoothstep((t - 2.7) / 1.3)  # 0 → 1, hold, → 0
    glance = math.sin(math.pi * min(1.0, max(0.0, (t - 1.3) / 1.4)))  # a look up during the hold
    pose["sacroiliac"][2] += 6.0 * turn
    pose["vl5"][2] += 18.0 * turn
    pose["skullbase"][2] += 32.0 * turn
    pose["skullbase"][1] += -10.0 * glance  # chin up: head tilts back
    pose["skullbase"][0] += 3.0 * turn       # a slight roll, natural when turning
    pose["r_shoulder"][1] += -6.0 * turn     # the far arm drifts forward with the torso
    pose["l_shoulder"][1] += 4.0 * turn
    pose["root_pos"][0] += 0.02 * turn       # weight onto the left leg
    return pose


def idle(t):
    duration = 2.0
    pose = rest()
    breathe(pose, t, duration)
    s = math.sin(2.0 * math.pi * t / duration)
    pose["root_pos"][0] += 0.012 * s
    pose["sacroiliac"][0] += -1.5 * s
    pose["vl5"][0] += 1.0 * s
    pose["l_hip"][0] += 1.5 * s
    pose["r_hip"][0] += 1.5 * s
    pose["skullbase"][2] += 2.0 * math.sin(2.0 * math.pi * t / duration + 1.0)
    return pose


def walk(t):
    period = 1.12
    phase = 2.0 * math.pi * t / period  # left heel strike at phase 0
    pose = rest()

    def leg(side, p):
        # Hip: flexion forward (negative X) at heel strike, extension behind at toe-off.
        pose[side + "_hip"][1] = -22.0 * math.cos(p) + 4.0
        # Knee: small flexion at loading, large in swing (peak ~60° around p = 1.35π).
        knee = 12.0 * max(0.0, math.sin(p)) ** 2 + 58.0 * max(0.0, math.sin(p - 0.85 * math.pi)) ** 2
        pose[side + "_knee"][1] = knee
        # Ankle: plantar flexion at push-off, dorsiflexion in swing.
        pose[side + "_ankle"][1] = -10.0 * math.sin(p - 0.6 * math.pi)

    leg("l", phase)
    leg("r", phase + math.pi)
    # Arms swing opposite to the legs; elbows bend more on the forward swing.
    for side, p in (("l", phase + math.pi), ("r", phase)):
        swing = -18.0 * math.cos(p)
        pose[side + "_shoulder"][1] = swing
        pose[side + "_elbow"][1] = -12.0 + min(0.0, swing) * 0.6
    # Pelvis turns towards the forward leg, the chest counter-rotates; the body bobs twice a cycle.
    pose["sacroiliac"][2] = 5.0 * math.cos(phase)
    pose["vl5"][2] = -7.0 * math.cos(phase)
    pose["sacroiliac"][0] = 3.0 * math.sin(phase)
    pose["vl5"][1] = 4.0  # a slight forward lean
    pose["skullbase"][1] = -3.0
    pose["root_pos"][1] = ROOT_HEIGHT - 0.04 - 0.02 * math.cos(2.0 * phase)  # lowest at heel strike
    pose["root_pos"][0] = 0.015 * math.sin(phase)
    return pose


# --- Common Ground motion library ---------------------------------------------------------------
# Gestures are keyframed in seconds and eased with smoothstep between keys (zero velocity at every
# key). A gesture of n frames has its last frame at END = (n - 1) * FRAME_TIME, so non-looping
# clips reach their final key exactly on the last frame.


def keys(t, points):
    """Eased keyframe track: points are (time [s], value); smoothstep between neighbouring keys."""
    if t <= points[0][0]:
        return points[0][1]
    for (t0, v0), (t1, v1) in zip(points, points[1:]):
        if t <= t1:
            return v0 + (v1 - v0) * smoothstep((t - t0) / (t1 - t0))
    return points[-1][1]


def end_time(frames):
    return (frames - 1) * FRAME_TIME


TURN_FRAMES = 25          # 1.00 s
WAVE_FRAMES = 40          # 1.60 s
CALL_OUT_FRAMES = 30      # 1.20 s
LOOK_AT_FRAMES = 30       # 1.20 s
NOD_FRAMES = 20           # 0.80 s
POINT_TOWARD_FRAMES = 35  # 1.40 s
POINT_DOWN_FRAMES = 30    # 1.20 s
TALK_FRAMES = 50          # 2.00 s


def turn(t):
    """Turn in place 90 degrees to the left: the head leads, the left foot steps first, then the right."""
    end = end_time(TURN_FRAMES)
    u = t / end
    pose = rest()
    breathe(pose, t, end)
    pose["HumanoidRoot"][2] += 90.0 * smoothstep(u)          # positive Y rotation: towards the left (+X)
    lead = math.sin(math.pi * smoothstep(u * 1.15))           # head and chest turn ahead of the pelvis
    pose["skullbase"][2] += 14.0 * lead
    pose["vl5"][2] += 5.0 * lead
    for side, start in (("l", 0.05), ("r", 0.45)):
        step = math.sin(math.pi * min(1.0, max(0.0, (u - start) / 0.5))) ** 2  # lift and set down
        pose[side + "_hip"][1] += -18.0 * step
        pose[side + "_knee"][1] += 34.0 * step
        pose[side + "_ankle"][1] += -8.0 * step
    pose["root_pos"][1] -= 0.012 * math.sin(math.pi * u)    # a slight dip while stepping
    pose["root_pos"][0] += 0.015 * math.sin(2.0 * math.pi * u)  # weight over the standing leg
    pose["l_shoulder"][1] += -6.0 * lead                      # arms swing a little with the turn
    pose["r_shoulder"][1] += 6.0 * lead
    return pose


def wave(t):
    """Right arm raised to the side with the forearm up; the hand waves side to side twice."""
    end = end_time(WAVE_FRAMES)
    pose = rest()
    breathe(pose, t, end)
    up = [(0.0, 0.0), (0.45, 1.0), (1.15, 1.0), (end, 0.0)]
    raised = keys(t, up)
    swing = keys(t, [(0.0, 0.0), (0.35, 0.0), (0.55, 1.0), (1.05, 1.0), (1.25, 0.0)])
    wag = 18.0 * swing * math.sin(2.0 * math.pi * 2.5 * (t - 0.35))  # 2.5 Hz
    pose["r_shoulder"][0] += -88.0 * raised   # abduct: the upper arm out to the right, about level
    pose["r_shoulder"][1] += -20.0 * raised   # and a little forward
    pose["r_elbow"][0] += -85.0 * raised + wag  # forearm up, wagging in the frontal plane
    pose["r_elbow"][1] += 8.0 * raised        # elbow straightened in the sagittal plane
    pose["r_wrist"][0] += 0.5 * wag            # the hand follows the forearm
    pose["vl5"][0] += 2.5 * raised             # the torso leans a little away from the raised arm
    pose["skullbase"][0] += -4.0 * raised      # the head tilts towards it, friendly
    pose["skullbase"][1] += -3.0 * raised      # chin slightly up
    return pose


def call_out(t):
    """Both hands cupped at the mouth; the head and chest push forward while calling."""
    end = end_time(CALL_OUT_FRAMES)
    pose = rest()
    breathe(pose, t, end)
    cup = keys(t, [(0.0, 0.0), (0.48, 1.0), (0.7, 1.0), (end, 0.0)])
    call = keys(t, [(0.0, 0.0), (0.4, 0.0), (0.55, 1.0), (0.7, 1.0), (0.9, 0.0)])
    for side, sign in (("l", 1.0), ("r", -1.0)):
        pose[side + "_shoulder"][1] += -60.0 * cup         # upper arms forward
        pose[side + "_shoulder"][0] += sign * 5.0 * cup    # elbows a little out
        pose[side + "_shoulder"][2] += sign * -30.0 * cup  # rotated in, so the hands meet
        pose[side + "_elbow"][1] += -130.0 * cup           # forearms folded up: fingertips at the mouth
        pose[side + "_wrist"][0] += sign * -10.0 * cup     # palms turned in, cupped
    pose["vl5"][1] += 6.0 * call                    # chest forward
    pose["skullbase"][1] += -8.0 * call - 2.0 * cup  # head up and out, calling
    pose["root_pos"][2] += 0.02 * call              # weight onto the front of the feet
    return pose


def look_at(t):
    """Head turns to the left (+X), the torso follows a little, and the pose is held to the end."""
    end = end_time(LOOK_AT_FRAMES)
    pose = rest()
    breathe(pose, t, end)
    head = keys(t, [(0.0, 0.0), (0.42, 1.06), (0.62, 1.0)])  # a small overshoot, then settle
    torso = keys(t, [(0.0, 0.0), (0.08, 0.0), (0.6, 1.0)])   # the torso follows the head
    pose["skullbase"][2] += 38.0 * head
    pose["skullbase"][0] += 2.5 * head
    pose["vl5"][2] += 10.0 * torso
    pose["sacroiliac"][2] += 3.0 * torso
    pose["r_shoulder"][1] += -3.0 * torso
    pose["root_pos"][0] += 0.01 * torso
    return pose


def nod(t):
    """One nod: the head drops forward, comes back slightly past neutral, settles."""
    pose = rest()
    angle = keys(t, [(0.0, 0.0), (0.22, 16.0), (0.48, -3.0), (0.66, 2.0), (end_time(NOD_FRAMES), 0.0)])
    pose["skullbase"][1] += angle  # positive X: chin down
    pose["vl5"][1] += 0.15 * angle
    return pose


def point_toward(t):
    """Right arm extended forward at shoulder height, index direction +Z; held, then lowered."""
    end = end_time(POINT_TOWARD_FRAMES)
    pose = rest()
    breathe(pose, t, end)
    arm = keys(t, [(0.0, 0.0), (0.45, 1.0), (1.0, 1.0), (end, 0.0)])
    pose["r_shoulder"][1] += -86.0 * arm    # swing forward to level
    pose["r_shoulder"][0] += -2.0 * arm     # slightly out (with the rest -4)
    pose["r_elbow"][1] += 6.0 * arm          # straighten the elbow
    pose["r_wrist"][1] += -4.0 * arm
    pose["vl5"][2] += -7.0 * arm             # the right shoulder leads (turn right)
    pose["skullbase"][2] += 7.0 * arm        # the head keeps facing the target
    pose["skullbase"][1] += -2.0 * arm
    pose["root_pos"][2] += 0.012 * arm       # a slight lean into the gesture
    return pose


def point_down(t):
    """Right arm points down to the ground in front; the torso and head lean to look at the spot."""
    end = end_time(POINT_DOWN_FRAMES)
    pose = rest()
    breathe(pose, t, end)
    arm = keys(t, [(0.0, 0.0), (0.4, 1.0), (0.85, 1.0), (end, 0.0)])
    pose["r_shoulder"][1] += -42.0 * arm    # forward and down
    pose["r_shoulder"][0] += 2.0 * arm      # towards the body's midline
    pose["r_elbow"][1] += 5.0 * arm
    pose["r_wrist"][1] += -6.0 * arm
    pose["vl5"][1] += 9.0 * arm              # lean forward
    pose["skullbase"][1] += 20.0 * arm       # look down at the spot
    pose["sacroiliac"][1] += 2.0 * arm
    return pose


def talk(t):
    """Talking: forearms raised in front, small beats of the hands, head nods and turns (loops)."""
    duration = TALK_FRAMES * FRAME_TIME  # frame n equals frame 0

    def wave_(k, phase):
        return math.sin(2.0 * math.pi * k * t / duration + phase)

    pose = rest()
    breathe(pose, t, duration)
    for side, sign, phase in (("l", 1.0, 0.0), ("r", -1.0, 1.7)):
        pose[side + "_shoulder"][1] += -14.0 + 4.0 * wave_(2, phase)   # upper arms a little forward
        pose[side + "_shoulder"][0] += sign * 4.0 * wave_(1, phase + 0.5)
        pose[side + "_elbow"][1] += -42.0 + 9.0 * wave_(3, phase) + 4.0 * wave_(5, phase)  # beats
        pose[side + "_wrist"][0] += sign * 8.0 * wave_(2, phase + 1.0)  # hands open and turn
    pose["skullbase"][1] += 3.0 * wave_(3, 0.4) + 1.5 * wave_(5, 1.1)   # small nods with the speech
    pose["skullbase"][2] += 6.0 * wave_(1, 0.9)                         # glance around the listeners
    pose["skullbase"][0] += 2.0 * wave_(2, 0.2)
    pose["vl5"][2] += 2.0 * wave_(1, 0.3)
    return pose


def row(pose):
    values = list(pose["root_pos"]) + list(pose["HumanoidRoot"])
    for name in channel_order()[1:]:
        values += pose[name]
    return " ".join("0" if abs(v) < 5e-5 else f"{v:.4f}".rstrip("0").rstrip(".") for v in values)


def write(path, frames, pose_at):
    lines = hierarchy()
    lines += ["MOTION", f"Frames: {frames}", f"Frame Time: {FRAME_TIME:g}"]
    lines += [row(pose_at(i * FRAME_TIME)) for i in range(frames)]
    with open(path, "w", newline="\n") as f:
        f.write("\n".join(lines) + "\n")


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenarios", "motions")
    os.makedirs(out, exist_ok=True)
    write(os.path.join(out, "look.bvh"), 100, look)  # 4.00 s
    write(os.path.join(out, "idle.bvh"), 50, idle)   # 2.00 s
    write(os.path.join(out, "walk.bvh"), 28, walk)   # 1.12 s
    write(os.path.join(out, "turn.bvh"), TURN_FRAMES, turn)
    write(os.path.join(out, "wave.bvh"), WAVE_FRAMES, wave)
    write(os.path.join(out, "call_out.bvh"), CALL_OUT_FRAMES, call_out)
    write(os.path.join(out, "look_at.bvh"), LOOK_AT_FRAMES, look_at)
    write(os.path.join(out, "nod.bvh"), NOD_FRAMES, nod)
    write(os.path.join(out, "point_toward.bvh"), POINT_TOWARD_FRAMES, point_toward)
    write(os.path.join(out, "point_down.bvh"), POINT_DOWN_FRAMES, point_down)
    write(os.path.join(out, "talk.bvh"), TALK_FRAMES, talk)


if __name__ == "__main__":
    main()
