#!/usr/bin/python3
"""Draws docs/img/social-relations.png: the sensory model of a group mate B (touch, hearing, vision;
Park, Peng, Quek, Cao "Common Ground", §3.2, Figure 2) and example positions of an initiator A for
the six relations A1..A6 of libs/common_ground/include/throng/common_ground/relation.hpp.

Parameters are the SensoryParams defaults in libs/common_ground/include/throng/common_ground/sensing.hpp; keep them
in sync. The example positions and the approach points x_i / x_j follow tests/common_ground/relations_test.cpp
and the formulas in relations.hpp. Usage: /usr/bin/python3 scripts/plot_relations.py [out.png]
"""
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle, Wedge  # noqa: E402

TOUCH_MARGIN = 0.1   # m
HEARING = 7.0        # d_h, m
VISION = 25.0        # d_v, m
FOV = 2.0944         # alpha, rad (120 deg)
RADIUS = 0.2         # body radius, m
STAND_OFF = 2.0      # pointInView default, m
MARGIN = 0.01        # kApproachMargin


def main(out):
    fig, ax = plt.subplots(figsize=(8, 9.5))
    half_deg = math.degrees(FOV / 2)
    # B at the origin facing +y (90 deg in matplotlib's angle convention).
    ax.add_patch(Wedge((0, 0), VISION, 90 - half_deg, 90 + half_deg, color="tab:blue", alpha=0.12,
                       label=f"vision: d_v = {VISION:g} m, α = {math.degrees(FOV):.0f}°"))
    ax.add_patch(Circle((0, 0), HEARING, color="tab:orange", alpha=0.18,
                        label=f"hearing: d_h = {HEARING:g} m (walls ignored)"))
    touch = 2 * RADIUS + TOUCH_MARGIN
    ax.add_patch(Circle((0, 0), touch, color="tab:red", alpha=0.45,
                        label=f"touch: r_A + r_B + {TOUCH_MARGIN:g} m = {touch:g} m"))
    ax.add_patch(Circle((0, 0), RADIUS, color="black"))
    ax.annotate("", xy=(0, 2.2), xytext=(0, 0), arrowprops=dict(arrowstyle="->", lw=2))
    ax.text(0.35, -1.0, "B", fontsize=14, weight="bold")

    # A wall in front of B: turns a face-to-face A2 into A4 (heard, not seen).
    wall = ((2.0, 3.0), (7.0, 3.0))
    ax.plot(*zip(*wall), color="dimgray", lw=5, solid_capstyle="butt", label="wall (blocks vision only)")
    ax.plot([0, 4.5], [0, 4.5], color="dimgray", lw=0.8, ls=":")

    # (name, position, facing, note, label offset); what B perceives of A is in the note.
    examples = [
        ("A1", (0.45, 0.0), (-1, 0), "touch", (0.5, 0.6)),
        ("A2", (-2.0, 4.5), (0.4, -1), "sees + hears", (0.6, 0.0)),
        ("A3", (0.0, -10.0), (0, 1), "B perceives nothing,\nA sees B", (0.6, 0.0)),
        ("A4", (-3.5, -4.0), (0.6, 0.8), "hears only", (0.6, 0.0)),
        ("A4", (4.5, 4.5), (-0.7, -0.7), "hears only\n(behind wall)", (0.6, 0.3)),
        ("A5", (4.0, 15.0), (-0.3, -1), "sees only", (0.6, 0.0)),
        ("A6", (10.5, -11.0), (1, -0.3), "neither perceives\nthe other", (-2.2, 1.8)),
    ]
    for name, (x, y), (fx, fy), note, (dx, dy) in examples:
        n = math.hypot(fx, fy)
        ax.add_patch(Circle((x, y), RADIUS * 1.6, color="tab:green", zorder=5))
        ax.annotate("", xy=(x + 1.3 * fx / n, y + 1.3 * fy / n), xytext=(x, y),
                    arrowprops=dict(arrowstyle="->", color="tab:green", lw=1.5), zorder=5)
        ax.text(x + dx, y + dy, f"{name}: {note}", fontsize=9, va="center", zorder=6)

    # Approach points for A3 (relations.hpp): x_i at the stand-off on a cone edge, x_j on the
    # hearing circle straight toward A.
    h = FOV / 2 - MARGIN
    xi = (-STAND_OFF * math.sin(h), STAND_OFF * math.cos(h))
    xj = (0.0, -(HEARING - MARGIN))
    a3 = (0.0, -10.0)
    for p, label, off in ((xi, "x_i (move into view, wave)", (-7.3, 0.7)),
                          (xj, "x_j (move into hearing,\ncall out)", (0.5, -0.2))):
        ax.plot(*p, marker="x", color="tab:purple", ms=10, mew=2.5, zorder=6)
        ax.annotate("", xy=p, xytext=a3, arrowprops=dict(arrowstyle="->", color="tab:purple", ls="--"))
        ax.text(p[0] + off[0], p[1] + off[1], label, color="tab:purple", fontsize=9)

    ax.set_xlim(-14, 14)
    ax.set_ylim(-13, 26)
    ax.set_aspect("equal")
    ax.grid(alpha=0.3)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("Relations of initiator A to group mate B (B at origin, facing +y)")
    ax.legend(loc="upper left", fontsize=8, framealpha=0.9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "docs/img/social-relations.png")
