#!/usr/bin/env python3
"""Turns drape_bench's CSV files into PNG plots and REPORT.md (one run, medians and ratios).

usage: python3 tests/bench/plot.py DIR      (DIR holds the CSVs written by drape_bench --out DIR)
"""
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REF_VIT = 15e6  # a well-known engine's XPBD cloth, vertex-iterations/s per core
MODELS = ["mass_spring", "pbd", "xpbd", "implicit"]
COLOURS = {"mass_spring": "tab:blue", "pbd": "tab:orange", "xpbd": "tab:green", "implicit": "tab:red"}
# Jolt Physics 5.5 soft bodies on the curtain of rest.csv (identical 12-spring network, pins, masses,
# stiffness), as measured for the solver's comparison: hanging-length error at rest per size and iteration
# count, and the cheapest Jolt setting within 1 % and 0.1 % with its ms per 60 Hz step (one core,
# medians of 5 interleaved rounds; LRA where cheaper).
JOLT = "Jolt 5.5, measured on a 2-vCPU x86-64 VM"
JOLT_LENGTH_ERROR = {17: {10: 0.0011, 20: 0.0002, 40: 0.00006}, 33: {10: 0.0048, 20: 0.0012, 40: 0.0005},
                     65: {10: 0.018, 20: 0.0049, 40: 0.0015}, 129: {10: 0.060, 20: 0.018, 40: 0.0054}}
JOLT_AT_LEVEL = {(0.01, 33): (10, 0.83), (0.01, 65): (20, 5.9), (0.01, 129): (40, 54.0),
                 (0.001, 33): (40, 3.3), (0.001, 65): (80, 23.0), (0.001, 129): (80, 105.0)}
STYLES = {"cpu": "-", "cpu_threaded": "--", "gles": ":"}


def read(out, name):
    path = os.path.join(out, name)
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def num(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def fin(v):
    return isinstance(v, float) and math.isfinite(v)


def machine_note(meta):
    cpu = meta.get("cpu", "?")
    return (f"{cpu}, {meta.get('hardware_threads', '?')} hardware threads shared with other builds "
            f"(1-min load average {meta.get('loadavg_1min_at_start', '?')} at start, "
            f"{meta.get('loadavg_1min_at_end', '?')} at end); {meta.get('mode', '?')} mode")


def default_cfg(meta):
    """(model, substeps, iterations) of the library's defaults as drape_bench recorded them (what a
    new cloth gets from the library, its budget as one step of a small cloth resolved it)."""
    return meta["default_model"], meta["default_substeps"], meta["default_iterations"]


def default_rows(rows, meta):
    """The rows of precision.csv run at the library's default: the model's automatic-budget row when
    the default asks for the automatic budget, else the rows at the default's resolved budget."""
    dm, ds, di = default_cfg(meta)
    mine = [r for r in rows if r["model"] == dm]
    auto = [r for r in mine if r["auto_substeps"] == "1"]
    if meta.get("default_auto_budget") == "1" and auto:
        return auto
    return [r for r in mine if r["substeps"] == ds and r["iterations"] == di]


def log_axes(ax, x=True, y=True):
    """Log scale on the axes that hold positive finite data; a note instead where none does
    (matplotlib cannot draw a log axis without a positive value)."""
    xs, ys = [], []
    for ln in ax.get_lines():
        tr = ln.get_transform()
        if tr != ax.get_yaxis_transform():  # axhline: x in axes coordinates
            xs += list(ln.get_xdata())
        if tr != ax.get_xaxis_transform():  # axvline: y in axes coordinates
            ys += list(ln.get_ydata())
    for col in ax.collections:
        off = col.get_offsets()
        if len(off):
            xs += [float(p[0]) for p in off]
            # Markers placed on an edge (y in axes coordinates) are not data on the y axis.
            if col.get_offset_transform() == ax.transData:
                ys += [float(p[1]) for p in off]
    def positive(v):
        out = []
        for a in v:
            try:
                a = float(a)
            except (TypeError, ValueError):
                continue
            if math.isfinite(a) and a > 0:
                out.append(a)
        return out
    ok = True
    # Limits set explicitly: edge markers (blended transforms) do not enter the data limits, and a
    # log axis left with matplotlib's default (0, 1) limits cannot be drawn.
    px, py = positive(xs), positive(ys)
    if x:
        if px:
            ax.set_xscale("log")
            ax.set_xlim(min(px) / 1.5, max(px) * 1.5)
        else:
            ok = False
    if y:
        if py:
            ax.set_yscale("log")
            ax.set_ylim(min(py) / 2, max(py) * 2)
        else:
            ok = False
    if not ok:
        ax.text(0.5, 0.5, "no positive values to plot", transform=ax.transAxes, ha="center", va="center",
                fontsize=8, color="grey")
    return ok


def variant(r):
    """A throughput row's model, with its budget where it is not the automatic one (e.g. implicit 1x1)."""
    return r["model"] if r["setting"] == "auto" else f"{r['model']} {r['setting']}"


def fig6(out, rows, meta, lines):
    if not rows:
        return
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.8))
    groups = defaultdict(list)
    for r in rows:
        if r["ok"] == "1":  # a rolled-back or capped step times no real frame
            groups[(variant(r), r["backend"])].append(r)
    for (m, be), rs in sorted(groups.items()):
        rs.sort(key=lambda r: num(r["vertices"]))
        v = [num(r["vertices"]) for r in rs]
        label = f"{m} {be}" + (" (Mesa llvmpipe, software)" if be == "gles" else "")
        marker = "o" if m == rs[0]["model"] else "s"
        a.plot(v, [num(r["ms_median"]) for r in rs], STYLES.get(be, "-"), marker=marker, color=COLOURS[rs[0]["model"]], label=label)
        b.plot(v, [num(r["vertex_iter_per_s"]) for r in rs], STYLES.get(be, "-"), marker=marker, color=COLOURS[rs[0]["model"]],
               label=label)
    b.axhline(REF_VIT, color="grey", lw=1)
    b.text(0.02, REF_VIT * 1.08, "reference engine 15 M/s per core", color="grey", fontsize=8,
           transform=b.get_yaxis_transform())
    b.axhline(5 * REF_VIT, color="grey", lw=1, ls=":")
    b.text(0.02, 5 * REF_VIT * 1.08, "target 5x = 75 M/s", color="grey", fontsize=8, transform=b.get_yaxis_transform())
    for ax, yl in ((a, "ms per step (median, 60 Hz frame)"), (b, "vertex-iterations / s")):
        log_axes(ax)
        ax.set_xlabel("vertices")
        ax.set_ylabel(yl)
        ax.grid(True, which="both", alpha=0.3)
    has_gles = any(r["backend"] == "gles" for r in rows)
    a.set_title("Step time vs vertex count (paper Fig. 6)")
    b.set_title("Throughput")
    a.legend(fontsize=7)
    note = ("GLES runs on Mesa llvmpipe (a software driver), not a GPU" if has_gles
            else "GLES backend not available in this build (drape_backend_available = 0)")
    fig.text(0.01, 0.01, note + ". " + machine_note(meta), fontsize=7)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(os.path.join(out, "fig6_step_time.png"), dpi=110)
    plt.close(fig)

    # Report tables.
    sizes = sorted({int(r["size"]) for r in rows})
    backends = [b for b in ("cpu", "cpu_threaded", "gles") if any(r["backend"] == b for r in rows)]
    idx = {(variant(r), r["backend"], int(r["size"])): r for r in rows}
    models = [v for m in MODELS for v in dict.fromkeys(variant(r) for r in rows if r["model"] == m)]
    lines.append("## Throughput (seed, paper Fig. 6)\n")
    lines.append("Hanging cloth (1 m, 0.2 kg, two top corners pinned), library defaults per model (automatic "
                 f"substeps and iterations, as throughput.csv records them; tethers max_stretch "
                 f"{meta.get('default_max_stretch', '?')}; MASS_SPRING: automatic substeps from the stability bound), "
                 "60 Hz. Vertex-iterations = vertices x substeps x iterations per frame (MASS_SPRING: 1 iteration). "
                 "Median of repeated frames after warm-up frames (none for MASS_SPRING from 128^2).\n")
    lines.append("| model | backend | " + " | ".join(f"{s}^2 ms/step" for s in sizes) + " | " +
                 " | ".join(f"{s}^2 M vit/s" for s in sizes) + " | max strain at " + f"{sizes[-1]}^2 |")
    lines.append("|" + "---|" * (3 + 2 * len(sizes)))
    for m in models:
        for be in backends:
            cells = [idx.get((m, be, s)) for s in sizes]
            ms = [(f"{num(c['ms_median']):.2f}" if c["ok"] == "1" else "unstable") if c else "" for c in cells]
            vit = [(f"{num(c['vertex_iter_per_s']) / 1e6:.1f}" if c["ok"] == "1" else "unstable") if c else "" for c in cells]
            last = cells[-1]
            lines.append(f"| {m} | {be} | " + " | ".join(ms) + " | " + " | ".join(vit) + " | " +
                         (f"{num(last['max_strain']):.3g}" if last else "") + " |")
    lines.append("")
    split = [r for r in rows if num(r.get("frame_steps")) > 1]
    if split:
        lines.append("MASS_SPRING needs more substeps per 60 Hz frame than one library step may take "
                     "(DRAPE_MAX_SUBSTEPS; a capped step is below its stability bound and is rolled back), so those "
                     "frames are timed as several steps of 1/60 s / n: " +
                     ", ".join(f"{r['size']}^2 {r['backend']} {r['frame_steps']} steps, {r['substeps']} substeps, "
                               f"median of {r['steps']} frame(s)" for r in split) + ".\n")
    lines.append("Ratio to the 15 M vertex-iterations/s reference (CPU backend, one core; target >= 5) and "
                 "CPU_THREADED / CPU speed-up (target >= 1.8 for 128^2 and up):\n")
    lines.append("| model | " + " | ".join(f"{s}^2 CPU / 15M" for s in sizes) + " | " +
                 " | ".join(f"{s}^2 threaded speed-up" for s in sizes) + " |")
    lines.append("|" + "---|" * (1 + 2 * len(sizes)))
    for m in models:
        r1 = []
        r2 = []
        for s in sizes:
            c, t = idx.get((m, "cpu", s)), idx.get((m, "cpu_threaded", s))
            r1.append(f"{num(c['vertex_iter_per_s']) / REF_VIT:.2f}" if c and c["ok"] == "1" else "")
            r2.append(f"{num(c['ms_median']) / num(t['ms_median']):.2f}" if c and t and c["ok"] == t["ok"] == "1" else "")
        lines.append(f"| {m} | " + " | ".join(r1) + " | " + " | ".join(r2) + " |")
    lines.append("")


def threads(out, rows, rounds, meta, lines):
    """Two threads against one: per-round speed-ups of interleaved rounds (threads_rounds.csv), the
    machine's own ceiling (the pool on work with no shared writes) beside the cloth's."""
    if not rows:
        return
    # calibration_empty times the pool's own cost per pass; its ratio is no speed-up
    many = [r for r in rows if (int(r["threads"]) > 1 or r["backend"] == "cpu_threaded")
            and r["scene"] != "calibration_empty"]
    keys = list(dict.fromkeys((r["scene"], r["backend"], r["threads"]) for r in many))
    by = defaultdict(list)
    for r in rounds:
        by[(r["scene"], r["backend"], r["threads"])].append(num(r["speedup"]))
    fig, ax = plt.subplots(figsize=(8, 4.5))
    data = [by.get(k, []) for k in keys]
    ax.boxplot(data, whis=(0, 100), widths=0.5)
    for i, d in enumerate(data):
        ax.plot([i + 1] * len(d), d, ".", color="tab:blue", alpha=0.5, ms=4)
    ax.set_xticks(range(1, len(keys) + 1))
    ax.set_xticklabels([f"{s}\n{b} x{t}" for s, b, t in keys], rotation=60,
                       fontsize=6, ha="right")
    ax.axhline(1.8, color="grey", lw=1, ls=":")
    ax.axhline(1.0, color="grey", lw=1)
    ax.set_ylabel("one thread's wall time / this one's, per round")
    ax.set_title("Two threads over one, interleaved rounds (box: quartiles, whiskers: min-max; dotted: 1.8x)",
                 fontsize=8)
    ax.grid(alpha=0.3, axis="y")
    fig.text(0.01, 0.01, machine_note(meta), fontsize=6)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(os.path.join(out, "threads.png"), dpi=110)
    plt.close(fig)
    lines.append("## Two threads over one (interleaved rounds)\n")
    lines.append("Each scene runs on one thread (the CPU backend; the pool with one thread for the calibration) and "
                 "on several in the same rounds, one side first in even rounds and last in odd ones; the speed-up "
                 "is one thread's wall time over the other's, per round. Calibration: the library's thread pool on "
                 "a compute kernel with no shared writes, in passes of about 50 us (short, like the cloth's) and "
                 "2 ms (long): what this machine gives two threads at best; calibration_wide: long passes of 32 "
                 "independent chains an item, bound by the core's issue width (two hardware threads of one core "
                 "gain far less there than two cores); calibration_empty: 1000 passes with no "
                 "work a round, so its several threads' ms per round are the pool's own cost per pass in us (its "
                 "speed-up means nothing). Cloth: the falling sheet (two top "
                 "corners), the same steps on each side; ceiling: the short calibration timed in the same rounds "
                 "(one thread's speed moves from round to round on a VM, even idle), and the cloth's per-round "
                 "speed-up over that round's ceiling (1.0: all the machine gave). CPU shares: CPU time / wall time over the rounds (the "
                 "workers spin between passes, so theirs includes waiting); wait: time runnable but not run "
                 "(schedstat); worker sleeps: the workers' voluntary context switches (a worker sleeps when a gap "
                 "between passes outlasts its spinning); steal: the machine's steal time (/proc/stat), per round.\n")
    lines.append("| scene | backend | threads | rounds | wall ms/round (median) | speed-up median | quartiles | "
                 "min-max | ceiling, same rounds | speed-up / ceiling | caller CPU share | workers' CPU share | "
                 "wait ms/round | worker sleeps/round | steal ms/round |")
    lines.append("|" + "---|" * 15)
    for r in rows:
        lines.append(f"| {r['scene']} | {r['backend']} | {r['threads']} | {r['rounds']} | "
                     f"{num(r['wall_ms_median']):.2f} | {num(r['speedup_median']):.2f} | "
                     f"{num(r['speedup_q1']):.2f}-{num(r['speedup_q3']):.2f} | "
                     f"{num(r['speedup_min']):.2f}-{num(r['speedup_max']):.2f} | "
                     + (f"{num(r['ceiling_speedup_median']):.2f} | {num(r['speedup_over_ceiling_median']):.2f} | "
                        if r.get("ceiling_speedup_median") else "| | ")
                     + f"{num(r['caller_cpu_share']):.2f} | "
                     f"{num(r['worker_cpu_share']):.2f} | {num(r['wait_ms_per_round']):.2f} | "
                     f"{num(r['worker_sleeps_per_round']):.1f} | {num(r['steal_ms_per_round']):.1f} |")
    lines.append("")


def pareto(points):
    """points: (cost, err, row); returns the non-dominated ones sorted by cost."""
    pts = sorted(points, key=lambda p: (p[0], p[1]))
    front, best = [], math.inf
    for p in pts:
        if p[1] < best:
            front.append(p)
            best = p[1]
    return front


def cfg(r):
    if r["model"] == "mass_spring":
        return f"mass_spring {r['substeps']} substeps" + (" (auto)" if r["auto_substeps"] == "1" else "")
    return f"{r['model']} {r['substeps']}x{r['iterations']}"


def tethers_table(rows, lines):
    """Two-corner cloth at 64^2..128^2 with and without tethers (scenes two_corners_N)."""
    rs = [r for r in rows if r["scene"].startswith("two_corners_")]
    if not rs:
        return
    lines.append("### Tethers on the two-corner cloth (`two_corners_N`)\n")
    lines.append("Same scene and Newton reference as `two_corners`, at N^2; each setting with tethers off "
                 "(max_stretch 0) and on (the default). Max strain at the end of the 3 s run and its peak over the run "
                 "(structural + shear springs); the exact equilibrium's max strain for comparison.\n")
    lines.append("| size | setting | max_stretch | ms/step | max strain (end) | peak max strain | exact max strain | E2 | stable |")
    lines.append("|---|---|---|---|---|---|---|---|---|")
    for r in rs:
        lines.append(f"| {r['size']}^2 | {cfg(r)} | {num(r['max_stretch']):g} | {num(r['ms_median']):.2f} | "
                     f"{num(r['max_strain']):.3g} | {num(r.get('peak_max_strain')):.3g} | {num(r['ref_max_strain']):.3g} | "
                     f"{num(r['e2']):.3g} | {'yes' if r['ok'] == '1' else 'no'} |")
    lines.append("")


def precision(out, rows, refs, meta, lines):
    if not rows:
        return
    scenes = []
    for r in rows:
        if r["scene"] not in scenes and not r["scene"].startswith("two_corners_"):
            scenes.append(r["scene"])
    dm, ds, di = default_cfg(meta)
    lines.append("## Work-precision\n")
    lines.append("Scenes: `two_corners` = cloth hanging from its two top corners in its plane, starts flat and "
                 "unstretched, 3 s (quick: 1 s) at 60 Hz with the default damping; reference = static equilibrium of "
                 "the same springs, masses and pins solved by Newton in double precision (Eigen sparse LDL^T, "
                 "tests/bench/reference.h). E2 = max vertex distance to it / cloth size, at the end. "
                 "Energy drift = max |E(t) - E(0)| / (M g H) over an undamped (damping 0, air drag 0) run of the same "
                 "configuration (1 s; quick 0.25 s); E = kinetic + gravity + spring energy as drape_stats reports it "
                 "(PBD reports no spring energy, so its drift is not comparable). "
                 "`chain_1eX` = R4 hanging chain, 20 particles of 5 g, tip mass 10^X times the chain's mass, spring "
                 "stiffness set so the exact top strain is 1%; starts at the exact equilibrium at rest; "
                 "E2 = max over 2 s of the max particle error / chain length (exact answer). "
                 "`sphere_drape` = 1 m cloth (no pins) falling from 5 cm above a sphere (r 0.25 m, friction 0.5), contact "
                 "at ~0.1 s; no exact answer, so the reference is the same scene converged: XPBD, 1 iteration, 1000 "
                 "substeps per 1/60 s frame (the library's maximum; h = 1.7e-5 s); E2 = max vertex distance to it at "
                 "0.2 s / cloth size (0.1 s after contact: later the overhang buckles into folds and the 1000- and "
                 "500-substep runs differ by 3-10 cm, so no converged reference exists for the settled drape). "
                 "PBD uses stiffness fractions (1, 0.5, 0.1) (chain: 1), so its error is distance to the physical "
                 "material, which PBD cannot represent. All with the library's default tethers (max_stretch "
                 f"{meta.get('default_max_stretch', '?')}) unless a table says otherwise. CPU backend.\n")
    for r in refs:
        if r.get("kind") == "xpbd_1000x1_vs_500x1":
            lines.append(f"Reference `{r['scene']}` {r['size']}^2: converged run (XPBD 1000x1); its distance to the same "
                         f"run at 500x1 is {num(r.get('residual')):.2g} m (an estimate of its own error), max strain "
                         f"{num(r['ref_max_strain']):.4f}.\n")
        else:
            lines.append(f"Reference `{r['scene']}` {r['size']}^2: Newton residual {num(r.get('residual', r.get('newton_residual_N'))):.1e} N, "
                         f"max strain {num(r['ref_max_strain']):.4f}.\n")
    levels = [0.3, 0.1, 0.03, 0.01, 0.003, 0.001, 1e-4]
    for scene in scenes:
        rs = [r for r in rows if r["scene"] == scene]
        metrics = [("e2", "E2 position error / size"), ("e1_rel_error", "E1 |max strain - ref| / ref")]
        if scene == "two_corners":
            metrics.append(("energy_drift_or_ext_error", "energy drift |dE| / (M g H), undamped"))
        elif scene.startswith("chain"):
            metrics.append(("energy_drift_or_ext_error", "tip extension relative error"))
        fig, axes = plt.subplots(1, len(metrics), figsize=(5.2 * len(metrics), 4.6))
        for ax, (key, title) in zip(axes, metrics):
            for m in MODELS:
                mr = [r for r in rs if r["model"] == m]
                ok = [r for r in mr if r["ok"] == "1" and fin(num(r[key])) and num(r[key]) > 0]
                bad = [r for r in mr if r["ok"] != "1"]
                if ok:
                    ax.scatter([num(r["ms_median"]) for r in ok], [num(r[key]) for r in ok], s=18, color=COLOURS[m], label=m)
                if bad:
                    # Unstable settings sit on the top edge of the panel (their error is not a number to plot).
                    ax.scatter([num(r["ms_median"]) for r in bad], [0.97] * len(bad), marker="x", color=COLOURS[m], s=30,
                               transform=ax.get_xaxis_transform(), label=f"{m} unstable step(s) (top edge)")
                if m != "mass_spring":
                    # Equal-cost diagonals: substeps x iterations constant.
                    by = defaultdict(list)
                    for r in ok:
                        by[int(r["substeps"]) * int(r["iterations"])].append(r)
                    for cost, cr in by.items():
                        if len(cr) < 2:
                            continue
                        cr.sort(key=lambda r: int(r["substeps"]))
                        ax.plot([num(r["ms_median"]) for r in cr], [num(r[key]) for r in cr], color=COLOURS[m], lw=0.6, alpha=0.5)
                        last = cr[-1]
                        ax.annotate(f"{last['substeps']}x{last['iterations']}", (num(last["ms_median"]), num(last[key])),
                                    fontsize=6, color=COLOURS[m])
            d = default_rows(rs, meta)
            if d and fin(num(d[0][key])) and num(d[0][key]) > 0:
                ax.scatter([num(d[0]["ms_median"])], [num(d[0][key])], marker="*", s=160, facecolor="none",
                           edgecolor="black", label=f"default {dm} {ds}x{di}", zorder=5)
            pts = [(num(r["ms_median"]), num(r[key]), r) for r in rs
                   if r["ok"] == "1" and fin(num(r[key])) and num(r[key]) > 0]
            fr = pareto(pts)
            if fr:
                ax.step([p[0] for p in fr], [p[1] for p in fr], where="post", color="black", lw=0.8, alpha=0.6, label="Pareto front")
            log_axes(ax)
            ax.set_xlabel("ms per step (median)")
            ax.set_title(title, fontsize=9)
            ax.grid(True, which="both", alpha=0.3)
        axes[0].legend(fontsize=6)
        size = rs[0]["size"]
        fig.suptitle(f"Work-precision, scene {scene} ({size} {'particles' if scene.startswith('chain') else '^2'}); "
                     "lines join equal substeps x iterations; labels = substeps x iterations", fontsize=9)
        fig.text(0.01, 0.01, machine_note(meta), fontsize=6)
        fig.tight_layout(rect=(0, 0.04, 1, 0.95))
        fig.savefig(os.path.join(out, f"precision_{scene}.png"), dpi=110)
        plt.close(fig)

        # Pareto-best setting per E2 level: the cheapest stable configuration reaching it.
        lines.append(f"### Scene `{scene}`: cheapest configuration per E2 level (Pareto-best)\n")
        lines.append("| E2 <= | best configuration | ms/step | E2 | max strain | best XPBD | ms/step | E2 |")
        lines.append("|---|---|---|---|---|---|---|---|")
        okrows = [r for r in rs if r["ok"] == "1" and fin(num(r["e2"]))]
        for lv in levels:
            c = [r for r in okrows if num(r["e2"]) <= lv]
            if not c:
                continue
            b = min(c, key=lambda r: num(r["ms_median"]))
            x = [r for r in c if r["model"] == "xpbd"]
            bx = min(x, key=lambda r: num(r["ms_median"])) if x else None
            lines.append(f"| {lv:g} | {cfg(b)} | {num(b['ms_median']):.3f} | {num(b['e2']):.2g} | {num(b['max_strain']):.3g} | "
                         + (f"{cfg(bx)} | {num(bx['ms_median']):.3f} | {num(bx['e2']):.2g} |" if bx else "- | - | - |"))
        unstable = [cfg(r) for r in rs if r["ok"] != "1"]
        if unstable:
            lines.append("")
            lines.append("Unstable (a step failed; left out of the table): " + ", ".join(unstable) + ".")
        if d:
            dr = d[0]
            cost = int(ds) * int(di)
            better = [r for r in okrows if num(r["ms_median"]) <= num(dr["ms_median"]) and num(r["e2"]) < num(dr["e2"]) and r is not dr]
            eq = [r for r in okrows if r["model"] == dm and int(r["substeps"]) * int(r["iterations"]) == cost]
            eq.sort(key=lambda r: num(r["e2"]))
            lines.append("")
            lines.append(f"**Default ({dm} {ds}x{di}, the marked star)**: {num(dr['ms_median']):.3f} ms/step, E2 "
                         f"{num(dr['e2']):.3g}, max strain {num(dr['max_strain']):.3g}. Equal-cost ({cost} solver passes) "
                         f"{dm} settings by E2: " +
                         ", ".join(f"{cfg(r)} {num(r['e2']):.3g} ({num(r['ms_median']):.3f} ms)" for r in eq) + ".")
            if better:
                bb = min(better, key=lambda r: num(r["e2"]))
                lines.append(f"Not Pareto-optimal here: {len(better)} configuration(s) are both faster (or equal) and more "
                             f"accurate; the most accurate of them is {cfg(bb)} ({num(bb['ms_median']):.3f} ms, E2 {num(bb['e2']):.3g}).")
            else:
                lines.append("On the Pareto front here: nothing measured is both faster and more accurate.")
        else:
            lines.append("")
            lines.append(f"The default ({dm} {ds}x{di}) was not measured in this scene.")
        lines.append("")
    tethers_table(rows, lines)


MODEL_NAMES = {"mass_spring": "MASS_SPRING", "pbd": "PBD", "xpbd": "XPBD", "implicit": "IMPLICIT"}


def rest_setting(r):
    """A rest.csv row's setting as asked for (auto = the library's automatic budget), with what it ran."""
    if r["model"] == "mass_spring":
        budget = "auto" if r["setting"] == "auto" else r["setting"] + " substeps"
    else:
        budget = f"auto {r['substeps']}x{r['iterations']}" if r["setting"] == "auto" else r["setting"]
    tethers = f", tethers {num(r['max_stretch']):g}" if num(r["max_stretch"]) > 0 else ""
    return f"{MODEL_NAMES[r['model']]} {budget}{tethers}" + (" (default)" if r["is_default"] == "1" else "")


def rest_key(r):
    """Same setting across sizes (MASS_SPRING's automatic substeps differ per size)."""
    return (r["model"], r["setting"], r["max_stretch"], r["is_default"])


def rest(out, rows, meta, lines):
    """Stretch-dominated rest states (accuracy.md R13) against the Newton equilibrium."""
    if not rows:
        return
    lines.append("## Stretch-dominated rest states (R13)\n")
    lines.append("Curtain pinned along its top row (1 kg) and sheet pinned along two opposite edges (0.5 kg), springs "
                 "2000/1000/200 N/m, run to rest (10 s; quick 3 s) with air drag 3/s (no force at rest), against the "
                 "double-precision Newton equilibrium of the same springs. vertex error = max |x - x_ref| / largest "
                 "displacement from the rest pose; length error = error of the lowest point / hanging length (the "
                 "metric of the Jolt figures; for the sheet, over its centre sag). ms = CPU time of the one thread that steps it, per 60 Hz step, median "
                 "over interleaved rounds once every setting is at rest (wall-clock median in rest.csv). Settings "
                 "without tethers except the library's defaults, which run as they are.\n")
    lines.append("| scene | size | setting | ms/step | vertex error | length error | max strain / exact |")
    lines.append("|---|---|---|---|---|---|---|")
    for r in rows:
        errors = (f"{num(r['vertex_error']):.2e} | {num(r['length_error']):.2e} | "
                  f"{num(r['max_strain']) / max(num(r['ref_max_strain']), 1e-12):.2f}" if fin(num(r["length_error"]))
                  else "not run to rest (timed only) | | ")
        lines.append(f"| {r['scene']} | {r['size']}^2 | {rest_setting(r)} | {num(r['cpu_ms_median']):.3f} | {errors} |")
    lines.append("")
    # Where the default sits, in words, per scene and size.
    for scene in ("curtain", "sheet"):
        for size in sorted({int(r["size"]) for r in rows if r["scene"] == scene}):
            rs = [r for r in rows if r["scene"] == scene and int(r["size"]) == size and r["ok"] == "1"]
            d = [r for r in rs if r["is_default"] == "1"]
            if not d:
                continue
            d = d[0]
            # Item 1 of the solver issue: the worst vertex and the lowest point within 0.5 % of the
            # largest displacement (NaN, not run to rest, never is).
            within = [r for r in rs if max(num(r["vertex_error"]), num(r["lowest_error"])) <= 0.005]
            best = min(within, key=lambda r: num(r["cpu_ms_median"])) if within else None
            lines.append(f"- **{scene} {size}^2, default {rest_setting(d)}** (star on precision_rest.png): "
                         f"{num(d['cpu_ms_median']):.3g} ms/step, {'hanging length' if scene == 'curtain' else 'centre sag'} "
                         f"{100 * num(d['length_error']):.3g} % off, "
                         f"worst vertex {num(d['vertex_error']):.3g} x the largest displacement"
                         + {"1": f"; CPU_THREADED ({d['threads']} threads) at rest: the same bits. ",
                            "0": f"; CPU_THREADED ({d['threads']} threads) at rest: DIFFERENT bits. "}.get(d.get("threaded_same"), ". ")
                         + (f"Cheapest measured setting within 0.5 % of the displacement at every vertex: {rest_setting(best)}, "
                            f"{num(best['cpu_ms_median']):.3g} ms ({num(best['cpu_ms_median']) / num(d['cpu_ms_median']):.2g} x "
                            f"the default's cost)." if best else "No measured setting is within 0.5 % of the displacement at every vertex."))
    lines.append("")
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, scene in zip(axes, ["curtain", "sheet"]):
        for model in MODELS:
            pts = [r for r in rows if r["scene"] == scene and r["model"] == model and fin(num(r["cpu_ms_median"]))
                   and fin(num(r["length_error"]))]
            if not pts:
                continue
            ax.scatter([num(r["cpu_ms_median"]) for r in pts], [max(num(r["length_error"]), 1e-9) for r in pts],
                       color=COLOURS[model], label=MODEL_NAMES[model], s=14)
            for r in pts:
                ax.annotate(f"{r['size']}^2 {r['setting']}", (num(r["cpu_ms_median"]), max(num(r["length_error"]), 1e-9)),
                            fontsize=5)
        d = [r for r in rows if r["scene"] == scene and r["is_default"] == "1"]
        if d:
            ax.scatter([num(r["cpu_ms_median"]) for r in d], [max(num(r["length_error"]), 1e-9) for r in d], marker="*",
                       s=160, facecolors="none", edgecolors="black", label=rest_setting(d[0]), zorder=5)
        if scene == "curtain":
            jolt_points(ax)
        log_axes(ax)
        ax.set_xlabel("ms per 60 Hz step (one core, median)")
        ax.set_ylabel("hanging-length error at rest" if scene == "curtain" else "centre sag error at rest")
        ax.set_title(f"{scene}: rest state vs Newton equilibrium", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
    fig.text(0.01, 0.01, machine_note(meta), fontsize=6)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(os.path.join(out, "precision_rest.png"), dpi=110)
    plt.close(fig)


def jolt_points(ax):
    """Jolt's settings with a known cost on a work-precision panel: error where it was measured,
    else drawn at the level it is within (triangle: at most that)."""
    for (level, size), (it, ms) in sorted(JOLT_AT_LEVEL.items()):
        err = JOLT_LENGTH_ERROR[size].get(it)
        ax.scatter([ms], [err if err else level], marker="x" if err else "v", color="black", s=30)
        ax.annotate(f"Jolt {size}^2 {it} it", (ms, err if err else level), fontsize=6)
    ax.scatter([], [], marker="x", color="black", label=JOLT)


def stiff_under_load(out, rows, meta, lines):
    """Max strain after 3 s hanging from two corners against the exact equilibrium's:
    stiff_under_load.png and a REPORT section (the target: at most 2x at the default budget)."""
    if not rows:
        return
    sizes = sorted({int(r["size"]) for r in rows})
    settings = list(dict.fromkeys((r["model"], r["setting"], r["max_stretch"], r["is_default"]) for r in rows))

    def label(st):
        model, setting, stretch, is_default = st
        return (f"{MODEL_NAMES[model]} {setting}" + (f", tethers {stretch}" if num(stretch) > 0 else "")
                + (" (default)" if is_default == "1" else ""))

    fig, ax = plt.subplots(figsize=(7.5, 4.6))
    width = 0.8 / len(settings)
    for k, st in enumerate(settings):
        cells = [next((r for r in rows if int(r["size"]) == n and (r["model"], r["setting"], r["max_stretch"],
                                                                   r["is_default"]) == st), None) for n in sizes]
        xs = [i + (k - (len(settings) - 1) / 2) * width for i, c in enumerate(cells) if c]
        ys = [num(c["strain_over_ref"]) for c in cells if c]
        ax.bar(xs, ys, width, color=COLOURS[st[0]], alpha=1.0 if st[3] == "1" else 0.55,
               edgecolor="black" if st[3] == "1" else "none", label=label(st))
    ax.axhline(2, color="black", ls=":", lw=1)
    ax.text(0.01, 2.1, "target: 2 x the equilibrium's", transform=ax.get_yaxis_transform(), fontsize=7)
    ax.set_yscale("log")
    ax.set_xticks(range(len(sizes)))
    ax.set_xticklabels([f"{n}^2" for n in sizes])
    ax.set_ylabel("max strain after 3 s / equilibrium's")
    ax.set_title("Stiff under load: cloth hanging from two corners (the default has a black edge)", fontsize=9)
    ax.legend(fontsize=7)
    fig.text(0.01, 0.01, machine_note(meta), fontsize=6)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(os.path.join(out, "stiff_under_load.png"), dpi=110)
    plt.close(fig)

    lines.append("## Stiff under load\n")
    lines.append("Cloth hanging from its two top corners (1 m, 0.2 kg, springs 2000/1000/200 N/m), 3 s at 60 Hz from "
                 "flat with the default damping, one thread; max strain of the structural and shear springs at the end "
                 "against the exact (Newton) equilibrium's. Target: at most 2x at the default budget, without tethers. "
                 "CSV: stiff_under_load.csv; plot: stiff_under_load.png.\n")
    lines.append("| setting | " + " | ".join(f"{n}^2 max strain (x equilibrium) / ms" for n in sizes) + " |")
    lines.append("|---|" + "---|" * len(sizes))
    for st in settings:
        cells = []
        for n in sizes:
            c = next((r for r in rows if int(r["size"]) == n and (r["model"], r["setting"], r["max_stretch"],
                                                                  r["is_default"]) == st), None)
            cells.append("" if not c else
                         f"{num(c['max_strain']):.3g} (x{num(c['strain_over_ref']):.2f}) / {num(c['ms_median']):.1f}"
                         + ("" if c["ok"] == "1" else " unstable"))
        lines.append(f"| {label(st)} | " + " | ".join(cells) + " |")
    lines.append("")


def fall(out, rows, meta, lines):
    """The sheet falling from flat against a fine-step MASS_SPRING reference: fall.png (error
    against cost, one panel per stiffness) and a REPORT section."""
    if not rows:
        return
    scales = sorted({num(r["stiffness_scale"]) for r in rows})
    fig, axes = plt.subplots(1, len(scales), figsize=(4 * len(scales), 3.8), squeeze=False)
    for ax, scale in zip(axes[0], scales):
        for r in (r for r in rows if num(r["stiffness_scale"]) == scale):
            default = r["is_default"] == "1"
            ax.scatter([num(r["ms_median"])], [num(r["max_vertex_error"])], color=COLOURS[r["model"]],
                       marker="*" if default else "o", s=160 if default else 24,
                       edgecolor="black" if default else "none")
            ax.annotate(f"{r['model']} {r['setting']}", (num(r["ms_median"]), num(r["max_vertex_error"])), fontsize=6)
        log_axes(ax)
        k = next(num(r["structural_stiffness"]) for r in rows if num(r["stiffness_scale"]) == scale)
        ax.set_title(f"structural {k:g} N/m", fontsize=9)
        ax.set_xlabel("ms per 60 Hz step (one thread)")
    axes[0][0].set_ylabel("max vertex distance from reference / size")
    fig.suptitle("Falling sheet, 0.5 s from flat (the default is a star)", fontsize=9)
    fig.text(0.01, 0.01, machine_note(meta), fontsize=6)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(os.path.join(out, "fall.png"), dpi=110)
    plt.close(fig)

    size = rows[0]["size"]
    lines.append("## Motion: a falling sheet\n")
    lines.append(f"Sheet {size}^2 (1 m, 0.2 kg), horizontal, pinned at the two corners of one edge, falling from flat "
                 "for 0.5 s at 60 Hz with the default damping and tethers, at the library's stiffness x1, x10, x50. "
                 "Reference: MASS_SPRING (the same springs) within its stability bound; its own error (against itself at "
                 "half the substep) is the ref column. Error: the largest distance of any vertex from the reference's "
                 "over all frames, over the cloth size; fall: how far the centre of mass fell against the reference's "
                 "(1 = as far; below 1 the cloth falls in slow motion). CSV: fall.csv; plot: fall.png.\n")
    lines.append("| stiffness | setting | error | fall | ms | ref |")
    lines.append("|---|---|---|---|---|---|")
    for r in rows:
        lines.append(f"| {num(r['structural_stiffness']):g} N/m | {r['model']} {r['setting']}"
                     + (" (default)" if r["is_default"] == "1" else "")
                     + f" | {num(r['max_vertex_error']):.3g} | {num(r['fall_ratio']):.2f} | {num(r['ms_median']):.3f}"
                     + f" | {num(r['ref_error']):.1e} |" + ("" if r["ok"] == "1" else " unstable"))
    lines.append("")


def curtain_vs_jolt(out, rows, meta, lines):
    """The curtain comparison re-measured, beside Jolt 5.5's figures: curtain_vs_jolt.csv,
    equal_error.csv, curtain_vs_jolt.png and a REPORT section."""
    rows = [r for r in rows if r["scene"] == "curtain" and r["ok"] == "1"]
    if not rows:
        return
    sizes = sorted({int(r["size"]) for r in rows})
    settings = []
    for r in rows:
        if rest_key(r) not in [rest_key(x) for x in settings]:
            settings.append(r)
    at = {(rest_key(r), int(r["size"])): r for r in rows}
    with open(os.path.join(out, "curtain_vs_jolt.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["size", "engine", "setting", "length_error", "vertex_error", "ms_per_step", "source"])
        for size in sizes:
            for r in [x for x in rows if int(x["size"]) == size]:
                w.writerow([size, "drape", rest_setting(r), r["length_error"], r["vertex_error"], r["cpu_ms_median"],
                            "this run, CPU time of one thread"])
            for it, err in JOLT_LENGTH_ERROR.get(size, {}).items():
                ms = [v[1] for k, v in JOLT_AT_LEVEL.items() if k[1] == size and v[0] == it]
                w.writerow([size, "jolt", f"{it} iterations", err, "", ms[0] if ms else "", JOLT])
    lines.append("## Curtain: Drape against Jolt 5.5\n")
    lines.append(f"The curtain comparison with Jolt re-measured in this run (curtain of the rest scenes above; ms = CPU time "
                 f"of one thread per 60 Hz step, medians of interleaved rounds at rest) beside Jolt's figures "
                 f"({JOLT}; Jolt's ms only where they were measured). Each cell: hanging-length error / "
                 "worst vertex error over the largest displacement / ms. CSV: curtain_vs_jolt.csv, equal_error.csv; "
                 "plot: curtain_vs_jolt.png.\n")
    lines.append("| setting | " + " | ".join(f"{s}^2" for s in sizes) + " |")
    lines.append("|---|" + "---|" * len(sizes))
    for st in settings:
        cells = []
        for s in sizes:
            r = at.get((rest_key(st), s))
            if not r:
                cells.append("")
            elif fin(num(r["length_error"])):
                cells.append(f"{100 * num(r['length_error']):.3g} % / {num(r['vertex_error']):.2g} / "
                             f"{num(r['cpu_ms_median']):.3g} ms")
            else:
                cells.append(f"not run to rest / {num(r['cpu_ms_median']):.3g} ms")
        lines.append(f"| {rest_setting(st)} | " + " | ".join(cells) + " |")
    for it in (10, 20, 40):
        cells = []
        for s in sizes:
            err = JOLT_LENGTH_ERROR.get(s, {}).get(it)
            ms = [v[1] for k, v in JOLT_AT_LEVEL.items() if k[1] == s and v[0] == it]
            cells.append((f"{100 * err:.3g} %" if err is not None else "") + (f" / {ms[0]:g} ms" if ms else ""))
        lines.append(f"| {JOLT}: {it} iterations | " + " | ".join(cells) + " |")
    lines.append("")
    # Time at equal error: the cheapest measured Drape setting within each level, against Jolt's.
    lines.append("Time at equal error: the cheapest Drape setting measured here whose hanging-length error is within "
                 "the level, against the cheapest Jolt setting within it.\n")
    lines.append("| level | size | Jolt 5.5 | cheapest Drape | Drape / Jolt | cheapest per Drape model |")
    lines.append("|---|---|---|---|---|---|")
    with open(os.path.join(out, "equal_error.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["level", "size", "jolt_iterations", "jolt_ms", "drape_setting", "drape_length_error", "drape_ms",
                    "drape_over_jolt"])
        for (level, size), (it, jms) in sorted(JOLT_AT_LEVEL.items(), key=lambda kv: (-kv[0][0], kv[0][1])):
            if size not in sizes:
                continue
            c = [r for r in rows if int(r["size"]) == size and num(r["length_error"]) <= level]
            b = min(c, key=lambda r: num(r["cpu_ms_median"])) if c else None
            per_model = []
            for m in MODELS:
                cm = [r for r in c if r["model"] == m]
                if cm:
                    bm = min(cm, key=lambda r: num(r["cpu_ms_median"]))
                    per_model.append(f"{rest_setting(bm)} {num(bm['cpu_ms_median']):.3g} ms")
            ratio = num(b["cpu_ms_median"]) / jms if b else math.nan
            w.writerow([level, size, it, jms, rest_setting(b) if b else "none", b["length_error"] if b else "",
                        b["cpu_ms_median"] if b else "", f"{ratio:.3g}" if b else ""])
            lines.append(f"| {100 * level:g} % | {size}^2 | {it} it, {jms:g} ms | "
                         + (f"{rest_setting(b)}, {num(b['cpu_ms_median']):.3g} ms | {ratio:.2g} x | " if b else
                            "none measured | - | ")
                         + "; ".join(per_model) + " |")
    lines.append("")
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.8))
    for st in settings:
        pts = [(s, at[(rest_key(st), s)]) for s in sizes if (rest_key(st), s) in at and fin(num(at[(rest_key(st), s)]["length_error"]))]
        colour = COLOURS[st["model"]]
        style = "-" if st["setting"] == "auto" else "--"
        width = 2.5 if st["is_default"] == "1" else 1
        a.plot([p[0] for p in pts], [max(num(p[1]["length_error"]), 1e-9) for p in pts], style, marker="o", color=colour,
               label=rest_setting(st), lw=width)
        b.plot([num(p[1]["cpu_ms_median"]) for p in pts], [max(num(p[1]["length_error"]), 1e-9) for p in pts], style,
               marker="o", color=colour, label=rest_setting(st), lw=width)
        for s, r in pts:
            b.annotate(f"{s}^2", (num(r["cpu_ms_median"]), max(num(r["length_error"]), 1e-9)), fontsize=6)
    for it in (10, 20, 40):
        js = [s for s in sizes if it in JOLT_LENGTH_ERROR.get(s, {})]
        a.plot(js, [JOLT_LENGTH_ERROR[s][it] for s in js], ":", marker="x", color="black", lw=1, label=f"{JOLT}: {it} it")
    jolt_points(b)
    for ax in (a, b):
        for level in (0.01, 0.001):
            ax.axhline(level, color="grey", lw=0.8, ls=":")
        log_axes(ax, x=ax is b)
        ax.set_ylabel("hanging-length error at rest")
        ax.grid(True, which="both", alpha=0.3)
    a.set_xscale("log", base=2)
    a.set_xticks(sizes, [f"{s}^2" for s in sizes])
    a.set_xlabel("curtain resolution")
    b.set_xlabel("ms per 60 Hz step (one core)")
    a.set_title("Hanging-length error vs resolution (thick: the default)", fontsize=9)
    b.set_title("Work-precision; dotted lines at 1 % and 0.1 %", fontsize=9)
    a.legend(fontsize=6)
    fig.text(0.01, 0.01, machine_note(meta), fontsize=6)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.savefig(os.path.join(out, "curtain_vs_jolt.png"), dpi=110)
    plt.close(fig)


def stress(out, rows, s10it, s8, meta, lines):
    if not rows:
        return
    s1 = [r for r in rows if r["test"] == "S1"]
    labels = []
    for r in s1:
        if r["case"] not in labels:
            labels.append(r["case"])
    n = int(meta.get("stress_grid", "16"))
    mass = float(meta.get("cloth_mass", "0.2"))
    m = mass / (n * n)
    fig, axes = plt.subplots(1, len(labels), figsize=(4.4 * len(labels), 4.2))
    if len(labels) == 1:
        axes = [axes]
    for ax, lab in zip(axes, labels):
        rs = [r for r in s1 if r["case"] == lab]
        for r in rs:
            ok = r["survived"] == "1"
            ax.scatter(num(r["stiffness"]), num(r["dt"]), marker="s", s=140, color="tab:green" if ok else "tab:red")
            if not ok:
                ax.annotate(f"{num(r['time_to_failure_s']):.2g}s", (num(r["stiffness"]), num(r["dt"])), fontsize=5,
                            ha="center", va="center", color="white")
        log_axes(ax)
        ax.set_xlabel("PBD stiffness fraction" if lab == "pbd" else "stiffness k (N/m, all groups)")
        ax.set_ylabel("frame dt (s)")
        ax.set_title(lab, fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        if lab.startswith("mass_spring"):
            ks = [10 ** (e / 10) for e in range(10, 91)]
            # Crude bound: w^2 <= 2 sum_j k_ij / m_i = 24 k / m (12 springs), h = 2 / w.
            h_crude = [2 / math.sqrt(24 * k / m) for k in ks]
            # accuracy.md, measured on a pinned planar grid with bend springs: h_crit = 0.64 sqrt(m/k).
            h_meas = [0.64 * math.sqrt(m / k) for k in ks]
            if lab == "mass_spring_1substep":
                ax.plot(ks, h_crude, "k-", lw=1, label="h = 2/w_max (crude bound)")
                ax.plot(ks, h_meas, "k--", lw=1, label="h_crit = 0.64 sqrt(m/k)")
            else:
                # With automatic substeps the substep is dt / substeps; the cap of 1000 substeps
                # makes the frame dt limit 1000 x h_crit.
                ax.plot(ks, [1000 * h for h in h_crude], "k-", lw=1, label="1000 x 2/w_max (substep cap)")
            ax.legend(fontsize=6, loc="lower left")
            ax.set_ylim(1e-3, 0.2)
    fig.suptitle(f"S1 stability map ({n}^2 cloth, {mass} kg, damping 0; green survived, red failed with "
                 "time of failure): Verlet limit overlaid on MASS_SPRING", fontsize=9)
    fig.text(0.01, 0.01, machine_note(meta), fontsize=6)
    fig.tight_layout(rect=(0, 0.04, 1, 0.94))
    fig.savefig(os.path.join(out, "stability_map.png"), dpi=110)
    plt.close(fig)

    lines.append("## Stress (accuracy.md S1 S2 S3 S5 S7 S10)\n")
    lines.append("Failure = the library rolled a step back (non-finite or strain > 10), non-finite output, speed > "
                 "10 x (sqrt(2 g H) + speed from the initial stored energy), bounding box > 10x initial, or energy growth "
                 "> 0.5 x (M g H + energy stored at the start) beyond the work put in. The energy is what the model "
                 "stores: kinetic + gravity, plus for MASS_SPRING and IMPLICIT the springs' 1/2 k (l - L0)^2 over the "
                 "simulated 12-spring table at the model's k (they apply exactly F = k (l - L0)). XPBD stores its "
                 "compliance energy 1/2 alpha |lambda/h^2|^2, which equals 1/2 k C^2 only for a converged solve (with a "
                 "few passes per substep its springs act softer, and 1/2 k C^2 of a still, stiff cloth is 1e2-1e4 x M g H); "
                 "drape_stats does not report lambda and PBD defines no spring energy, so for both the springs count as "
                 "0 (>= 0 whatever they store, so kinetic + gravity alone must not exceed the start's energy). Runs with "
                 "a moving kinematic collider (S3 heavy sphere, S8) do work the check cannot count and have no energy "
                 "check; neither has PBD started stretched (S5). Before the table is made, drape_bench checks the "
                 "criterion: a MASS_SPRING cloth stepped above its Verlet stability bound must fail on energy growth "
                 "and a still XPBD cloth at 1e9 N/m must not. The energy_growth column gives the largest growth as a "
                 "fraction of the scale (blank where not checked).\n")
    for lab in labels:
        rs = [r for r in s1 if r["case"] == lab]
        ok = sum(r["survived"] == "1" for r in rs)
        crit = sorted({r["criterion"] for r in rs if r["survived"] != "1"})
        lines.append(f"- S1 `{lab}`: {ok}/{len(rs)} cells survived" + (f"; failures: {', '.join(crit)}" if crit else "") + ".")
    lines.append("")
    lines.append("| test | case | model | dt | substeps | survived | failed at (s) | criterion | max strain | energy growth |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        if r["test"] == "S1":
            continue
        lines.append(f"| {r['test']} | {r['case']} | {r['model']} | {num(r['dt']):.4g} | {r['substeps']} | "
                     f"{'yes' if r['survived'] == '1' else 'no'} | "
                     f"{'' if r['survived'] == '1' else format(num(r['time_to_failure_s']), '.3g')} | {r['criterion']} | "
                     f"{num(r['max_strain']):.3g} | {format(num(r.get('energy_growth')), '.3g') if fin(num(r.get('energy_growth'))) else ''} |")
    lines.append("")
    if s8:
        lines.append("S8 fast sphere (r = 0.1 m) through the hanging cloth's middle, 1 m of travel: largest fraction "
                     "of all vertices inside the sphere or behind it (in its swept disc, on the side it came from):\n")
        lines.append("| speed (m/s) | radii per frame | model | fraction inside/behind | survived |")
        lines.append("|---|---|---|---|---|")
        for r in s8:
            if r["test"] != "S8":
                continue
            lines.append(f"| {r['speed_m_per_s']} | {num(r['speed_m_per_s']) / 60 / 0.1:.1f} | {r['model']} | "
                         f"{num(r['max_fraction_inside_or_behind']):.3f} | {'yes' if r['survived'] == '1' else 'no'} |")
        lines.append("")
        hs = [r for r in s8 if r["test"] == "S3_heavy_sphere"]
        if hs:
            lines.append("S3 heavy sphere: colliders are kinematic in the C API (no two-way coupling), so the heavy "
                         "sphere is one that does not yield: r = 0.15 m, lowered at 0.6 m/s for 1 s into the middle of the "
                         "cloth pinned at its four corners, then held 0.4 m below them (~15% stretch along the "
                         "diagonals, beyond the 10% tether limit). Largest fraction of vertices inside the sphere: " +
                         ", ".join(f"{r['model']} {num(r['max_fraction_inside_or_behind']):.3f}"
                                   f"{'' if r['survived'] == '1' else ' (failed)'}" for r in hs) + ".\n")
    lines.append("S10 max strain column: at the end of the run (not the transient peak); `_no_tethers` rows run with "
                 "max_stretch 0. MASS_SPRING above 64^2 is skipped (hundreds of substeps per frame).\n")
    if s10it:
        lines.append("S10: solver passes per frame (substeps x 1 iteration, the default form, tethers on) needed for "
                     "max strain <= 1% after 1 s hanging (doubling from 16; each size starts at the previous answer):\n")
        lines.append("| model | size | passes per frame | max strain then |")
        lines.append("|---|---|---|---|")
        for r in s10it:
            lines.append(f"| {r['model']} | {r['size']}^2 | "
                         f"{r.get('passes_for_1pct', r.get('iterations_for_1pct')) if r['reached'] == '1' else '> ' + r.get('max_passes', '?')} | "
                         f"{num(r['max_strain_at_that']):.3g} |")
        lines.append("")


def vibration(out, rows, meta, lines):
    if not rows:
        return
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.2))
    for m in MODELS:
        rs = [r for r in rows if r["model"] == m]
        ax = b if m == "pbd" else a
        ok = [r for r in rs if r["survived"] == "1" and fin(num(r["vibration_m"])) and num(r["vibration_m"]) > 0]
        ok.sort(key=lambda r: num(r["structural_stiffness"]))
        if ok:
            ax.plot([num(r["structural_stiffness"]) for r in ok], [num(r["vibration_m"]) for r in ok], marker="o",
                    color=COLOURS[m], label=m)
        # Values a log axis cannot show go on its edges (x in data, y in axes coordinates), not at
        # made-up heights: exactly 0 on the bottom edge, failed runs on the top edge.
        zero = [r for r in rs if r["survived"] == "1" and num(r["vibration_m"]) == 0]
        if zero:
            ax.scatter([num(r["structural_stiffness"]) for r in zero], [0.03] * len(zero), marker="v", color=COLOURS[m],
                       transform=ax.get_xaxis_transform(), label=f"{m}: exactly 0 (bottom edge)")
        bad = [r for r in rs if r["survived"] != "1" or not fin(num(r["vibration_m"]))]
        if bad:
            ax.scatter([num(r["structural_stiffness"]) for r in bad], [0.97] * len(bad), marker="x", s=50,
                       color=COLOURS[m], transform=ax.get_xaxis_transform(), label=f"{m}: failed (top edge)")
    for ax, xl in ((a, "structural stiffness (N/m; shear, bend = 1/2, 1/10 of it)"), (b, "PBD structural stiffness fraction")):
        if ax.lines or ax.collections:  # a partial run may have no rows for a panel
            log_axes(ax)
            ax.legend(fontsize=7)
        else:
            ax.text(0.5, 0.5, "no rows in vibration.csv", transform=ax.transAxes, ha="center", va="center",
                    fontsize=8, color="grey")
        ax.set_xlabel(xl)
        ax.set_ylabel("vibration: mean |x_t - x_{t-1}| of the middle vertex (m)")
        ax.grid(True, which="both", alpha=0.3)
    n = meta.get("vibration_grid", "16")
    fig.suptitle(f"Vibration at rest vs stiffness (paper Fig. 7): {n}^2 cloth falls from horizontal, hangs from two "
                 "corners, air drag 2/s, measured over " + ("0.25 s after 1 s" if meta.get("mode") == "quick" else "1 s after 5 s")
                 + " of settling", fontsize=9)
    fig.text(0.01, 0.01, machine_note(meta), fontsize=6)
    fig.tight_layout(rect=(0, 0.04, 1, 0.94))
    fig.savefig(os.path.join(out, "fig7_vibration.png"), dpi=110)
    plt.close(fig)
    lines.append("## Vibration at rest (paper Fig. 7)\n")
    lines.append("| model | structural stiffness | substeps | vibration (m/step) | survived |")
    lines.append("|---|---|---|---|---|")
    for r in rows:
        lines.append(f"| {r['model']} | {num(r['structural_stiffness']):.4g} | {r['substeps']} | {num(r['vibration_m']):.3g} | "
                     f"{'yes' if r['survived'] == '1' else 'no: ' + r['criterion']} |")
    lines.append("")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "bench-out"
    meta = {r["key"]: r["value"] for r in read(out, "meta.csv")}
    lines = ["# Drape benchmark report\n",
             f"Machine: {machine_note(meta)}. Backends available: {meta.get('backends', '?')}. "
             f"Run time {num(meta.get('seconds', 'nan')):.0f} s. All numbers come from this one run; timings are "
             "medians of repeated steps on a machine shared with other engineers' builds, so they move between runs "
             "(compare ratios within a run). Plots: fig6_step_time.png, threads.png, precision_*.png, curtain_vs_jolt.png, "
             "stiff_under_load.png, fall.png, stability_map.png, fig7_vibration.png.\n"]
    sections = [
        lambda: fig6(out, read(out, "throughput.csv"), meta, lines),
        lambda: threads(out, read(out, "threads.csv"), read(out, "threads_rounds.csv"), meta, lines),
        lambda: precision(out, read(out, "precision.csv"), read(out, "reference.csv"), meta, lines),
        lambda: rest(out, read(out, "rest.csv"), meta, lines),
        lambda: curtain_vs_jolt(out, read(out, "rest.csv"), meta, lines),
        lambda: stiff_under_load(out, read(out, "stiff_under_load.csv"), meta, lines),
        lambda: fall(out, read(out, "fall.csv"), meta, lines),
        lambda: stress(out, read(out, "stress.csv"), read(out, "s10_iterations.csv"), read(out, "s8_colliders.csv"),
                       meta, lines),
        lambda: vibration(out, read(out, "vibration.csv"), meta, lines),
    ]
    failed = 0
    for section in sections:
        try:
            section()
        except Exception as e:  # one bad plot (e.g. a partial run) must not lose the rest of the report
            failed += 1
            plt.close("all")
            lines.append(f"(a section failed to plot: {type(e).__name__}: {e})\n")
            print(f"plot.py: warning: {type(e).__name__}: {e}", file=sys.stderr)
    with open(os.path.join(out, "REPORT.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    if failed:
        print(f"plot.py: {failed} section(s) failed", file=sys.stderr)
    print(f"plot.py: wrote {out}/REPORT.md and {len([p for p in os.listdir(out) if p.endswith('.png')])} PNGs")


if __name__ == "__main__":
    main()
