"""Pareto front, the markdown fragment and the time-against-error figure."""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FAMILY_STYLE = {  # marker, colour
    "default": ("*", "black"),
    "dt": ("o", "tab:blue"),
    "tolerance": ("s", "tab:orange"),
    "cutoff": ("^", "tab:green"),
    "combined": ("D", "tab:purple"),
    "adaptive": ("v", "tab:brown"),
    "reference": ("X", "tab:red"),
    "numerical reference": ("P", "tab:red"),
}


def pareto_front(rows, cost, error):
    """Indices of rows not dominated by another row (no other is at most as costly and at most as
    wrong, and strictly better in one). NaN errors are never on the front."""
    front = []
    for i, r in enumerate(rows):
        c, e = cost(r), error(r)
        if math.isnan(e):
            continue
        dominated = any(
            (cost(s) <= c and error(s) <= e) and (cost(s) < c or error(s) < e)
            for j, s in enumerate(rows) if j != i and not math.isnan(error(s)))
        if not dominated:
            front.append(i)
    return front


def _fmt(x, digits=3):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "—"
    return f"{x:.{digits}g}"


def deterministic_table(rows):
    head = ("| family | dt | tolerance | cutoff | wall s | cpu s | steps/s | CG it/step "
            "| position err (a) | orientation err (rad) | Pareto "
            "| numerical position err (a) | numerical orientation err (rad) | numerical Pareto |\n"
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n")
    lines = []
    for r in rows:
        s, t = r["setting"], r["timing"]
        name = f"**{s.family}**" if s.is_default else s.family
        lines.append(
            f"| {name} | {s.dt_text} | {s.tolerance:g} | {s.cutoff:g} | {t.wall:.2f} | {t.cpu:.2f} "
            f"| {t.steps / r['cost']:.0f} | {_fmt(t.cg_per_step)} | {_fmt(r['position'])} "
            f"| {_fmt(r['orientation'])} | {'yes' if r.get('pareto') else ''} "
            f"| {_fmt(r.get('numerical_position'))} | {_fmt(r.get('numerical_orientation'))} "
            f"| {'yes' if r.get('numerical_pareto') else ''} |")
    return head + "\n".join(lines) + "\n"


def brownian_table(rows):
    head = ("| family | dt | tolerance | cutoff | wall s | cpu s | CG it/step | eta_r | "
            "delta_theta_m (rad) | g near contact | consistent (2 SE) | same cutoff: largest Δ, consistent |\n"
            "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n")
    lines = []
    for r in rows:
        s, t = r["setting"], r["timing"]
        name = f"**{s.family}**" if s.is_default else s.family
        cells = []
        for q in ("eta_r", "delta_theta_m", "g_contact"):
            value, se = r["observed"][q]
            cell = f"{value:.3f} ± {se:.3f}"
            if "compared" in r:
                err, comb, _ = r["compared"][q]
                cell += f" (Δ {err:.3f} = {err / comb:.1f} SE)" if comb > 0 else f" (Δ {err:.3f})"
            cells.append(cell)
        consistent = "reference" if "compared" not in r else (
            "yes" if all(c for _, _, c in r["compared"].values()) else
            "no: " + ", ".join(q for q, (_, _, c) in r["compared"].items() if not c))
        same = "—"
        if "numerical_compared" in r:
            worst = max(err / comb if comb > 0 else math.inf for err, comb, _ in r["numerical_compared"].values())
            ok = all(c for _, _, c in r["numerical_compared"].values())
            same = f"{worst:.1f} SE, {'yes' if ok else 'no'}"
        elif s.family == "numerical reference":
            same = "reference"
        lines.append(f"| {name} | {s.dt_text} | {s.tolerance:g} | {s.cutoff:g} | {t.wall:.1f} "
                     f"| {t.cpu:.1f} | {_fmt(t.cg_per_step)} | " + " | ".join(cells) + f" | {consistent} | {same} |")
    return head + "\n".join(lines) + "\n"


def _draw_front(ax, points):
    """Staircase through the Pareto points (sorted by cost)."""
    points = sorted(points)
    xs, ys = [], []
    for k, (x, y) in enumerate(points):
        if k:
            xs.append(x)
            ys.append(points[k - 1][1])
        xs.append(x)
        ys.append(y)
    ax.plot(xs, ys, "-", color="grey", lw=1.2, zorder=1, label="Pareto front")


def _scatter(ax, rows, error, clock):
    """Cost against error, one marker per family, labels dt/tolerance/cutoff, default ringed."""
    seen = set()
    for r in rows:
        s, y = r["setting"], error(r)
        marker, colour = FAMILY_STYLE[s.family]
        ax.scatter(r["cost"], y, marker=marker, color=colour, s=70 if s.is_default else 36, zorder=3,
                   label=None if s.family in seen else s.family)
        seen.add(s.family)
        ax.annotate(f"{s.dt_text}/{s.tolerance:g}/{s.cutoff:g}", (r["cost"], y), fontsize=6,
                    xytext=(3, 3), textcoords="offset points")
        if s.is_default:
            ax.scatter(r["cost"], y, s=320, facecolors="none", edgecolors="red", lw=2, zorder=4,
                       label="current default")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(f"{clock} time per run (s)")
    ax.grid(True, which="both", alpha=0.3)


def plot(det_rows, brown_rows, clock, path, title, plan):
    strain = plan.strain
    fig, axes = plt.subplots(1, 3, figsize=(17, 5.5))
    floor = 1e-12  # identical trajectories (error 0) are drawn at this floor of the log axis

    rows = [r for r in det_rows if r["setting"].family not in ("reference", "numerical reference")]
    ax = axes[0]
    _scatter(ax, rows, lambda r: max(r["position"], floor), clock)
    _draw_front(ax, [(r["cost"], max(r["position"], floor)) for r in rows if r.get("pareto")])
    ax.set_ylabel(f"RMS position error after strain {strain:g} (a)")
    ax.set_title(f"deterministic, against the tight reference\n{plan.reference.label}", fontsize=10)
    ax.legend(fontsize=7)

    ax = axes[1]
    rows = [r for r in rows if "numerical_position" in r]
    _scatter(ax, rows, lambda r: max(r["numerical_position"], floor), clock)
    _draw_front(ax, [(r["cost"], max(r["numerical_position"], floor)) for r in rows if r.get("numerical_pareto")])
    ax.set_ylabel(f"RMS position error after strain {strain:g} (a)")
    ax.set_title("deterministic, same cutoff: numerical error of dt and tolerance\n"
                 f"against {plan.numerical_reference.label}", fontsize=10)
    ax.legend(fontsize=7)

    ax = axes[2]
    rows = [r for r in brown_rows if "compared" in r]
    worst = {id(r): max(max(err / comb if comb > 0 else math.inf for err, comb, _ in r["compared"].values()),
                        1e-2) for r in rows}
    _scatter(ax, rows, lambda r: worst[id(r)], clock)
    ax.axhline(2.0, color="red", ls="--", lw=1, label="2 SE (consistent below)")
    ax.set_ylabel("largest |value - reference| / combined SE")
    ax.set_title("Brownian, Pe = 10: eta_r, delta_theta_m, g near contact\n"
                 f"against {plan.brownian_reference.label}", fontsize=10)
    ax.legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
