"""PNG plots of scripts/verify.py --report (matplotlib, Agg backend). Each takes datas = {model
tag: the test's measured data} so that the models appear side by side, and the PNG path."""
import numpy as np

from validation import measures as M
from validation.plots import _plt, _save  # noqa: F401  (one Agg set-up for both scripts)

COLOURS = ["tab:blue", "tab:red", "tab:green", "tab:purple"]


def ring(datas, path, title):
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 4), dpi=80)
    rho = np.linspace(0.2, 5.4, 200)
    ax.plot(rho, M.weidmann(rho), "k-", lw=1.5, label="Weidmann (1993)")
    ax.fill_between(rho, M.weidmann(rho) - 0.15, M.weidmann(rho) + 0.15, color="k", alpha=0.1, label="± 0.15 m/s")
    for (tag, d), c in zip(datas.items(), COLOURS):
        ax.plot([r["density"] for r in d["rows"]], [r["speed"] for r in d["rows"]], "o-", color=c, label=tag)
    ax.set(xlabel="density [1/m²]", ylabel="mean speed [m/s]", xlim=(0, 5.6), ylim=(-0.05, 1.6), title=title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    _save(fig, path)


def corner(datas, path, title):
    plt = _plt()
    fig, axes = plt.subplots(1, len(datas), figsize=(3.6 * len(datas) + 0.5, 3.8), dpi=80, squeeze=False)
    for ax, (tag, d), c in zip(axes[0], datas.items(), COLOURS):
        w = np.array(d["walls"] + [d["walls"][0]])
        ax.plot(w[:, 0], w[:, 1], "k-", lw=2)
        ax.plot(d["x"], d["y"], ".", ms=1, color=c)
        ax.set(aspect="equal", title=f"{tag}", xlabel="x [m]", ylabel="y [m]")
    fig.suptitle(title, fontsize=10)
    _save(fig, path)


def demographics(datas, path, title):
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 3.8), dpi=80)
    first = next(iter(datas.values()))
    names = list(first["groups"])
    for k, g in enumerate(names):
        lo, hi = first["groups"][g]["range"]
        ax.add_patch(plt.Rectangle((k - 0.4, lo), 0.8, hi - lo, color="k", alpha=0.1))
    for j, ((tag, d), c) in enumerate(zip(datas.items(), COLOURS)):
        for k, g in enumerate(names):
            v = d["groups"][g]["speeds"]
            ax.plot(np.full(len(v), k - 0.25 + 0.5 * (j + 0.5) / len(datas)), v, "o", mfc="none", color=c,
                    label=tag if k == 0 else None)
    ax.set_xticks(range(len(names)), names)
    ax.set(ylabel="measured speed [m/s]", title=title + " (grey: group's range)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    _save(fig, path)


def sensitivity(datas, path, title):
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 3.8), dpi=80)
    for (tag, d), c in zip(datas.items(), COLOURS):
        ax.plot([r["speed"] for r in d["rows"]], [r["evacuation_s"] for r in d["rows"]], "o-", color=c, label=tag)
    ax.set(xlabel="mean desired speed [m/s]", ylabel="evacuation time [s]", title=title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    _save(fig, path)


def hall(datas, path, title):
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 3.8), dpi=80)
    for (tag, d), c in zip(datas.items(), COLOURS):
        for key, style in (("open", "-"), ("closed", "--")):
            t = d["exit_times"][key]
            ax.step(np.r_[0, t], np.arange(len(t) + 1), style, where="post", color=c,
                    label=f"{tag}, {'4 doors' if key == 'open' else '2 doors'}")
    ax.set(xlabel="time [s]", ylabel="persons out", title=title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    _save(fig, path)


def bottlenecks(datas, path, title):
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 3.8), dpi=80)
    for (tag, d), c in zip(datas.items(), COLOURS):
        ax.plot(d["t"], d["first"], "-", color=c, label=f"{tag}, before the first")
        ax.plot(d["t"], d["second"], ":", color=c, label=f"{tag}, before the second")
    ax.axhline(2.0, color="k", lw=0.8)
    ax.set(xlabel="time [s]", ylabel="density in 2 × 2 m [1/m²]", title=title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    _save(fig, path)


def counter(datas, path, title):
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.4, 3.8), dpi=80)
    for (tag, d), c in zip(datas.items(), COLOURS):
        ax.plot([r["against"] for r in d["rows"]], [r["last_forward_s"] for r in d["rows"]], "o-", color=c, label=tag)
    ax.set(xlabel="persons walking against", ylabel="last of the 50 arrives [s]", title=title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    _save(fig, path)


def corridor_fd(datas, path, title):
    """ISO 13: speed and flow against the measured density, per model, with Weidmann's speed and the
    SFPE flow limit."""
    from . import geometry as G
    plt = _plt()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(8.4, 3.6), dpi=80)
    rho = np.linspace(0.1, 1.4, 100)
    a1.plot(rho, M.weidmann(rho), "k-", lw=1.2, label="Weidmann (1993)")
    c = G.CORRIDOR_FD
    a2.axhline(c["sfpe_max"] * (c["width"] - 2 * c["boundary"]), color="k", lw=0.8, label="SFPE maximum")
    for (tag, d), col in zip(datas.items(), COLOURS):
        dens = [r["density"] for r in d["rows"]]
        a1.plot(dens, [r["speed"] for r in d["rows"]], "o-", color=col, label=tag)
        a2.plot(dens, [r["flow"] for r in d["rows"]], "o-", color=col, label=tag)
    a1.set(xlabel="density in x 30 … 40 m [1/m²]", ylabel="speed [m/s]", ylim=(0, 1.6))
    a2.set(xlabel="density in x 30 … 40 m [1/m²]", ylabel="flow across x = 40 m [1/s]")
    for ax in (a1, a2):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title, fontsize=10)
    _save(fig, path)
