#!/usr/bin/env python3
"""Reads what bench/compare.sh measured in its work folder and prints one Markdown table of
ratios (peer / skyroute), the goals' verdicts and the callgrind profile; also writes it to
WORK/table.md.

Usage: python3 bench/peers_table.py WORK "COMMAND"

Every number comes from a file in WORK (the file names are bench/compare.sh's); nothing is
estimated. Needs numpy.
"""

import datetime
import glob
import json
import math
import os
import platform
import re
import statistics
import subprocess
import sys

import numpy as np

MAPS = [("niendorf", "niendorf-urban"), ("dense", "dense-city")]
PLANNERS = [("prmstar", "PRM*"), ("prmstar-dmv", "PRM* + DubinsMotionValidator"), ("lazyprm", "LazyPRM")]


def load(work, name):
    with open(os.path.join(work, name)) as f:
        return json.load(f)


def rank(xs, q):
    """Nearest-rank quantile, as the Rust and C++ sides compute it."""
    v = sorted(xs)
    return v[max(1, math.ceil(q * len(v))) - 1] if v else float("nan")


def ms(x):
    return f"{x * 1e3:.3g}"


def ratio(a, b):
    return f"{a / b:.3g}" if b else "—"


def machine():
    model = "?"
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        model = re.search(r"Model name:\s*(.+)", out).group(1).strip()
    except (OSError, AttributeError):
        pass
    return f"`nproc` {os.cpu_count()}, `lscpu` model {model}, {platform.system()} {platform.release()}"


def query_rows(work, key, title, verdicts, notes):
    """The rows of one map's query comparison: skyroute against each OMPL configuration."""
    info = load(work, f"{key}.info.json")
    ours = load(work, f"{key}.plan.json")
    build = load(work, f"{key}.build.json")["median_s"]
    oq = ours["queries"]
    n_ours = ours["summary"]["solved"]
    t_ours = [q["plan_median_s"] for q in oq]
    q_ours = [rank(t_ours, 0.5), rank(t_ours, 0.9), max(t_ours)]
    runs = {pkey: load(work, f"{key}.{pkey}.json") for pkey, _ in PLANNERS}
    checks = {pkey: load(work, f"{key}.{pkey}.check.json") for pkey, _ in PLANNERS}
    rows = [(f"{title}: vertices / edges", f"{info['vertices']} / {info['edges']} directed",
             ", ".join(f"{name} {int(runs[k]['milestones'])} / {int(runs[k]['edges'])}" for k, name in PLANNERS
                       if k != "prmstar-dmv") + " undirected", "")]
    for pkey, name in PLANNERS:
        o = runs[pkey]
        checked = f"{o['build_state_checks'] / 1e6:.1f} M state checks" if o["build_state_checks"] else "no checks"
        rows.append((f"{title}: roadmap construction, s: {name}", f"{build:.3g}", f"{o['build_s']:.3g} ({checked})",
                     ratio(o["build_s"], build)))
    for pkey, name in PLANNERS:
        t = [q["solve_s"] for q in runs[pkey]["queries"]]
        q = [rank(t, 0.5), rank(t, 0.9), max(t)]
        rows.append((f"{title}: query median / p90 / max, ms: {name}", " / ".join(ms(x) for x in q_ours),
                     " / ".join(ms(x) for x in q), " / ".join(ratio(a, b) for a, b in zip(q, q_ours))))
        if pkey.startswith("prmstar"):
            verdicts.append((f"{title}: our median query ≥ 100× faster than OMPL C++ {name}",
                             f"{q[0] / q_ours[0]:.0f}×", q[0] / q_ours[0] >= 100))
    verdicts.append((f"{title}: our query max / median ≤ 1.5", f"{q_ours[2] / q_ours[0]:.2f}", q_ours[2] / q_ours[0] <= 1.5))
    solved = {k: [q for q in runs[k]["queries"] if q["solved"]] for k, _ in PLANNERS}
    rows.append((f"{title}: solved of {len(oq)}", f"{n_ours}",
                 ", ".join(f"{name} {len(solved[k])}" for k, name in PLANNERS), ""))
    hits = {k: {(int(r["route"][0]), r["route"][2]): r["conflicting_motions"] > 0 for r in checks[k]} for k, _ in PLANNERS}
    cells = []
    for pkey, name in PLANNERS:
        counts = []
        for kind in ("raw", "simplified"):
            exact = sum(1 for q in solved[pkey] if hits[pkey].get((q["query"], kind)))
            dense = sum(1 for q in solved[pkey] if q[f"{kind}_dense_blocked_points"] > 0)
            own = sum(1 for q in solved[pkey] if q[f"{kind}_rejected_motions"] > 0)
            counts.append(f"{exact}" if exact == dense == own else f"{exact} (dense {dense}, OMPL's validator {own})")
        rejected = sum(q[f"{k}_rejected_motions"] for q in solved[pkey] for k in ("raw", "simplified"))
        reversed_ok = sum(q[f"{k}_rejected_motions_valid_reversed"] for q in solved[pkey] for k in ("raw", "simplified"))
        cells.append(f"{name} {counts[0]} / {counts[1]} of {len(solved[pkey])} ({reversed_ok} of the "
                     f"{rejected} motions OMPL rejects in flight pass its check the other way round)")
    clear_ours = sum(1 for q in oq if q["exactly_clear"])
    rows.append((f"{title}: routes that come within the clearance, raw / simplified (exact check with skyroute's "
                 "predicates; the 0.1 m dense check and OMPL's own motion validator in the direction of flight agree "
                 "unless noted)", f"{n_ours - clear_ours} of {n_ours}", "; ".join(cells), ""))
    same = open(os.path.join(work, f"{key}.prmstar.routes.txt")).read() == \
        open(os.path.join(work, f"{key}.prmstar-dmv.routes.txt")).read()
    if same:
        notes.append(f"{title}: PRM* with DubinsMotionValidator returned the same routes as with "
                     "DiscreteMotionValidator (same roadmap, same checks, other interpolation cost)")
    for pkey, name in PLANNERS:
        if pkey == "prmstar-dmv" and same:
            continue
        byq = {q["query"]: q for q in solved[pkey]}
        both = [(a, byq[a["query"]]) for a in oq if a["solved"] and a["query"] in byq]
        cells = []
        for mine, theirs, label in (("final_length_m", "simplified_length_m", "simplified / ours post-processed"),
                                    ("planned_length_m", "raw_length_m", "raw / ours as planned")):
            r = [b[theirs] / a[mine] for a, b in both]
            longer = sum(1 for x in r if x < 1 - 1e-6)
            cells.append(f"{label} {statistics.median(r):.3f} (ours longer in {longer} of {len(r)})")
            if mine == "final_length_m":
                verdicts.append((f"{title}: our routes at most as long as {name}'s (post-processed vs simplified)",
                                 f"longer in {longer} of {len(r)}", longer == 0))
        clear = [(a, b) for a, b in both if not hits[pkey].get((b["query"], "simplified"), True)]
        if clear:
            r = [b["simplified_length_m"] / a["final_length_m"] for a, b in clear]
            cells.append(f"clear simplified routes only {statistics.median(r):.3f} "
                         f"(ours longer in {sum(1 for x in r if x < 1 - 1e-6)} of {len(r)})")
        rows.append((f"{title}: route length, median OMPL / ours: {name}", "", "; ".join(cells), ""))
    v = load(work, f"{key}.validity.json")
    rows.append((f"{title}: C++ point checker against skyroute's verdicts", "",
                 f"{int(v['disagreements'])} of {int(v['points'])} points differ (at most "
                 f"{v['disagreement_max_offset_from_contour_m'] * 1e3:.3g} mm from the contour)", ""))
    return rows


def dubins_ir(work, name, pairs=100_000, passes=2):
    """Instructions per path of one solver's callgrind run (one timed pass and the lengths pass)."""
    with open(os.path.join(work, "cg", f"dubins.{name}.out")) as f:
        total = int(re.search(r"^(?:summary|totals):\s*(\d+)", f.read(), re.M).group(1))
    return total / (pairs * passes)


def dubins_rows(work, notes):
    o = load(work, "dubins.ours.json")
    m = load(work, "dubins.ompl.json")
    w = load(work, "dubins.walker.json")
    lo = np.fromfile(os.path.join(work, "dubins.ours.bin"))
    lm = np.fromfile(os.path.join(work, "dubins.ompl.bin"))
    lw = np.fromfile(os.path.join(work, "dubins.walker.bin"))
    pairs = np.fromfile(os.path.join(work, "pairs.bin")).reshape(-1, 6)
    n = len(lo)
    d = np.abs(lo - lm)
    big = np.where(d > 1.0)[0]
    rest = np.delete(d, big)
    ir = {k: dubins_ir(work, k) for k in ("ours", "ompl", "walker")}
    rows = [
        (f"Dubins shortest path, ns per path ({n} pairs, median of 5 passes)", f"{o['ns_per_path_median']:.0f}", f"OMPL {m['ns_per_path_median']:.0f}", ratio(m["ns_per_path_median"], o["ns_per_path_median"])),
        ("", "", f"Walker dubins.c {w['ns_per_path_median']:.0f}", ratio(w["ns_per_path_median"], o["ns_per_path_median"])),
        ("Dubins shortest path, instructions per path (callgrind, 100 000 pairs)", f"{ir['ours']:.0f}", f"OMPL {ir['ompl']:.0f}", ratio(ir["ompl"], ir["ours"])),
        ("", "", f"Walker dubins.c {ir['walker']:.0f}", ratio(ir["walker"], ir["ours"])),
        ("Dubins: largest absolute length difference, ours (f32) − OMPL (f64)", f"{d.max():.4g} m", f"{len(big)} pairs differ by > 1 m", ""),
        ("Dubins: the same without those pairs", f"{rest.max() * 1e3:.3g} mm ({(rest / np.delete(lm, big)).max():.2g} relative)", "", ""),
        ("Dubins: largest absolute length difference, OMPL − Walker (both f64)", "", f"{np.abs(lm - lw).max():.3g} m", ""),
    ]
    r = load(work, "dubins.ours.json")["radius_m"]
    for i in big:
        x0, y0, h0, x1, y1, h1 = pairs[i]
        gaps = []
        for k1, k3 in ((1, -1), (-1, 1)):  # LSR, RSL: their circles must be >= 2r apart
            c1 = (x0 - k1 * r * math.sin(h0), y0 + k1 * r * math.cos(h0))
            c3 = (x1 - k3 * r * math.sin(h1), y1 + k3 * r * math.cos(h1))
            gaps.append(math.hypot(c3[0] - c1[0], c3[1] - c1[1]) - 2 * r)
        g = min(gaps, key=abs)
        notes.append(f"Dubins pair {i}: ours {lo[i]:.2f} m, OMPL {lm[i]:.2f} m, Walker {lw[i]:.2f} m; the circles of "
                     f"its LSR/RSL word are {g * 1e3:+.3f} mm from touching (2r apart) in f64")
    return rows


def sssp_rows(work):
    rows = []
    for key, title in (("niendorf", "niendorf-urban roadmap"), ("jacksboro", "medeiros-jacksboro terrain")):
        s = load(work, f"{key}.sssp.json")
        sp = load(work, f"{key}.scipy.json")
        ours = s["ours_s"]["median"]
        rows.append((f"single-source Dijkstra, {title} ({s['vertices']} v, {s['edges']} e), median ms over {len(s['sources'])} sources",
                     ms(ours), f"petgraph {ms(s['petgraph_s']['median'])}", ratio(s["petgraph_s"]["median"], ours)))
        rows.append(("", "", f"SciPy {ms(sp['scipy_s']['median'])}", ratio(sp["scipy_s"]["median"], ours)))
        rows.append((f"single-source distances equal (rel. 1e-5), {title}", "",
                     f"petgraph: {s['petgraph_mismatches']} differ (max rel {s['petgraph_max_rel_diff']:.2g}); "
                     f"SciPy: {sp['mismatches_vs_ours']} differ (max rel {sp['max_rel_diff_vs_ours']:.2g})", ""))
    return rows


def callgrind(work, verdicts, notes):
    files = sorted(glob.glob(os.path.join(work, "cg", "per.out.*")), key=lambda s: int(s.rsplit(".", 1)[1]))
    ir = []
    for f in files:
        with open(f) as fh:
            m = re.search(r"^(?:summary|totals):\s*(\d+)", fh.read(), re.M)
            ir.append(int(m.group(1)))
    plan = load(work, "niendorf.plan.json")["queries"]
    wall = [q["plan_median_s"] for q in plan]
    med = rank(ir, 0.5)
    rows = [("niendorf-urban: query instructions (callgrind Ir) median / p90 / max", f"{med / 1e6:.2f} M / {rank(ir, 0.9) / 1e6:.2f} M / {max(ir) / 1e6:.2f} M", "", ""),
            ("niendorf-urban: query wall time median / p90 / max (same queries)", f"{ms(rank(wall, 0.5))} / {ms(rank(wall, 0.9))} / {ms(max(wall))} ms", "", "")]
    verdicts.append(("niendorf-urban: our query max / median ≤ 1.5 in instructions", f"{max(ir) / med:.2f}", max(ir) / med <= 1.5))
    solved = [(n, q["planned_length_m"]) for n, q in zip(ir, plan) if q["solved"]]
    r = np.corrcoef([n for n, _ in solved], [l for _, l in solved])[0, 1]
    notes.append(f"niendorf-urban: a query's instructions correlate with its planned route length (Pearson r = {r:.2f} "
                 f"over the {len(solved)} solved queries)")
    top = []
    with open(os.path.join(work, "cg", "annotate.txt")) as fh:
        body = fh.read().split("file:function", 1)[-1]
    for line in body.splitlines():
        m = re.match(r"\s*([\d,]+)\s+\(\s*([\d.]+)%\)\s+(.*)", line)
        if not m:
            continue
        name = m.group(3).split(":", 1)[-1].split(" [")[0]
        if "skyroute::" not in name or name in (t[1] for t in top):
            continue
        top.append((m.group(2), name))
    return rows, top[:8], len(ir)


def main():
    work, command = sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else "bench/compare.sh"
    verdicts, notes, rows = [], [], []
    for key, title in MAPS:
        rows += query_rows(work, key, title, verdicts, notes)
    rows += dubins_rows(work, notes)
    rows += sssp_rows(work)
    cg_rows, top, n_ir = callgrind(work, verdicts, notes)
    rows += cg_rows
    out = [f"Measured {datetime.date.today().isoformat()} on {machine()}.", f"Command: `{command}`", "",
           "| comparison | skyroute | peer | peer / skyroute |", "|---|---|---|---|"]
    out += [f"| {a} | {b} | {c} | {d} |" for a, b, c, d in rows]
    out += ["", "Goals:"]
    out += [f"- {what}: {value}: {'met' if ok else 'NOT met'}" for what, value, ok in verdicts]
    if notes:
        out += ["", "Notes:"] + [f"- {n}" for n in notes]
    out += ["", f"Top skyroute functions by inclusive instructions over the {n_ir} niendorf-urban queries (callgrind_annotate --inclusive=yes):"]
    out += [f"- {pct}% `{name}`" for pct, name in top]
    text = "\n".join(out) + "\n"
    with open(os.path.join(work, "table.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
