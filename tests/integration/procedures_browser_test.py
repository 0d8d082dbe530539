#!/usr/bin/python3
"""The instructor station's procedures in a real browser (headless Chromium through
chromedriver, as instructor_browser_test.py, whose WebDriver helpers this uses), on the
procedures trainer's rig flying config/glove_logs/procedures_right.csv. One scenario a run:

  --scenario gear_unsafe  the instructor inserts "gear unsafe" from the page's Failures panel:
      1. the page is live and the systems node's values arrive;
      2. once the gear is down again before landing (three green), the failure is inserted:
         its row says INSERTED and the left gear lamp turns red. The log presses the master
         caution and recycles the gear about 19 s of simulated time later (10 s of wall time at
         the test's rate 2): the margin for a slow page or a loaded machine;
      3. the gear-unsafe abnormal starts and is scored: its steps are done as the hand presses
         the master caution and raises and lowers the gear, and the gear lamps end green;
      4. a screenshot.
  --scenario reset        a run frozen, reset and scored again:
      1. the page is live; "Before start" is complete;
      2. Freeze, then Reset to start: every procedure waits again, the systems stand still;
      3. Restart replay, Unfreeze: "Before start" is flown again and complete, started after
         the reset;
      4. a screenshot.
Exit status: 0 pass, 1 fail (which check, what it saw), 77 skip (Chromium cannot run here).
"""
import argparse
import sys
import time
import urllib.parse
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from instructor_browser_test import (  # noqa: E402  (the helpers of the station's own test)
    FAIL, PASS, SKIP, CheckFailed, Skip, browser)

STATE_JS = """
const q = (s) => document.querySelector(s);
const procedures = {};
for (const div of document.querySelectorAll('#procedures .procedure')) {
  procedures[div.dataset.name] = {
    state: div.dataset.state, errors: Number(div.dataset.errors),
    started: div.dataset.startedS === '' ? null : Number(div.dataset.startedS),
    steps: [...div.querySelectorAll('li.step')].map((li) => ({status: li.dataset.status,
                                                               flags: li.dataset.flags})),
  };
}
const failures = {};
for (const tr of document.querySelectorAll('#failures tr[data-failure]'))
  failures[tr.dataset.failure] = tr.dataset.inserted === 'true';
const lamps = {};
for (const id of ['gear-nose', 'gear-left', 'gear-right', 'master-caution'])
  lamps[id] = q('#' + id) ? q('#' + id).dataset.lamp : null;
const t = q('#systems-time');
return {conn: q('#conn') ? q('#conn').dataset.conn : null,
        systemsTime: t && t.dataset.simTime !== '' ? Number(t.dataset.simTime) : null,
        frozen: q('#frozen') ? q('#frozen').dataset.frozen : null,
        procedures, failures, lamps};
"""


class Page:
    def __init__(self, driver, deadline):
        self.driver = driver
        self.deadline = deadline

    def state(self):
        return self.driver.execute(STATE_JS)

    def until(self, condition, within, what):
        """Polls the page until condition(state) is true; the state, or CheckFailed with the
        last one seen."""
        end = min(time.monotonic() + within, self.deadline)
        seen = None
        while time.monotonic() < end:
            seen = self.state()
            if condition(seen):
                return seen
            time.sleep(0.2)
        raise CheckFailed(f"{what}: not within {within:.0f} s; the page had {brief(seen)}")

    def click(self, css):
        element = self.driver.find(css)
        if element is None:
            raise CheckFailed(f"no {css} on the page")
        self.driver.click(element)


def brief(state):
    if not state:
        return "nothing"
    procs = {n: f"{p['state']}({sum(s['status'] == 'done' for s in p['steps'])}/{len(p['steps'])} done,"
                f" {p['errors']} err, from {p['started']})" for n, p in state["procedures"].items()}
    return (f"conn {state['conn']}, systems at {state['systemsTime']}, frozen {state['frozen']}, "
            f"failures {state['failures']}, lamps {state['lamps']}, procedures {procs}")


def done_steps(proc):
    return sum(s["status"] == "done" for s in proc["steps"]) if proc else 0


def check(n, name, body):
    try:
        said = body()
    except CheckFailed as e:
        print(f"FAIL check {n} ({name}): {e}", flush=True)
        raise
    print(f"ok check {n} ({name}){': ' + said if said else ''}", flush=True)


def gear_unsafe(page, args):
    check(1, "live, systems values arrive", lambda: "systems at %.2f s" % page.until(
        lambda s: s["conn"] == "live" and s["systemsTime"] is not None and
        "gear_unsafe_left" in s["failures"], 60, "systems")["systemsTime"])

    def insert():
        # not earlier: the log's "after take-off" gear raise would clear the failure at once
        ready = page.until(lambda s: done_steps(s["procedures"].get("before_landing")) >= 2,
                           args.timeout, "before landing: gear down, three green")
        page.click('#failures tr[data-failure="gear_unsafe_left"] button.insert')
        s = page.until(lambda s: s["failures"].get("gear_unsafe_left") and
                       s["lamps"]["gear-left"] == "red", 15, "gear unsafe inserted, left lamp red")
        return (f"three green at {ready['systemsTime']:.2f} s, inserted at "
                f"{s['systemsTime']:.2f} s, lamps {s['lamps']}")
    check(2, "failure inserted from the page", insert)

    def scored():
        s = page.until(lambda s: (s["procedures"].get("gear_unsafe") or {}).get("state")
                       in ("running", "complete") and
                       done_steps(s["procedures"]["gear_unsafe"]) >= 3 and
                       s["lamps"]["gear-left"] == "green", args.timeout, "the abnormal scored")
        p = s["procedures"]["gear_unsafe"]
        flagged = sum(1 for st in p["steps"] if st["flags"])
        return (f"gear_unsafe {p['state']}: {done_steps(p)}/{len(p['steps'])} steps done, "
                f"{flagged} flagged, {p['errors']} errors; lamps {s['lamps']}")
    check(3, "the abnormal procedure is scored", scored)


def reset(page, args):
    def before_start():
        s = page.until(lambda s: s["conn"] == "live" and
                       (s["procedures"].get("before_start") or {}).get("state") == "complete",
                       args.timeout, "before start complete")
        return f"before start complete at systems time {s['systemsTime']:.2f} s"
    check(1, "before start complete", before_start)

    def freeze_and_reset():
        page.click("#freeze")
        page.until(lambda s: s["frozen"] == "true", 15, "frozen")
        page.click("#reset-start")
        s = page.until(lambda s: all(p["state"] == "waiting" and p["errors"] == 0
                                     for p in s["procedures"].values()) and s["procedures"],
                       15, "every procedure waiting again after the reset")
        t0 = s["systemsTime"]
        time.sleep(1.0)
        t1 = page.state()["systemsTime"]
        if t1 != t0:
            raise CheckFailed(f"frozen, the systems went on: {t0} -> {t1}")
        page.reset_at = t0
        return f"reset at {t0:.2f} s; every procedure waiting, the systems still"
    check(2, "frozen and reset", freeze_and_reset)

    def scored_again():
        page.click("#restart-replay")
        page.click("#unfreeze")
        s = page.until(lambda s: (s["procedures"].get("before_start") or {}).get("state") == "complete"
                       and (s["procedures"]["before_start"]["started"] or -1) >= page.reset_at,
                       args.timeout, "before start flown again")
        p = s["procedures"]["before_start"]
        return (f"before start complete again, started at {p['started']:.2f} s "
                f"(reset at {page.reset_at:.2f} s), {p['errors']} errors")
    check(3, "scored again", scored_again)


def run(args):
    deadline = time.monotonic() + args.timeout + 60
    with browser(args, args.url, "vcockpit-procedures-browser-") as driver:
        driver.navigate(args.url)
        page = Page(driver, deadline)
        (gear_unsafe if args.scenario == "gear_unsafe" else reset)(page, args)
        if args.screenshot:
            Path(args.screenshot).write_bytes(driver.screenshot())
            print(f"ok check 4 (screenshot): {args.screenshot}", flush=True)
        print(f"PASS: scenario {args.scenario}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__)
    ap.add_argument("--url", required=True)
    ap.add_argument("--scenario", choices=["gear_unsafe", "reset"], required=True)
    ap.add_argument("--screenshot")
    ap.add_argument("--chromium", default="/usr/bin/chromium")
    ap.add_argument("--chromedriver", default="/usr/bin/chromedriver")
    ap.add_argument("--timeout", type=float, default=120.0, help="per check, seconds")
    ap.add_argument("--driver-port", type=int, default=0)
    args = ap.parse_args()
    if urllib.parse.urlsplit(args.url).hostname not in ("127.0.0.1", "localhost"):
        print("FAIL: the station must be on loopback", file=sys.stderr)
        return FAIL
    try:
        run(args)
        return PASS
    except Skip as e:
        print(f"SKIP: {e}")
        return SKIP
    except CheckFailed:
        return FAIL


if __name__ == "__main__":
    sys.exit(main())
