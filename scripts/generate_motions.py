#!/usr/bin/env python3
"""Generates the bundled motion clips scenarios/motions/{look,idle,walk}.bvh procedurally.

Authored for throng (no captured data): an H-Anim-like skeleton in metres, Y up, facing +Z (the
figure's left is +X), rest pose standing with arms hanging. Rotations are in degrees, channel
order Zrotation Xrotation Yrotation; a positive X rotation swings a hanging limb backwards.

    look.bvh  4.00 s  stand, turn torso and head to the left, look slightly up, turn back
    idle.bvh  2.00 s  stand and breathe, small weight shift (loops)
    walk.bvh  1.12 s  one walk cycle (two steps) in place; the viewer moves the root (loops)

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


if __name__ == "__main__":
    main()
