#!/usr/bin/python3
"""The grasp study's report: tables and plots from grasp_study's trials (scripts/study).

  study_report.py TRIALS.json TIMELINE_DIR OUT_DIR --command "..." [--wall-s S]

Writes OUT_DIR/results.md, OUT_DIR/results.json and OUT_DIR/*.png. Everything but the header
(date, machine, wall time) follows from the trials: the same seed gives the same tables.
Debian's python3-matplotlib (scripts/setup installs it).
"""
import argparse
import json
import math
import os
import platform
import statistics
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

RULE_LABELS = {
    "strict": "(a) strict",
    "relaxed": "(b) relaxed",
    "relaxed_gesture": "(c) relaxed + gesture",
    "default": "(d) project default",
    "default_paper_gesture": "(e) project, paper's gesture reading",
}
RULE_COLORS = {"strict": "#8c564b", "relaxed": "#d62728", "relaxed_gesture": "#1f77b4",
               "default": "#2ca02c", "default_paper_gesture": "#9467bd"}
# where a failed trial failed (bench/study/grasp_trial.hpp), in order
FAILURES = ["never grasped", "lost while held", "dropped", "misplaced", "wrong changes"]
FAILURE_COLORS = ["#7f7f7f", "#d62728", "#ff7f0e", "#bcbd22", "#17becf"]


def percentile(values, q):
    """Linear-interpolated percentile (q in [0, 100]) of a non-empty list."""
    v = sorted(values)
    if len(v) == 1:
        return v[0]
    pos = (len(v) - 1) * q / 100.0
    lo = math.floor(pos)
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (pos - lo)


def summary(values):
    """mean, p50, p90 and the 95 % confidence interval of the mean (normal approximation)."""
    if not values:
        return {"n": 0, "mean": None, "p50": None, "p90": None, "ci95": [None, None]}
    mean = statistics.fmean(values)
    half = 1.96 * statistics.stdev(values) / math.sqrt(len(values)) if len(values) > 1 else 0.0
    return {"n": len(values), "mean": mean, "p50": percentile(values, 50),
            "p90": percentile(values, 90), "ci95": [mean - half, mean + half]}


def proportion(successes, n):
    """Share and its Wilson 95 % interval."""
    if n == 0:
        return {"n": 0, "share": None, "ci95": [None, None]}
    z = 1.96
    p = successes / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return {"n": n, "successes": successes, "share": p,
            "ci95": [max(0.0, centre - half), min(1.0, centre + half)]}


def rule_metrics(trials):
    res = [t["result"] for t in trials]
    grasped = [r for r in res if r["grasped"]]
    lifted = [r for r in res if r["lifted"]]
    loose = [r for r in res if not r.get("control_case", False)]  # no drops or depth for controls
    return {
        "trials": len(res),
        "success": proportion(sum(r["success"] for r in res), len(res)),
        "grasped": proportion(len(grasped), len(res)),
        "convergence_s": summary([r["convergence_s"] for r in grasped if r["convergence_s"] >= 0]),
        "switch_rate_hz": summary([r["switch_rate_hz"] for r in res]),
        "hand_pen_max_mm": summary([r["hand_pen_max_mm"] for r in res]),
        "hand_pen_mean_mm": summary([r["hand_pen_mean_mm"] for r in res]),
        "object_pen_max_mm": summary([r["object_pen_max_mm"] for r in loose]),
        "object_pen_mean_mm": summary([r["object_pen_mean_mm"] for r in loose]),
        "drops_per_trial": summary([float(r["drops"]) for r in loose]),
        "trials_with_drop": proportion(sum(1 for r in loose if r["drops"] > 0), len(loose)),
        "place_error_mm": summary([r["place_error_mm"] for r in lifted]),
    }


def fmt(x, digits=2):
    return "–" if x is None else f"{x:.{digits}f}"


def fmt_summary(s, digits=2):
    if s["n"] == 0:
        return "–"
    return (f"{fmt(s['mean'], digits)} [{fmt(s['ci95'][0], digits)}, {fmt(s['ci95'][1], digits)}]"
            f" · p50 {fmt(s['p50'], digits)} · p90 {fmt(s['p90'], digits)}")


def fmt_share(p):
    if p["n"] == 0:
        return "–"
    return (f"{100 * p['share']:.0f} % [{100 * p['ci95'][0]:.0f}, {100 * p['ci95'][1]:.0f}]"
            f" ({p['successes']}/{p['n']})")


def machine_line():
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{platform.system()} {platform.release()}, {os.cpu_count()} cores, {cpu}"


def commit_line():
    try:
        rev = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                             text=True, check=True).stdout.strip()
        # the report's own outputs do not count (they are written before this is asked)
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no", "--",
                                ".", ":(exclude)docs/study"],
                               capture_output=True, text=True, check=True).stdout.strip()
        return rev + (" (with uncommitted changes)" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def plot_rules(compared, metrics, path):
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2))
    names = [RULE_LABELS[r] for r in compared]
    colors = [RULE_COLORS[r] for r in compared]
    x = range(len(compared))

    def bars(ax, values, lo, hi, title, ylabel):
        err = [[max(0.0, v - l) for v, l in zip(values, lo)], [max(0.0, h - v) for v, h in zip(values, hi)]]
        ax.bar(x, values, color=colors, yerr=err, capsize=4)
        ax.set_xticks(list(x), names, rotation=20, ha="right", fontsize=8)
        ax.set_title(title, fontsize=10)
        ax.set_ylabel(ylabel)

    succ = [100 * metrics[r]["success"]["share"] for r in compared]
    bars(axes[0], succ, [100 * metrics[r]["success"]["ci95"][0] for r in compared],
         [100 * metrics[r]["success"]["ci95"][1] for r in compared],
         "success", "% of trials")
    axes[0].set_ylim(0, 100)
    conv = [metrics[r]["convergence_s"]["mean"] or 0.0 for r in compared]
    bars(axes[1], conv, [metrics[r]["convergence_s"]["ci95"][0] or 0.0 for r in compared],
         [metrics[r]["convergence_s"]["ci95"][1] or 0.0 for r in compared],
         "first contact → stable grasp (grasped trials)", "s (mean, 95 % CI)")
    chatter = [metrics[r]["switch_rate_hz"]["mean"] for r in compared]
    bars(axes[2], chatter, [metrics[r]["switch_rate_hz"]["ci95"][0] for r in compared],
         [metrics[r]["switch_rate_hz"]["ci95"][1] for r in compared],
         "grasp-state switches while the fingers are closed", "per second (mean, 95 % CI)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_penetration(compared, by_rule, path):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    names = [RULE_LABELS[r] for r in compared]
    for ax, key, title in ((axes[0], "hand_pen_max_mm", "hand link into the object (max per trial)"),
                           (axes[1], "object_pen_max_mm", "object into other bodies (max per trial)")):
        data = [[t["result"][key] for t in by_rule[r]] for r in compared]
        parts = ax.boxplot(data, labels=names, patch_artist=True, showfliers=True)
        for patch, r in zip(parts["boxes"], compared):
            patch.set_facecolor(RULE_COLORS[r])
            patch.set_alpha(0.6)
        ax.set_title(title, fontsize=10)
        ax.set_ylabel("mm")
        ax.tick_params(axis="x", labelrotation=20, labelsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_sweeps(sweeps, path):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for ax, group, xlabel, logx in ((axes[0], "alpha0", "α0 (deg)", False),
                                    (axes[1], "xi", "ξ (N), η = 0.1 m × ξ", True)):
        points = sweeps.get(group, [])
        if not points:
            continue
        xs = [p["value"] for p in points]
        succ = [100 * p["metrics"]["success"]["share"] for p in points]
        lo = [100 * p["metrics"]["success"]["ci95"][0] for p in points]
        hi = [100 * p["metrics"]["success"]["ci95"][1] for p in points]
        ax.plot(xs, succ, "o-", color="#1f77b4", label="success %")
        ax.fill_between(xs, lo, hi, color="#1f77b4", alpha=0.15)
        ax.set_ylim(0, 100)
        ax.set_xlabel(xlabel)
        ax.set_ylabel("success % (95 % CI)", color="#1f77b4")
        if logx:
            ax.set_xscale("log")
        ax2 = ax.twinx()
        ax2.plot(xs, [p["metrics"]["switch_rate_hz"]["mean"] for p in points], "s--",
                 color="#d62728", label="switches/s")
        ax2.set_ylabel("grasp-state switches per second", color="#d62728")
        ax2.set_ylim(bottom=0)
        ax.set_title(f"rule (c) with {xlabel.split(' ')[0]} swept", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def read_timeline(path):
    rows = []
    with open(path) as f:
        header = f.readline().strip().split(",")
        for line in f:
            rows.append(dict(zip(header, line.strip().split(","))))
    return rows


def plot_timeline(timeline_dir, rules, path, strict_xi, shipped):
    shown = [r for r in ("relaxed", "default") if os.path.exists(f"{timeline_dir}/timeline_{r}.csv")]
    if not shown:
        return False
    fig, axes = plt.subplots(4, len(shown), figsize=(6 * len(shown), 8), sharex=True, squeeze=False)
    for col, rule in enumerate(shown):
        rows = read_timeline(f"{timeline_dir}/timeline_{rule}.csv")
        t = [float(r["t_s"]) for r in rows]
        params = rules[rule]["params"]
        axes[0][col].step(t, [int(r["links"]) for r in rows], where="post", color="k")
        axes[0][col].set_ylabel("links on the cup")
        axes[0][col].set_title(RULE_LABELS[rule] + ": the first cup trial", fontsize=10)
        axes[1][col].plot(t, [float(r["residual_force_N"]) for r in rows], color="#1f77b4")
        axes[1][col].axhline(params["xi_N"], color="#1f77b4", ls=":", label="ξ")
        if params["exit_scale"] > 1:  # the looser test while held
            axes[1][col].axhline(params["xi_N"] * params["exit_scale"], color="#1f77b4", ls="--",
                                 lw=0.8)
        axes[1][col].set_ylabel("|ΣF| (N)")
        axes[1][col].set_ylim(0, 3 * params["xi_N"] * params["exit_scale"])
        axes[2][col].plot(t, [float(r["residual_torque_Nm"]) for r in rows], color="#ff7f0e")
        axes[2][col].axhline(params["eta_Nm"], color="#ff7f0e", ls=":", label="η")
        if params["exit_scale"] > 1:
            axes[2][col].axhline(params["eta_Nm"] * params["exit_scale"], color="#ff7f0e", ls="--",
                                 lw=0.8)
        axes[2][col].set_ylabel("|ΣM| (N m)")
        axes[2][col].set_ylim(0, 3 * params["eta_Nm"] * params["exit_scale"])
        axes[3][col].step(t, [int(r["held"]) for r in rows], where="post", color="#2ca02c",
                          label="held")
        axes[3][col].plot(t, [(float(r["z_m"]) - float(rows[0]["z_m"])) * 10 for r in rows],
                          color="#7f7f7f", label="height × 10 (m)")
        axes[3][col].set_ylabel("held / height")
        axes[3][col].set_xlabel("t (s)")
        axes[3][col].legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return True


def plot_failures(compared, by_rule, objects, path):
    # one panel per rule: for each object, its failed trials by where they failed
    fig, axes = plt.subplots(1, len(compared), figsize=(3.2 * len(compared), 3.6), sharey=True)
    for ax, name in zip(axes, compared):
        bottom = [0] * len(objects)
        for kind, color in zip(FAILURES, FAILURE_COLORS):
            counts = [sum(1 for t in by_rule.get(name, [])
                          if t["object"] == o and not t["result"]["success"]
                          and t["result"].get("failure") == kind)
                      for o in objects]
            ax.bar(range(len(objects)), counts, bottom=bottom, color=color, label=kind)
            bottom = [b + c for b, c in zip(bottom, counts)]
        ax.set_xticks(range(len(objects)))
        ax.set_xticklabels(objects, rotation=60, ha="right", fontsize=7)
        ax.set_title(RULE_LABELS.get(name, name), fontsize=8)
    axes[0].set_ylabel("failed trials")
    axes[-1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path + ".tmp.png", dpi=110)
    plt.close(fig)
    os.replace(path + ".tmp.png", path)


def gesture_text(p):
    rule = p["gesture_rule"]
    if rule is False or rule == "none":
        return "none"
    reading = "project's reading" if rule in (True, "project") else "paper's reading"
    return f"> 2 links, thumb, α0 {p['alpha0_deg']:g}° ({reading})"


def additions_text(name, p):
    if p.get("hold_rule") != "grip":
        return "none: one test decides grasp and release every step"
    return (f"held until the tracked hand lets go (opened by {p['release_opening_share']:g} of its "
            f"grasp flexion and ≥ {p['release_opening_deg']:g}°, or its thumb or opposed fingers "
            f"{p['release_gap_m'] * 100:g} cm off the object), hold {p['min_hold_s']:g} s, "
            f"release delay {p['release_delay_s']:g} s, cooldown {p['regrab_cooldown_s']:g} s, "
            f"palm opposition")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("trials")
    ap.add_argument("timeline_dir")
    ap.add_argument("out_dir")
    ap.add_argument("--command", default="scripts/study")
    args = ap.parse_args()
    with open(args.trials) as f:
        doc = json.load(f)
    os.makedirs(args.out_dir, exist_ok=True)
    rules = {r["name"]: r for r in doc["rules"]}
    by_rule = {}
    for t in doc["trials"]:
        by_rule.setdefault(t["rule"], []).append(t)
    compared = [r["name"] for r in doc["rules"] if r["group"] == "rules"]
    metrics = {name: rule_metrics(by_rule.get(name, [])) for name in rules}
    objects = [o["name"] for o in doc["objects"]]
    per_object = {name: {o: rule_metrics([t for t in by_rule.get(name, []) if t["object"] == o])
                         for o in objects} for name in compared}
    sweeps = {}
    for r in doc["rules"]:
        if r["group"] != "rules":
            sweeps.setdefault(r["group"], []).append({"name": r["name"], "value": r["value"],
                                                      "metrics": metrics[r["name"]]})
    shipped = rules["default"]["params"]

    plot_rules(compared, metrics, f"{args.out_dir}/rules.png")
    plot_penetration(compared, by_rule, f"{args.out_dir}/penetration.png")
    plot_failures(compared, by_rule, objects, f"{args.out_dir}/failures.png")
    if sweeps:
        plot_sweeps(sweeps, f"{args.out_dir}/sweeps.png")
    have_timeline = plot_timeline(args.timeline_dir, rules, f"{args.out_dir}/timeline.png",
                                  doc["strict"]["xi_N"], shipped)

    out = {"seed": doc["seed"], "trials_per_object": doc["trials_per_object"],
           "sweep_trials_per_object": doc["sweep_trials_per_object"], "objects": objects,
           "rules": doc["rules"], "metrics": metrics, "per_object": per_object,
           "sweeps": sweeps}
    with open(f"{args.out_dir}/results.json.tmp", "w") as f:
        json.dump(out, f, indent=1, sort_keys=True)
        f.write("\n")
    os.replace(f"{args.out_dir}/results.json.tmp", f"{args.out_dir}/results.json")

    n_total = len(doc["trials"])
    md = []
    md.append("# The grasp study: strict vs relaxed vs relaxed + gesture vs the project's rule, in "
              "both readings of the gesture constraint\n")
    md.append(f"- Command: `{args.command}`")
    md.append(f"- Commit: {commit_line()}")
    md.append(f"- Machine: {machine_line()}")
    md.append(f"- Seed {doc['seed']}: {n_total} trials, {doc['trials_per_object']} per object "
              f"and compared rule ({len(objects)} objects: {', '.join(objects)}), "
              f"{doc['sweep_trials_per_object']} per object at each sweep point; "
              f"{doc['wall_s']:.0f} s of wall time")
    md.append("- Made by `scripts/study` (bench/study/, scripts/study_report.py); the same seed "
              "gives the same tables (only this header changes).\n")
    md.append("## The rules\n")
    md.append("| rule | eqs. 30-31 | gesture rule | additions |")
    md.append("|---|---|---|---|")
    for name in compared:
        p = rules[name]["params"]
        gesture = gesture_text(p)
        additions = additions_text(name, p)
        md.append(f"| {RULE_LABELS[name]} | ξ {p['xi_N']:g} N, η {p['eta_Nm']:g} N m | {gesture} | "
                  f"{additions} |")
    md.append("")
    md.append("The paper gives no values for ξ and η; (b)-(d) use the project's (config/cockpit.yaml), "
              f"and (a) takes ξ {doc['strict']['xi_N']:g} N and η {doc['strict']['eta_Nm']:g} N m "
              "(5 % of the cup's weight) for \"near zero\". Every rule runs the same trials: trial i "
              "of an object has the same hand size, approach, aperture, closing time and glove input "
              "under each rule.\n")
    md.append("## Headline\n")
    md.append("Mean [95 % CI] · p50 · p90 over the trials (convergence: over the grasped trials; "
              "placement error: over the lifted ones). The controls' rows (knobs, levers) count in "
              "every metric but the loose objects' own: drops, depth into other bodies, "
              "placement.\n")
    md.append("| metric | " + " | ".join(RULE_LABELS[r] for r in compared) + " |")
    md.append("|---|" + "---|" * len(compared))
    rows = [
        ("success (objects: lifted ≥ 5 cm, placed ≤ 3 cm, released; controls: exactly the "
         "gesture's changes)", lambda m: fmt_share(m["success"])),
        ("grasped at all", lambda m: fmt_share(m["grasped"])),
        ("first contact → grasp (s)", lambda m: fmt_summary(m["convergence_s"])),
        ("grasp-state switches per s, fingers closed", lambda m: fmt_summary(m["switch_rate_hz"])),
        ("hand into object, max (mm)", lambda m: fmt_summary(m["hand_pen_max_mm"])),
        ("hand into object, mean (mm)", lambda m: fmt_summary(m["hand_pen_mean_mm"])),
        ("object into others, max (mm; loose objects)", lambda m: fmt_summary(m["object_pen_max_mm"])),
        ("object into others, mean (mm; loose objects)", lambda m: fmt_summary(m["object_pen_mean_mm"])),
        ("loose-object trials with a drop", lambda m: fmt_share(m["trials_with_drop"])),
        ("placement error (mm)", lambda m: fmt_summary(m["place_error_mm"], 1)),
    ]
    for label, cell in rows:
        md.append(f"| {label} | " + " | ".join(cell(metrics[r]) for r in compared) + " |")
    md.append("")
    md.append("![success, convergence and chatter per rule](rules.png)\n")
    md.append("![penetration per rule](penetration.png)\n")
    md.append("## Success per object\n")
    md.append("| object | " + " | ".join(RULE_LABELS[r] for r in compared) + " |")
    md.append("|---|" + "---|" * len(compared))
    for o in objects:
        md.append(f"| {o} | " + " | ".join(fmt_share(per_object[r][o]["success"]) for r in compared) + " |")
    md.append("")
    md.append("## Where the failed trials failed\n")
    md.append("never grasped; lost while held (grasped, let go or slipped before it was lifted "
              "5 cm); dropped (lifted, let go and fallen 2 cm); misplaced (lifted, not dropped, not "
              "set down within 3 cm or still held); a control: wrong changes.\n")
    md.append("| object | " + " | ".join(RULE_LABELS[r] for r in compared) + " |")
    md.append("|---|" + "---|" * len(compared))
    for o in objects:
        cells = []
        for r in compared:
            failed = [t["result"] for t in by_rule.get(r, [])
                      if t["object"] == o and not t["result"]["success"]]
            parts = [f"{sum(1 for t in failed if t.get('failure') == k)} {k}" for k in FAILURES
                     if any(t.get("failure") == k for t in failed)]
            cells.append(", ".join(parts) if parts else "—")
        md.append(f"| {o} | " + " | ".join(cells) + " |")
    md.append("")
    md.append("![where the failed trials failed](failures.png)\n")
    md.append("## Sweeps of rule (c)\n")
    for group, label, unit in (("alpha0", "α0", "°"), ("xi", "ξ (η = 0.1 m × ξ)", " N")):
        points = sweeps.get(group, [])
        if not points:
            continue
        md.append(f"| {label} | success | first contact → grasp (s) | switches per s | hand into object, max (mm) |")
        md.append("|---|---|---|---|---|")
        for p in points:
            m = p["metrics"]
            md.append(f"| {p['value']:g}{unit} | {fmt_share(m['success'])} | "
                      f"{fmt(m['convergence_s']['p50'])} (p50) | {fmt(m['switch_rate_hz']['mean'])} | "
                      f"{fmt(m['hand_pen_max_mm']['mean'])} |")
        md.append("")
    if sweeps:
        md.append("![the α0 and ξ sweeps](sweeps.png)\n")
    if have_timeline:
        md.append("## One trial's timeline\n")
        md.append("The first cup trial under rule (b) and under the project's rule: hand links on "
                  "the cup, eq. 30's |ΣF| and eq. 31's |ΣM| against their thresholds (dotted; "
                  "dashed: the looser test while held), and whether it is held (every 10 ms).\n")
        md.append("![one trial's timeline](timeline.png)\n")
    md.append("## How a trial is measured\n")
    md.append("Each trial replays an object's gesture script (config/gestures/*_pick_place.yaml; "
              "two_hand_lift_{right,left} for the heavy bar; panel_knobs and pedestal_levers for "
              "the grasped controls) varied by a seed "
              "(bench/study/trial_variation.hpp: approach direction and height, grip aperture, "
              "closing time 0.3-0.8 s, hand size, glove input from clean to harsh) through the "
              "offline runner's replay (SampleValidator, HandTimeline), then 1 s more. "
              "Definitions: bench/study/grasp_trial.hpp.\n")
    with open(f"{args.out_dir}/results.md.tmp", "w") as f:
        f.write("\n".join(md))
    os.replace(f"{args.out_dir}/results.md.tmp", f"{args.out_dir}/results.md")
    print(f"study_report: {n_total} trials -> {args.out_dir}/results.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
