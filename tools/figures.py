"""The figures of the docs pages that are drawn from a study's JSON (tools/render_docs.py --figures):
FIGURES maps a page to its figures, each a function of the page's JSON and the path to write."""

from __future__ import annotations

import math


def plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as pyplot

    return pyplot


def parts(config):
    """'Argyris 14×5, Δt=1e-5, m=10' -> ('Argyris 14×5', 1e-5, 10)."""
    items = config.split(", ")
    get = lambda key: next((i.split("=")[1] for i in items if i.startswith(key)), None)  # noqa: E731
    return items[0], float(get("Δt=")), int(get("m=") or 0)


def colors(meshes):
    cmap = plt().get_cmap("tab10")
    return {m: cmap(k % 10) for k, m in enumerate(sorted(set(meshes)))}


MARKERS = {1e-3: "s", 1e-4: "D", 1e-5: "o", 5e-6: "v", 2e-6: "<", 1e-6: "*", 5e-7: "P"}


def speed_vs_error(d, path):
    """Error against wall time per simulated second: the sine scene's trajectory and first impact
    (only if they converge), `modes` against the exact scheme on §5.2, the §5.2 energy against Δt."""
    fig, axes = plt().subplots(2, 2, figsize=(13, 10))
    color = colors(parts(r["config"])[0] for r in d["errors"] + d["free"])
    for ax, key, q, title in (
        (axes[0, 0], "err_trajectory", "trajectory", "sine scene: corner_1 before the first impact (relative)"),
        (axes[0, 1], "err_impact", "impact", "sine scene: |t₁ − t₁,ref| [s]"),
    ):
        lines = {}
        for r in d["errors"]:
            if r[key]:
                mesh, dt, m = parts(r["config"])
                c = color[mesh]
                ax.scatter(
                    r["wall_per_sim_s"], r[key], color="white" if m else c, edgecolor=c, marker=MARKERS.get(dt, "o")
                )
                if not m and "engine=" not in r["config"]:
                    lines.setdefault(mesh, []).append((r["wall_per_sim_s"], r[key]))
        for mesh, xy in lines.items():
            ax.plot(*zip(*sorted(xy)), color=color[mesh], lw=0.8, label=mesh)
        unc = d["quantities"][q].get("ref_uncertainty")
        if unc and math.isfinite(unc):
            ax.axhline(unc, color="0.5", ls=":", lw=1, label="reference uncertainty")
        if not d["quantities"][q]["converges"]:
            ax.text(0.5, 0.5, "does not converge: not used as an error", ha="center", transform=ax.transAxes)
        ax.set(xscale="log", yscale="log", title=title, xlabel="wall time per simulated second [s]")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7)
    ax = axes[1, 0]
    wall = {r["config"]: r["wall_per_sim_s"] for r in d["free"]}
    groups = {}
    for m in d["modes"]:
        mesh, dt, modes = parts(m["config"])
        groups.setdefault((mesh, dt), []).append((wall[m["config"]], max(abs(m["rel_err"]), 1e-6), modes))
    for (mesh, dt), pts in groups.items():
        pts.sort()
        ax.plot(
            [p[0] for p in pts],
            [p[1] for p in pts],
            marker=MARKERS.get(dt, "o"),
            color=color[mesh],
            label=f"{mesh}, Δt={dt:g}",
        )
        for x, y, modes in pts:
            ax.annotate(str(modes), (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.axhline(0.01, color="r", ls="--", lw=0.8, label="1 % goal")
    ax.set(xscale="log", yscale="log", xlabel="wall time per simulated second [s]", ylabel="relative error")
    ax.set_title("§5.2: energy lost by 0.5 s, modes m against the exact scheme (same mesh, Δt)", fontsize=10)
    ax.legend(fontsize=7)
    ax = axes[1, 1]
    for s in d["quantities"]["energy_lost_0p5s"]["sequences"]:
        if s["name"].startswith("Δt"):
            dts = [parts(label)[1] for label in s["labels"]]
            ax.plot(dts, s["values"], marker="o", color=color[parts(s["labels"][0])[0]], label=s["name"])
    ax.set(xscale="log", xlabel="Δt [s]", ylabel="energy lost by 0.5 s [J]")
    ax.set_title("§5.2: energy lost by 0.5 s against Δt (exact scheme)", fontsize=10)
    ax.invert_xaxis()
    ax.legend(fontsize=7)
    fig.suptitle("PlateImpact: error against wall time per simulated second (hollow: modes m)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def scaling(d, path):
    """Per-step time (engine auto and sparse) and the floor against the number of dofs."""
    fig, ax = plt().subplots(figsize=(7.5, 5))
    for element, color in (("argyris", "#3182bd"), ("fvs", "#d94801")):
        rs = sorted((r for r in d["scaling"] if r["element"] == element), key=lambda r: r["dofs"])
        n = [r["dofs"] for r in rs]
        ax.plot(n, [r["auto"]["step_s"] for r in rs], "o-", color=color, label=f"{element}: step, engine=auto")
        ax.plot(n, [r["sparse"]["step_s"] for r in rs], "s--", color=color, label=f"{element}: step, engine=sparse")
        ax.plot(n, [r["auto"]["floor_solve_s"] for r in rs], "x:", color=color, label=f"{element}: floor (one solve)")
    ax.set(xscale="log", yscale="log", xlabel="free dofs", ylabel="seconds per step")
    ax.set_title("Per-step time and floor against the number of dofs (sine scene, Δt=1e-5)", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def impact_pareto(d, path):
    """§5.2 after impact: corner_1 error and energy lost against CPU time, per law."""
    fig, axes = plt().subplots(1, 2, figsize=(11, 4.2))
    for law in dict.fromkeys(e["law"] for e in d["errors"]):
        rows = [e for e in d["errors"] if e["law"] == law]
        cpu = [e["cpu_per_second"] for e in rows]
        axes[0].loglog(cpu, [max(e["corner_error"], 1e-9) for e in rows], "o-", label=law)
        axes[1].loglog(cpu, [max(abs(e["energy_loss"]), 1e-13) for e in rows], "o-", label=law)
    axes[0].set_ylabel("corner_1 error over 0.3 s (m)")
    axes[1].set_ylabel("|energy lost| after 0.5 s / E0")
    for ax in axes:
        ax.set_xlabel("CPU s per simulated s")
    axes[0].legend(fontsize=8)
    fig.suptitle("§5.2 after impact: error against cost, each law against its own finest-dt reference")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


FIGURES = {
    "performance.md": {
        "speed_vs_error.png": (speed_vs_error, "speed"),
        "scaling.png": (scaling, "speed"),
        "impact_pareto.png": (impact_pareto, "laws"),
    },
}
