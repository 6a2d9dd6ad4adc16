"""PNG plots of scripts/validate.py (matplotlib, Agg backend): corridor speed-density, the 0.5 m
bottleneck's cumulative passings, the ring fundamental diagram with Weidmann's curve, single file
against Seyfried et al. 2005, bottleneck flow against width."""
import numpy as np

from . import measures as M


def _plt():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _save(fig, path):
    fig.tight_layout()
    fig.savefig(path)
    _plt().close(fig)


def corridor(results, path, tag):
    """Speed-density and specific flow-density of the corridor and the jam, experiment and throng."""
    plt = _plt()
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(10, 4.2), dpi=90)
    rho = np.linspace(0.05, 5.4, 200)
    ax.plot(rho, M.weidmann(rho), "k-", lw=1.5, label="Weidmann (1993)")
    ax2.plot(rho, M.weidmann(rho) * rho, "k-", lw=1.5, label="Weidmann (1993)")
    for name, colour in (("corridor", "tab:blue"), ("jam", "tab:red")):
        res = results.get(name)
        if not res:
            continue
        for source, classes, marker, fill in (("experiment", res["experiment"]["classes"], "o", colour),
                                              (f"throng ({tag})", res["classes"], "s", "white")):
            cr = np.array([c["density"] for c in classes])
            cv = np.array([c["speed"] for c in classes])
            ce = [c["speed_sd"] for c in classes]
            ax.errorbar(cr, cv, yerr=ce, fmt=marker, mfc=fill, color=colour, ms=6, capsize=2,
                        label=f"{source}, {name}")
            ax2.plot(cr, cr * cv, marker, mfc=fill, color=colour, ms=6, label=f"{source}, {name}")
    ax.set(xlabel="density ρ [1/m²] (area 1.8 m × 2 m)", ylabel="mean speed v [m/s]", xlim=(0, 8), ylim=(0, 1.8),
           title="Speed–density, 1.8 m corridor (steady state)")
    ax2.set(xlabel="density ρ [1/m²]", ylabel="specific flow ρ·v [1/(m·s)]", xlim=(0, 8), ylim=(0, 3),
            title="Specific flow–density")
    for a in (ax, ax2):
        a.grid(alpha=0.3)
        a.legend(fontsize=7, loc="upper right")
    _save(fig, path)


def bottleneck_cumulative(res, path, tag):
    """Cumulative passings at the 0.5 m bottleneck: the experiment and throng's seeds."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.5, 4.2), dpi=90)
    exp = res.get("experiment_050")
    if exp:
        t = np.array(exp["times"])
        ax.step(np.r_[0, t], np.arange(len(t) + 1), where="post", color="k", lw=2,
                label=f"experiment 040_c_56_h- ({exp['flow']:.2f} /s)")
    row = res["widths"].get("0.5")
    if row and row["accepted"]:
        for i, r in enumerate(x for x in row["runs"] if "error" not in x):
            tt = np.array(r["times"])
            ax.step(np.r_[0, tt], np.arange(len(tt) + 1), where="post", color="tab:blue", lw=1, alpha=0.8,
                    label=f"throng ({tag}), {len(row['runs'])} seeds, {row['flow']:.2f} /s mean" if i == 0 else None)
    elif row:
        ax.text(0.5, 0.5, f"throng ({tag}): refused by throng check", transform=ax.transAxes, ha="center")
    ax.set(xlabel="time t [s]", ylabel="persons passed the line y = 0", ylim=(0, 78),
           title="0.5 m bottleneck, 75 persons, default body: cumulative passings")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    _save(fig, path)


def ring(res, path, tag):
    """Ring fundamental diagram: throng's mean tangential speed per density, Weidmann, the band."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.5, 4.5), dpi=90)
    rho = np.linspace(0.2, 5.4, 200)
    ax.plot(rho, M.weidmann(rho), "k-", lw=1.5, label="Weidmann (1993)")
    ax.fill_between(rho, M.weidmann(rho) - 0.15, M.weidmann(rho) + 0.15, color="k", alpha=0.1, label="band ± 0.15 m/s")
    _ring_points(ax, res, tag)
    ax.set(xlabel="density ρ = N / A [1/m²]", ylabel="mean tangential speed [m/s]",
           xlim=(0, 5.6), ylim=(-0.1, 1.6), title="Fundamental diagram, 2 m wide ring (r 3–5 m)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    _save(fig, path)


def _ring_points(ax, res, tag):
    for row in res["densities"].values():
        runs = [r for r in row["runs"] if "error" not in r]
        ax.plot([r["density"] for r in runs], [r["speed"] for r in runs], "s", mfc="none", color="tab:blue",
                ms=4, alpha=0.6)
    rows = [r for r in res["densities"].values() if r.get("density") is not None]
    ax.plot([r["density"] for r in rows], [r["speed"] for r in rows], "o-", color="tab:blue", ms=7,
            label=f"throng ({tag}): seeds (squares), mean (circles)")


def single_file(res, path, tag):
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.5, 4.5), dpi=90)
    lam = np.linspace(0.5, 2.6, 200)
    ax.plot(lam, M.seyfried_1d(lam), "k-", lw=1.5, label="Seyfried et al. 2005: 1/ρ = 0.36 m + 1.06 s·v")
    ax.fill_between(lam, M.seyfried_1d(lam) - 0.15, M.seyfried_1d(lam) + 0.15, color="k", alpha=0.1,
                    label="band ± 0.15 m/s")
    _ring_points(ax, res, tag)
    ax.set(xlabel="line density ρ = N / L [1/m]", ylabel="mean tangential speed [m/s]",
           xlim=(0.5, 2.6), ylim=(-0.1, 1.6), title="Single file, 0.8 m wide ring (26 m around)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    _save(fig, path)


def bottleneck_widths(res, trend, path, tag):
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.5, 4.5), dpi=90)
    w = np.linspace(0.45, 1.25, 100)
    e = np.array([trend(x) for x in w])
    ax.plot(w[w > 0.55], e[w > 0.55], "k-", lw=1.5, label="1.9 /(m·s) · w (Seyfried 2009, Kretz 2006, Liddle 2011)")
    ax.fill_between(w[w > 0.55], 0.75 * e[w > 0.55], 1.25 * e[w > 0.55], color="k", alpha=0.1, label="band ± 25 %")
    ax.errorbar([0.5], [1.15], yerr=[[0.29], [0.29]], fmt="D", color="k", capsize=3, label="Wuppertal 040_c_56_h- ± 25 %")
    refused = True
    for row in res["widths"].values():
        runs = [r for r in row["runs"] if "error" not in r]
        ax.plot([row["width"]] * len(runs), [r["flow"] for r in runs], "s", mfc="none", color="tab:blue", ms=4)
        if not row["accepted"]:
            ax.plot([row["width"]], [0.0], "x", color="tab:red", ms=9, label="refused by throng check" if refused else None)
            refused = False
    rows = [r for r in res["widths"].values() if r.get("flow") is not None]
    ax.plot([r["width"] for r in rows], [r["flow"] for r in rows], "o-", color="tab:blue", ms=7,
            label=f"throng ({tag}), mean of seeds")
    ax.set(xlabel="bottleneck width w [m] (1.1 m long)", ylabel="flow (N−1)/(t_N−t_1) [1/s]", xlim=(0.4, 1.3),
           ylim=(-0.1, 3.0), title="75 persons through a bottleneck, default body")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left")
    _save(fig, path)
