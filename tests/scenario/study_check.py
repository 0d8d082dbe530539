#!/usr/bin/python3
"""Checks a grasp study's outputs (scripts/study --quick in study_quick):
the files exist, every rule (both readings of the gesture constraint among them) has trials, the
failed trials are placed, and the numbers are not degenerate.

  study_check.py OUT_DIR
"""
import json
import os
import sys


def main(out_dir):
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    for name in ("results.md", "results.json", "rules.png", "penetration.png", "failures.png",
                 "sweeps.png", "timeline.png"):
        path = os.path.join(out_dir, name)
        check(os.path.isfile(path) and os.path.getsize(path) > 0, f"{name} missing or empty")
    if failures:
        print("\n".join(failures))
        return 1
    with open(os.path.join(out_dir, "results.json")) as f:
        doc = json.load(f)
    metrics = doc["metrics"]
    compared = [r["name"] for r in doc["rules"] if r["group"] == "rules"]
    check(compared == ["strict", "relaxed", "relaxed_gesture", "default", "default_paper_gesture"],
          f"rules {compared}")
    total = successes = 0
    for r in doc["rules"]:
        m = metrics[r["name"]]
        check(m["trials"] > 0, f"rule {r['name']} has no trials")
        total += m["success"]["n"]
        successes += m["success"]["successes"]
    check(0 < successes < total, f"degenerate: {successes} of {total} trials succeed")
    for name in compared:
        m = metrics[name]
        check(m["trials"] == len(doc["objects"]) * doc["trials_per_object"],
              f"rule {name}: {m['trials']} trials")
    # the figures are figures: the rules differ, convergence times and penetration vary
    shares = {metrics[n]["success"]["share"] for n in compared}
    check(len(shares) > 1, f"every rule has the same success share {shares}")
    chatter = [metrics[n]["switch_rate_hz"]["mean"] for n in compared]
    check(len(set(chatter)) > 1, f"every rule chatters alike: {chatter}")
    conv = metrics["default"]["convergence_s"]
    check(conv["n"] > 0 and conv["p90"] >= conv["p50"] > 0,
          f"default convergence {conv}")
    pen = metrics["default"]["hand_pen_max_mm"]
    check(pen["mean"] > 0 and pen["p90"] >= pen["p50"], f"default hand penetration {pen}")
    for group in ("alpha0", "xi"):
        check(len(doc["sweeps"].get(group, [])) >= 5, f"sweep {group} missing")
    with open(os.path.join(out_dir, "results.md")) as f:
        md = f.read()
    for text in ("## Headline", "(a) strict", "(d) project default", "(e) project, paper's gesture",
                 "## Where the failed trials failed", "failures.png", "## Sweeps", "rules.png"):
        check(text in md, f"results.md lacks {text!r}")
    if failures:
        print("\n".join(failures))
        return 1
    print(f"study_check: {total} trials, {successes} succeed; outputs complete")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
