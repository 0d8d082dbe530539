#!/usr/bin/env python3
"""Turns the raw outputs of scripts/bench into bench/results.md and bench/results.json.

usage: bench_report.py OUT_DIR RESULTS.md RESULTS.json

Every figure is read from a file a benchmark wrote in OUT_DIR; each target says where it stands.
A missing or unreadable input is an error naming the file.
"""
import datetime
import json
import os
import platform
import subprocess
import sys


def median_offline_run(out_dir):
    """The offline runs' summary with the median real-time factor, and every run's factor."""
    runs = sorted((load(out_dir, f"offline_runs/{name}/summary.json")
                   for name in sorted(os.listdir(os.path.join(out_dir, "offline_runs")))
                   if os.path.isdir(os.path.join(out_dir, "offline_runs", name))),
                  key=lambda s: s["realtime_factor"])
    if not runs:
        raise SystemExit(f"{out_dir}/offline_runs: no offline run")
    median = dict(runs[len(runs) // 2])
    median["realtime_factor_runs"] = [r["realtime_factor"] for r in runs]
    return median


def load(out_dir, name):
    path = os.path.join(out_dir, name)
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"bench_report: {path}: {e}")


def machine():
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    mem_gib = 0.0
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemTotal:"):
                    mem_gib = int(line.split()[1]) / 1024 / 1024
    except OSError:
        pass
    os_name = platform.system()
    try:
        with open("/etc/os-release") as f:
            for line in f:
                if line.startswith("PRETTY_NAME="):
                    os_name = line.split("=", 1)[1].strip().strip('"')
    except OSError:
        pass
    return {"cpu": cpu, "cores": os.cpu_count(), "memory_gib": round(mem_gib, 1),
            "os": os_name, "kernel": platform.release()}


def commit():
    def git(*args):
        return subprocess.run(["git", *args], capture_output=True, text=True).stdout.strip()
    sha = git("rev-parse", "--short=12", "HEAD") or "unknown"
    dirty = git("status", "--porcelain", "--untracked-files=no")
    return sha + ("+uncommitted changes" if dirty else "")


SCENES = {0: "cockpit, right hand holding the cup (5 loose objects, 11 controls, left hand idle)",
          10: "cockpit + 10 loose objects (15 loose, 11 controls)",
          100: "cockpit + 100 loose objects (105 loose, 11 controls)",
          300: "cockpit + 300 loose objects (305 loose, 11 controls)",
          500: "cockpit + 500 loose objects (505 loose, 11 controls)"}


def physics_rows(gbench):
    """BM_WorldStep/N/1 (sleeping), BM_WorldStep/N/0 (every object awake) and BM_MujocoStep/N side
    by side; the pile (BM_PileStep/N/S); plus the micro-benchmarks."""
    ours, awake, mujoco, collision, pile, fk = {}, {}, {}, {}, {}, None
    for b in gbench["benchmarks"]:
        if b.get("run_type", "iteration") != "iteration":
            continue
        parts = b["name"].split("/")
        kind = parts[0]
        arg = int(parts[1]) if len(parts) > 1 and parts[1].isdigit() else None
        arg2 = int(parts[2]) if len(parts) > 2 and parts[2].isdigit() else None
        figures = {k: b[k] for k in ("p50_us", "p99_us", "max_us", "contacts",
                                     "dynamic_objects", "pairs", "cup_held", "asleep",
                                     "lowest_z_mm") if k in b}
        mean_us = b["real_time"] * {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}[b["time_unit"]]
        figures["mean_us"] = mean_us
        if kind == "BM_WorldStep":
            (awake if arg2 == 0 else ours)[arg] = figures
        elif kind == "BM_PileStep":
            key = "asleep" if arg2 != 0 else "awake"
            pile[key] = dict(figures, objects=arg)
        elif kind == "BM_MujocoStep":
            mujoco[arg] = figures
        elif kind == "BM_Collision":
            collision[arg] = figures
        elif kind == "BM_HandForwardKinematics":
            fk = {"mean_ns": mean_us * 1e3}
    rows = []
    for n in sorted(ours):
        o, m = ours[n], mujoco.get(n)
        rows.append({"loose_objects": n, "scene": SCENES.get(n, f"{n} loose objects"),
                     "dynamic_objects": int(o.get("dynamic_objects", 0)),
                     "ours": o, "ours_awake": awake.get(n), "mujoco": m,
                     "ratio_p50": o["p50_us"] / m["p50_us"] if m else None,
                     "ratio_p99": o["p99_us"] / m["p99_us"] if m else None,
                     "ratio_awake_p50": (awake[n]["p50_us"] / m["p50_us"]
                                         if m and awake.get(n) else None),
                     "ratio_awake_p99": (awake[n]["p99_us"] / m["p99_us"]
                                         if m and awake.get(n) else None),
                     "collision": collision.get(n)})
    return rows, fk, pile


FOLLOW_RATES = (33, 60, 120, 1000)


def input_rows(out_dir):
    """Step 7: per source rate, the real-time hand lag with the interpolation delay and with none
    (--input-delay 0), and offline on the gesture recorded at that rate, interpolated and with
    each sample taken in one step (--max-gap 0)."""
    rows = []
    for hz in FOLLOW_RATES:
        rt = load(out_dir, f"follow_{hz}_adaptive.json")
        rt0 = load(out_dir, f"follow_{hz}_0.json")
        off = load(out_dir, f"offline_{hz}_gap0.25/summary.json")
        off0 = load(out_dir, f"offline_{hz}_gap0/summary.json")
        rows.append({"rate_hz": hz,
                     "realtime": {k: rt.get(k) for k in ("input_delay_ms", "hand_lag_us",
                                                         "hand_peak_wrist_speed_mps", "input")},
                     "realtime_no_delay": {k: rt0.get(k) for k in ("hand_lag_us",
                                                                   "hand_peak_wrist_speed_mps",
                                                                   "input")},
                     "offline": {k: off.get(k) for k in ("grasps", "releases",
                                                         "hand_peak_wrist_speed_mps",
                                                         "hand_peak_joint_speed_radps")},
                     "offline_each_sample_in_one_step": {
                         k: off0.get(k) for k in ("grasps", "releases", "hand_peak_wrist_speed_mps",
                                                  "hand_peak_joint_speed_radps")}})
    return rows


def status(met):
    return "met" if met else "not met"


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    out_dir, md_path, json_path = sys.argv[1:]
    gbench = load(out_dir, "physics.json")
    floor = load(out_dir, "dds_floor.json")
    rt = load(out_dir, "physics_rt.json")
    ig = load(out_dir, "ig.json")
    ig_video = load(out_dir, "ig_video.json")
    ig_nocache = load(out_dir, "ig_nocache.json")
    tips = {case: load(out_dir, f"tip_{case}.json")
            for case in ("bundled", "typical", "harsh", "real_leap")}
    video = ig_video.get("video", {})
    fps_drop = 100.0 * (1.0 - ig_video["fps"] / ig["fps"]) if ig["fps"] > 0 else 0.0
    rig = load(out_dir, "rig/summary.json")
    rig_fps = rig["frames_rendered"] / rig["wall_s"] if rig.get("wall_s") else 0.0
    rig_novideo = load(out_dir, "rig_novideo/summary.json")
    rig_novideo_fps = (rig_novideo["frames_rendered"] / rig_novideo["wall_s"]
                       if rig_novideo.get("wall_s") else 0.0)
    rig_drop = 100.0 * (1.0 - rig_fps / rig_novideo_fps) if rig_novideo_fps > 0 else 0.0
    offline = median_offline_run(out_dir)
    retarget = load(out_dir, "retarget.json")
    rows, fk, pile = physics_rows(gbench)
    follow = input_rows(out_dir)

    transit = rt["dds_transit_us"]
    floor_transit = floor["dds_transit_us"]
    e2e = rig["glove_to_frame_latency_ms"]
    row500 = next((r for r in rows if r["loose_objects"] == 500), None)
    row300 = next((r for r in rows if r["loose_objects"] == 300), None)
    slower = [r for r in rows if r["ratio_p50"] is not None and
              (r["ratio_p50"] > 1.0 or r["ratio_p99"] > 1.0)]
    # MuJoCo 2.2 has no sleeping: the like-for-like figure is ours with every object awake
    slower_awake = [r for r in rows if r["ratio_awake_p50"] is None or
                    r["ratio_awake_p50"] > 1.0 or r["ratio_awake_p99"] > 1.0]
    pile_asleep, pile_awake = pile.get("asleep"), pile.get("awake")
    pile_share = (pile_asleep["p50_us"] / pile_awake["p50_us"]
                  if pile_asleep and pile_awake else None)
    targets = [
        {"target": "physics step no slower than MuJoCo on the same scene, every object awake "
                   "(p50 and p99; MuJoCo 2.2 has no sleeping)",
         "measured": ", ".join(f"{r['dynamic_objects']} dynamic: {r['ratio_awake_p50']:.2f}x / "
                               f"{r['ratio_awake_p99']:.2f}x"
                               for r in rows if r["ratio_awake_p50"] is not None) or "not run",
         "met": not slower_awake and bool(rows)},
        {"target": "... and with its resting objects asleep (p50 and p99; ours "
                   "with its resting objects asleep, MuJoCo 2.2 has no sleeping)",
         "measured": ", ".join(f"{r['dynamic_objects']} dynamic: {r['ratio_p50']:.2f}x / "
                               f"{r['ratio_p99']:.2f}x"
                               for r in rows if r["ratio_p50"] is not None),
         "met": not slower and bool(rows)},
        {"target": "500 loose objects: one step p99 under 2 ms, every object awake",
         "measured": (f"p50 {row500['ours']['p50_us']:.0f} us, p99 {row500['ours']['p99_us']:.0f} us "
                      f"({row500['ours'].get('asleep', 0):.0f} asleep); every object awake: p50 "
                      f"{row500['ours_awake']['p50_us']:.0f} us, p99 "
                      f"{row500['ours_awake']['p99_us']:.0f} us")
         if row500 and row500.get("ours_awake") else "not run",
         "met": bool(row500) and bool(row500.get("ours_awake")) and
                row500["ours_awake"]["p99_us"] < 2000.0},
        {"target": "300 loose objects, every object awake: one step p99 under 1 ms (the 1 kHz "
                   "loop keeps real time)",
         "measured": (f"p50 {row300['ours_awake']['p50_us']:.0f} us, p99 "
                      f"{row300['ours_awake']['p99_us']:.0f} us")
         if row300 and row300.get("ours_awake") else "not run",
         "met": bool(row300) and bool(row300.get("ours_awake")) and
                row300["ours_awake"]["p99_us"] < 1000.0},
        {"target": "a pile of 200 objects asleep costs under 10 % of its awake step",
         "measured": (f"{pile_asleep['p50_us']:.1f} us asleep ({pile_asleep.get('asleep', 0):.0f} "
                      f"of {pile_asleep['objects']}) vs {pile_awake['p50_us']:.0f} us awake "
                      f"(p50): {100 * pile_share:.1f} %") if pile_share is not None else "not run",
         "met": pile_share is not None and pile_share < 0.10 and
                pile_asleep.get("asleep", 0) == pile_asleep["objects"]},
        {"target": "glove -> physics DDS latency p99 under 0.5 ms",
         "measured": f"p99 {transit['p99']:.0f} us", "met": transit["p99"] < 500.0},
        {"target": "... and within 2x of the bare Fast DDS floor (p99)",
         "measured": f"{transit['p99']:.0f} us vs floor {floor_transit['p99']:.0f} us "
                     f"({transit['p99'] / max(floor_transit['p99'], 1e-9):.2f}x)",
         "met": transit["p99"] <= 2.0 * floor_transit["p99"]},
        {"target": "stereo 1280x720 per eye at 90 fps or better (physics and glove at 1 kHz)",
         "measured": f"{ig['fps']:.1f} fps", "met": ig["fps"] >= 90.0},
        {"target": "the cockpit's triangles per eye, 100k or more (a model cockpit)",
         "measured": f"{ig.get('triangles_per_eye', {}).get('total', 0):,} "
                     f"({ig.get('triangles_per_eye', {}).get('fixed', 0):,} fixed)",
         "met": ig.get('triangles_per_eye', {}).get('total', 0) >= 100_000},
        {"target": "the default rig's frame rate drops under 5 % with its video recorded",
         "measured": f"{rig_novideo_fps:.1f} -> {rig_fps:.1f} fps ({rig_drop:+.1f} %); unpaced, "
                     f"{ig['fps']:.1f} -> {ig_video['fps']:.1f} fps ({fps_drop:+.1f} %)",
         "met": rig_drop < 5.0},
        {"target": "glove-to-frame latency p99 under 20 ms",
         "measured": f"p99 {e2e['p99']:.1f} ms", "met": e2e["p99"] < 20.0},
        {"target": "hand-tracking retargeting, both hands, p99 under 0.2 ms per frame",
         "measured": f"p50 {retarget['all']['p50_us']:.0f} us, p99 {retarget['all']['p99_us']:.0f} us "
                     f"(two-handed three-claps p99 {retarget['three-claps']['p99_us']:.0f} us)",
         "met": retarget["all"]["p99_us"] < 200.0 and retarget["three-claps"]["p99_us"] < 200.0},
        {"target": "offline runner at 100x real time or better",
         "measured": f"{offline['realtime_factor']:.1f}x", "met": offline["realtime_factor"] >= 100.0},
    ]

    results = {
        "machine": machine(),
        "date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M"),
        "commit": commit(),
        "physics_step": rows,
        "pile": pile,
        "hand_forward_kinematics": fk,
        "dds_latency_at_1khz": {"glove_to_physics": rt, "bare_fast_dds_floor": floor},
        "realtime_loop": {k: rt.get(k) for k in ("duration_s", "steps", "rate_hz", "late_steps",
                                                  "step_compute_us")},
        "image_generator": ig,
        "image_generator_recording_video": ig_video,
        "image_generator_without_background_cache": ig_nocache,
        "fingertip_error_at_frame_end": tips,
        "end_to_end": {"glove_to_frame_latency_ms": e2e,
                       "parts_ms": rig.get("latency_parts_ms"),
                       "frames_rendered": rig.get("frames_rendered")},
        "offline": {k: offline.get(k) for k in ("simulated_s", "wall_s", "realtime_factor",
                                                 "realtime_factor_runs", "stage_wall_s",
                                                 "stage_timing_every")},
        "hand_input_in_time": follow,
        "retarget_per_frame": retarget,
        "targets": targets,
    }
    tmp = json_path + ".partial"
    with open(tmp, "w") as f:
        json.dump(results, f, indent=2)
        f.write("\n")
    os.replace(tmp, json_path)

    m = results["machine"]
    md = []
    md.append("# vcockpit benchmark results\n")
    md.append(f"Written by `scripts/bench` on {results['date_utc']} UTC, commit `{results['commit']}`.  ")
    md.append(f"Machine: {m['cpu']}, {m['cores']} cores, {m['memory_gib']} GiB, {m['os']} "
              f"(kernel {m['kernel']}). All DDS traffic on loopback (UDP, `loopback` profile).\n")
    md.append("## Targets\n")
    md.append("| target | measured | |")
    md.append("|---|---|---|")
    for t in targets:
        md.append(f"| {t['target']} | {t['measured']} | {status(t['met'])} |")
    md.append("")
    md.append("## Physics step: ours and MuJoCo 2.2.2, same scenes, same run\n")
    md.append("One 1 ms step with the hand holding the cup (ours: collision, the soft contact "
              "solve, grasp test; MuJoCo: `mj_step`, Newton solver, the hand's links as mocap bodies). "
              "Wall time per step, single thread.\n")
    md.append("Ours with sleeping (the default: objects at rest sleep, docs/ARCHITECTURE.md, "
              "\"Sleeping\"), and with every object kept awake (`sleep: {enabled: false}`).\n")
    md.append("| scene | asleep | ours p50 / p99 (us) | contacts | every object awake: "
              "p50 / p99 (us) | MuJoCo p50 / p99 (us) | contacts | ours / MuJoCo "
              "(p50 / p99) | every object awake: ours / MuJoCo (p50 / p99) |")
    md.append("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        o, mj, aw = r["ours"], r["mujoco"] or {}, r.get("ours_awake") or {}
        awake_text = (f"{aw['p50_us']:.1f} / {aw['p99_us']:.1f}"
                      if aw else "")
        md.append(f"| {r['scene']} | {o.get('asleep', 0):.0f} | "
                  f"{o['p50_us']:.1f} / {o['p99_us']:.1f} | {o.get('contacts', 0):.0f} | "
                  f"{awake_text} | "
                  f"{mj.get('p50_us', float('nan')):.1f} / {mj.get('p99_us', float('nan')):.1f} | "
                  f"{mj.get('contacts', 0):.0f} | "
                  f"{r['ratio_p50']:.2f}x / {r['ratio_p99']:.2f}x | " +
                  (f"{r['ratio_awake_p50']:.2f}x / {r['ratio_awake_p99']:.2f}x |"
                   if r["ratio_awake_p50"] is not None else " |")
                  if r["ratio_p50"] is not None else
                  f"| {r['scene']} | ... | | {o['p50_us']:.1f} / {o['p99_us']:.1f} | | | | | | |")
    md.append("")
    if pile_asleep and pile_awake:
        md.append(f"A pile of {pile_asleep['objects']} boxes and balls in a bin "
                  f"(`bench_scenes.hpp`, `pile_scene`), 6 s after the drop: with sleeping "
                  f"{pile_asleep.get('asleep', 0):.0f} asleep, {pile_asleep['p50_us']:.1f} / {pile_asleep['p99_us']:.1f} us "
                  f"(p50 / p99); every object awake, "
                  f"{pile_awake.get('contacts', 0):.0f} contacts, {pile_awake['p50_us']:.0f} / "
                  f"{pile_awake['p99_us']:.0f} us. The lowest object's centroid "
                  f"{pile_asleep.get('lowest_z_mm', 0):.1f} mm and "
                  f"{pile_awake.get('lowest_z_mm', 0):.1f} mm above the floor.\n")
    md.append("Collision detection alone (broadphase + narrowphase, one step's poses, every "
              "object awake):\n")
    md.append("| scene | pairs | contacts | p50 (us) | p99 (us) |")
    md.append("|---|---|---|---|---|")
    for r in rows:
        c = r["collision"]
        if c:
            md.append(f"| {r['scene']} | {c.get('pairs', 0):.0f} | {c.get('contacts', 0):.0f} | "
                      f"{c['p50_us']:.1f} | {c['p99_us']:.1f} |")
    if fk:
        md.append(f"\nHand forward kinematics (22 joints, 16 links): {fk['mean_ns']:.0f} ns.\n")
    md.append("## DDS latency, glove -> physics at 1 kHz\n")
    md.append("Transit = Fast DDS reception stamp minus source stamp (same clock, same machine). "
              "The floor is a bare Fast DDS writer -> reader of the same type with the same QoS "
              "profile, measured in the same run.\n")
    md.append("| | samples | p50 (us) | p99 (us) | max (us) |")
    md.append("|---|---|---|---|---|")
    md.append(f"| bare Fast DDS floor: transit | {floor_transit['count']} | {floor_transit['p50']:.0f} "
              f"| {floor_transit['p99']:.0f} | {floor_transit['max']:.0f} |")
    if "take_latency_us" in floor:
        t = floor["take_latency_us"]
        md.append(f"| bare Fast DDS floor: write -> take (waitset) | {t['count']} | {t['p50']:.0f} | "
                  f"{t['p99']:.0f} | {t['max']:.0f} |")
    md.append(f"| glove_driver -> physics_node: transit | {transit['count']} | {transit['p50']:.0f} | "
              f"{transit['p99']:.0f} | {transit['max']:.0f} |")
    a = rt["age_at_step_us"]
    md.append(f"| glove_driver -> physics_node: write -> used by a step | {a['count']} | "
              f"{a['p50']:.0f} | {a['p99']:.0f} | {a['max']:.0f} |")
    md.append("\n(The 1 kHz loop takes samples at the start of each step, so a sample waits up to "
              "one period after it arrives.)\n")
    md.append("## Physics real-time loop\n")
    sc = rt.get("step_compute_us", {})
    md.append(f"{rt['duration_s']:.1f} s at a 1 kHz target with the glove replay: "
              f"{rt['steps']} steps, {rt['rate_hz']:.2f} Hz achieved, {rt['late_steps']} late "
              f"steps; step compute p50 {sc.get('p50', 0):.0f} us, p99 {sc.get('p99', 0):.0f} us, "
              f"max {sc.get('max', 0):.0f} us.\n")
    md.append("## Image generator\n")
    md.append(f"Stereo {ig['width_px']}x{ig['height_px']} per eye, default cockpit, OSMesa "
              f"(llvmpipe), unpaced, physics and glove running at 1 kHz on the same cores: "
              f"{ig['frames']} frames in {ig['wall_s']:.2f} s = **{ig['fps']:.1f} fps**; render "
              f"p50 {ig['render_ms']['p50']:.1f} ms, p99 {ig['render_ms']['p99']:.1f} ms.\n")
    parts = ig.get("frame_parts_ms", {})
    md.append(f"Each frame's parts (p50, ms): background restored "
              f"{parts.get('background', {}).get('p50', 0):.2f}, newest state latched "
              f"{parts.get('latch', {}).get('p50', 0):.2f}, moving layer submitted "
              f"{parts.get('moving', {}).get('p50', 0):.2f}, rasterised and read back "
              f"{parts.get('finish', {}).get('p50', 0):.2f}; the static cockpit drawn "
              f"{ig.get('background_redraws', 0)} time(s). The scene has "
              f"{ig.get('triangles_per_eye', {}).get('total', 0):,} triangles per eye "
              f"({ig.get('triangles_per_eye', {}).get('fixed', 0):,} in the cockpit's fixed layer, "
              f"{ig.get('triangles_per_eye', {}).get('moving', 0):,} moving). Drawing the whole cockpit every frame "
              f"instead (`--no-background-cache`, as before the cache): "
              f"**{ig_nocache['fps']:.1f} fps**, render p50 "
              f"{ig_nocache['render_ms']['p50']:.1f} ms.\n")
    md.append(f"The same, recording the run's video ({video.get('width_px')}x"
              f"{video.get('height_px')} H.264 at {video.get('fps')} fps): "
              f"**{ig_video['fps']:.1f} fps** ({fps_drop:.1f} % fewer); render p50 "
              f"{ig_video['render_ms']['p50']:.1f} ms, p99 {ig_video['render_ms']['p99']:.1f} ms; "
              f"{video.get('video_frames')} frames in the video ({video.get('repeated')} display "
              f"periods held the previous image), "
              f"{video.get('frames_dropped')} of {video.get('frames_submitted')} rendered frames "
              f"left out because the encoder, on idle CPU time only, was behind.\n")
    md.append("## The drawn fingertip against the glove at frame end\n")
    md.append("Real time (rate 1): the physics at 1 kHz, frames at the HMD's 90 Hz; for each "
              "frame the tracked index fingertip drawn, as received and as predicted for the "
              "frame's end (`--predict-hand`), against the glove log's at that moment "
              "(`bench/fingertip_error`).\n")
    md.append("| log | frames | without prediction p50 / p99 (mm) | with prediction p50 / p99 (mm) "
              "| horizon p50 (ms) |")
    md.append("|---|---|---|---|---|")
    names = {"bundled": "bundled grasp", "typical": "degraded: typical (60 Hz, jitter, noise, "
             "dropouts)", "harsh": "degraded: harsh (30 Hz, gaps, ...)",
             "real_leap": "real Leap Motion recording"}
    for case, t in tips.items():
        a, b = t["without_prediction_mm"], t["with_prediction_mm"]
        md.append(f"| {names[case]} | {t['frames']} | {a['p50']:.1f} / {a['p99']:.1f} | "
                  f"{b['p50']:.1f} / {b['p99']:.1f} | {t['horizon_ms']['p50']:.1f} |")
    md.append("")
    md.append("## End to end: glove sample -> rendered frame\n")
    parts = rig.get("latency_parts_ms") or {}
    md.append(f"The default rig (`config/rig.yaml`: lockstep replay, frames paced at the HMD's "
              f"90 Hz, hands predicted to the frame's end), "
              f"{e2e['samples']} hand samples drawn: p50 {e2e['p50']:.1f} ms, p99 {e2e['p99']:.1f} "
              f"ms, max {e2e['max']:.1f} ms. Of which: the sample's age when the frame took it (the latch) "
              f"p50 {parts.get('age_at_render_start_p50', 0):.1f} ms (p99 "
              f"{parts.get('age_at_render_start_p99', 0):.1f}), latch to frame end p50 "
              f"{parts.get('render_p50', 0):.1f} ms (p99 {parts.get('render_p99', 0):.1f}).\n")
    md.append("## Offline runner\n")
    st = offline["stage_wall_s"]
    runs = offline["realtime_factor_runs"]
    md.append(f"`physics_node --offline` on the bundled log, the median of {len(runs)} runs: "
              f"{offline['simulated_s']:.1f} s simulated in {offline['wall_s']:.3f} s = "
              f"**{offline['realtime_factor']:.1f}x real time** (the runs: "
              + ", ".join(f"{r:.1f}x" for r in runs) + "). Wall time by stage (s, "
              f"from one step in {offline.get('stage_timing_every', 1)}): "
              + ", ".join(f"{k} {v:.3f}" for k, v in st.items()) + ".\n")
    md.append("## Hand tracking: retargeting time per frame\n")
    md.append("`bench/bench_retarget`: every frame of the six real Leap recordings "
              "(`tests/data/real/leap/`), each calibrated on itself, retargeted to the hand model "
              "(`hand/tracking/retarget.hpp`), the frame's hands one after the other; five passes.\n")
    md.append("| recording | frames | p50 (us) | p99 (us) | max (us) |")
    md.append("|---|---|---|---|---|")
    for name, r in retarget.items():
        if name == "all":
            continue
        md.append(f"| {name} | {r['frames']} | {r['p50_us']:.1f} | {r['p99_us']:.1f} | {r['max_us']:.1f} |")
    md.append(f"| all | | {retarget['all']['p50_us']:.1f} | {retarget['all']['p99_us']:.1f} | |")
    md.append("")
    md.append("## Hand input in time\n")
    md.append("The bundled gesture (`config/gestures/reach_grasp_lift_release.yaml`) played by "
              "`glove_driver --source synthetic --rate-hz R`. **Real time**: `physics_node` at 1 "
              "kHz; hand lag = the step's end minus the source stamp of the hand it shows "
              "(transit + interpolation delay + any wait for a late sample), with the adaptive "
              "delay and with `--input-delay 0` (the newest sample at once, held until the next: "
              "the behaviour before interpolation). **Offline**: the same gesture recorded at R "
              "and replayed with `physics_node --offline`, interpolated and with `--max-gap 0` "
              "(each sample taken in one step). The recorded wrist never exceeds about 0.45 m/s.\n")
    md.append("| rate | delay (ms) | hand lag p50 / p99 / max (ms) | late intervals | peak wrist "
              "(m/s) | no delay: lag p50 / p99 / max (ms) | no delay: peak wrist (m/s) |")
    md.append("|---|---|---|---|---|---|---|")
    for r in follow:
        a, b = r["realtime"], r["realtime_no_delay"]
        la, lb = a["hand_lag_us"], b["hand_lag_us"]
        md.append(f"| {r['rate_hz']} Hz | {a['input_delay_ms']:.1f} | {la['p50'] / 1e3:.1f} / "
                  f"{la['p99'] / 1e3:.1f} / {la['max'] / 1e3:.1f} | "
                  f"{a['input']['intervals_late']} of {a['input']['intervals']} | "
                  f"{a['hand_peak_wrist_speed_mps']:.2f} | {lb['p50'] / 1e3:.1f} / "
                  f"{lb['p99'] / 1e3:.1f} / {lb['max'] / 1e3:.1f} | "
                  f"{b['hand_peak_wrist_speed_mps']:.2f} |")
    md.append("")
    md.append("| rate | offline, interpolated: peak wrist (m/s), joint (rad/s), grasps/releases | "
              "each sample in one step: peak wrist, joint, grasps/releases |")
    md.append("|---|---|---|")
    for r in follow:
        o, o0 = r["offline"], r["offline_each_sample_in_one_step"]
        md.append(f"| {r['rate_hz']} Hz | {o['hand_peak_wrist_speed_mps']:.2f}, "
                  f"{o['hand_peak_joint_speed_radps']:.1f}, {o['grasps']}/{o['releases']} | "
                  f"{o0['hand_peak_wrist_speed_mps']:.2f}, {o0['hand_peak_joint_speed_radps']:.1f}, "
                  f"{o0['grasps']}/{o0['releases']} |")
    md.append("")
    tmp = md_path + ".partial"
    with open(tmp, "w") as f:
        f.write("\n".join(md))
    os.replace(tmp, md_path)
    print("\n".join(md[:len(targets) + 8]))


if __name__ == "__main__":
    main()
