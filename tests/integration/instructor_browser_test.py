#!/usr/bin/python3
"""The instructor station's page in a real browser: headless Chromium driven through
chromedriver's W3C WebDriver HTTP API (Python standard library only). Checks, in order:
  1. the page loads and #conn says live;
  2. the rows of the nodes named by --nodes exist and are alive;
  3. the pilot's view shows a picture, not a blank frame (luminance spread, distinct colours);
  4. a screenshot of the page goes to --screenshot;
  5. Freeze: #frozen says FROZEN, the sim time holds still, node status keeps arriving;
  6. Unfreeze: the sim time advances again;
  7. a control's position button moves the control (its row shows the new position).
Exit status: 0 pass, 1 fail (which check, what it saw), 77 skip (chromium or chromedriver
missing, or chromium cannot start here).

  /usr/bin/python3 tests/integration/instructor_browser_test.py \\
      --url http://127.0.0.1:8088/ --screenshot out/instructor.png
  /usr/bin/python3 tests/integration/instructor_browser_test.py --self-test [--screenshot PNG]
      # runs the checks against tests/integration/instructor_mock_server.py: they must pass on
      # the well-behaved mock and fail, at the right check, on each misbehaving one

Traffic stays on loopback: the station must be on 127.0.0.0/8 (or localhost), chromedriver
listens on loopback only, and chromium's proxy and name resolution point nowhere for any other
host.
"""
import argparse
import base64
import contextlib
import ipaddress
import json
import os
import re
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.parse
import urllib.request
from pathlib import Path

PASS, FAIL, SKIP = 0, 1, 77
ELEMENT = "element-6066-11e4-a52e-4f735466cecf"   # the W3C web element identifier key
# no proxy from the environment: every request here is to loopback
HTTP = urllib.request.build_opener(urllib.request.ProxyHandler({}))
ALIVE_WITHIN_S = 3.0   # the station calls a node stale after ~3 s without status


class Skip(Exception):
    """The browser cannot run here: not the page's fault."""


class CheckFailed(Exception):
    pass


class WebDriverError(Exception):
    def __init__(self, error, message):
        first = message.splitlines()[0] if message else ""
        super().__init__(first if first.startswith(error) else f"{error}: {first}")
        self.error = error


class WebDriver:
    """The few W3C WebDriver endpoints the test uses, over chromedriver's loopback port."""

    def __init__(self, port):
        self.base = f"http://127.0.0.1:{port}"
        self.session = None

    def call(self, method, path, body=None, timeout=30.0):
        data = None if body is None else json.dumps(body).encode()
        req = urllib.request.Request(self.base + path, data=data, method=method,
                                     headers={"Content-Type": "application/json; charset=utf-8"})
        try:
            with HTTP.open(req, timeout=timeout) as reply:
                return json.load(reply).get("value")
        except urllib.error.HTTPError as e:
            try:
                value = json.load(e).get("value") or {}
            except ValueError:
                value = {}
            raise WebDriverError(value.get("error", f"HTTP {e.code}"),
                                 value.get("message", "")) from None

    def ready(self):
        try:
            return bool((self.call("GET", "/status", timeout=2.0) or {}).get("ready"))
        except (OSError, ValueError, WebDriverError):
            return False

    def start(self, chromium, args):
        caps = {"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            "pageLoadStrategy": "normal",
            "timeouts": {"implicit": 0, "pageLoad": 30000, "script": 15000},
            "goog:chromeOptions": {"binary": chromium, "args": args},
        }}}
        self.session = self.call("POST", "/session", caps, timeout=90.0)["sessionId"]

    def _s(self, path):
        return f"/session/{self.session}{path}"

    def navigate(self, url):
        self.call("POST", self._s("/url"), {"url": url}, timeout=40.0)

    def find(self, css):
        """The element's id, or None when nothing matches."""
        try:
            found = self.call("POST", self._s("/element"), {"using": "css selector", "value": css})
        except WebDriverError as e:
            if e.error == "no such element":
                return None
            raise
        return found[ELEMENT]

    def click(self, element):
        self.call("POST", self._s(f"/element/{element}/click"), {})

    def execute(self, script, *args):
        return self.call("POST", self._s("/execute/sync"), {"script": script, "args": list(args)})

    def screenshot(self):
        return base64.b64decode(self.call("GET", self._s("/screenshot"), timeout=30.0))

    def quit(self):
        if self.session:
            self.call("DELETE", self._s(""), timeout=15.0)
            self.session = None


# ---- the browser and its driver ------------------------------------------------------------

def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def chromium_args(user_data_dir, station_host):
    return [
        "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
        "--window-size=1400,1000", "--no-first-run", "--disable-extensions",
        "--disable-background-networking", f"--user-data-dir={user_data_dir}",
        "--force-device-scale-factor=1", "--hide-scrollbars",
        # background services that would call out
        "--disable-component-update", "--disable-sync", "--disable-default-apps",
        "--no-default-browser-check", "--disable-domain-reliability", "--disable-breakpad",
        "--disable-client-side-phishing-detection", "--no-pings", "--metrics-recording-only",
        # only loopback: any other host goes to a closed loopback port (Chromium never proxies
        # loopback itself) and no host name but the station's resolves
        "--proxy-server=http://127.0.0.1:9",
        f"--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE localhost, EXCLUDE {station_host}",
    ]


def chromium_says(chromium, workdir):
    """Why chromium does not start (chromedriver does not pass its stderr on): the last lines
    it prints when started alone on a blank page."""
    cmd = [chromium, *chromium_args(workdir / "probe", "localhost"), "--dump-dom", "about:blank"]
    try:
        run = subprocess.run(cmd, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                             errors="replace", timeout=20)
    except (OSError, subprocess.TimeoutExpired) as e:
        return f"; alone: {e}"
    lines = [l for l in run.stderr.splitlines() if l.strip()][-3:]
    return f"; alone it exits {run.returncode}" + "".join(f"\n  {l}" for l in lines)


def start_chromedriver(path, port, workdir):
    """chromedriver on loopback only (no --allowed-ips: with it, it would listen on every
    interface), in its own process group so that chromium goes with it at the end."""
    out = open(workdir / "chromedriver.out", "wb")
    proc = subprocess.Popen([path, f"--port={port}", f"--log-path={workdir / 'chromedriver.log'}"],
                            stdin=subprocess.DEVNULL, stdout=out, stderr=subprocess.STDOUT,
                            start_new_session=True)
    out.close()
    driver = WebDriver(port)
    end = time.monotonic() + 20.0
    while not driver.ready():
        if proc.poll() is not None or time.monotonic() > end:
            said = (workdir / "chromedriver.out").read_text(errors="replace").strip()[-500:]
            stop_group(proc)
            raise Skip(f"chromedriver did not start on 127.0.0.1:{port}: {said or 'no output'}")
        time.sleep(0.1)
    return proc, driver


def stop_group(proc):
    """Ends chromedriver and whatever it started (chromium), politely first."""
    for sig, grace in ((signal.SIGTERM, 5.0), (signal.SIGKILL, 5.0)):
        try:
            os.killpg(proc.pid, sig)
        except ProcessLookupError:
            break
        end = time.monotonic() + grace
        while time.monotonic() < end:
            proc.poll()
            try:
                os.killpg(proc.pid, 0)
            except ProcessLookupError:
                proc.wait()
                return
            time.sleep(0.05)
    proc.wait()


# ---- reading the page ----------------------------------------------------------------------

SNAPSHOT_JS = """
const q = (s) => document.querySelector(s);
const text = (s) => { const e = q(s); return e ? e.textContent.trim() : null; };
const nodes = {};
for (const tr of document.querySelectorAll('#nodes tr[data-node]')) {
  nodes[tr.dataset.node] = {classes: [...tr.classList], age: tr.dataset.ageS ?? null};
}
const controls = [...document.querySelectorAll('#controls tr[data-control-id]')].map((tr) => ({
  id: tr.dataset.controlId,
  name: tr.dataset.name ?? tr.cells[0].textContent.trim(),
  positionName: (tr.querySelector('.position-name') || {textContent: ''}).textContent.trim(),
  buttons: [...tr.querySelectorAll('button.set-position')].map((b) => ({
    position: b.dataset.position, name: b.textContent.trim(),
    current: b.classList.contains('current')})),
}));
const simTime = q('#sim-time');
return {title: document.title, url: location.href, conn: text('#conn'),
        simTimeText: text('#sim-time'), simTime: simTime ? simTime.dataset.simTime ?? null : null,
        frozen: text('#frozen'), lastAck: text('#last-ack'), nodes, controls};
"""

# Luminance spread and distinct colours (4 bits per channel) over a 64 x 36 grid of the view.
VIEW_STATS_JS = """
const img = document.getElementById('view');
if (!img) return {loaded: false, why: 'no #view element'};
if (!img.complete || !img.naturalWidth) return {loaded: false, why: 'not loaded', src: img.src};
const w = img.naturalWidth, h = img.naturalHeight;
const canvas = document.createElement('canvas');
canvas.width = w; canvas.height = h;
const g = canvas.getContext('2d');
g.drawImage(img, 0, 0);
const px = g.getImageData(0, 0, w, h).data;
let sum = 0, sum2 = 0, n = 0;
const colours = new Set();
for (let j = 0; j < 36; j++) for (let i = 0; i < 64; i++) {
  const x = Math.floor((i + 0.5) * w / 64), y = Math.floor((j + 0.5) * h / 36);
  const k = (y * w + x) * 4, r = px[k], gr = px[k + 1], b = px[k + 2];
  const lum = 0.2126 * r + 0.7152 * gr + 0.0722 * b;
  sum += lum; sum2 += lum * lum; n++;
  colours.add(((r >> 4) << 8) | ((gr >> 4) << 4) | (b >> 4));
}
const mean = sum / n;
return {loaded: true, width: w, height: h, stddev: Math.sqrt(Math.max(0, sum2 / n - mean * mean)),
        colours: colours.size};
"""


def sim_time(snap):
    """The page's sim time in seconds (its data attribute, else its text), or None."""
    if snap.get("simTime"):
        return float(snap["simTime"])
    m = re.match(r"\s*(-?\d+(?:\.\d+)?)", snap.get("simTimeText") or "")
    return float(m.group(1)) if m else None


def alive(snap, name):
    row = snap["nodes"].get(name)
    return bool(row) and "alive" in row["classes"]


def describe_nodes(snap, names):
    parts = []
    for name in names:
        row = snap["nodes"].get(name)
        parts.append(f"{name} " + ("(no row)" if not row else
                                   f"[{' '.join(row['classes'])}] age {row['age']} s"))
    return ", ".join(parts)


class Station:
    """The checks, against one page in one browser session."""

    def __init__(self, driver, args, deadline):
        self.wd, self.args, self.deadline = driver, args, deadline
        self.nodes = [n for n in args.nodes.split(",") if n]

    def snapshot(self):
        return self.wd.execute(SNAPSHOT_JS)

    def wait(self, probe, within):
        """Polls probe() -> (ok, seen) until ok, `within` seconds, or the overall deadline;
        returns (ok, seen, seconds waited)."""
        start = time.monotonic()
        end = min(start + within, self.deadline)
        while True:
            ok, seen = probe()
            if ok or time.monotonic() >= end:
                return ok, seen, time.monotonic() - start
            time.sleep(0.1)

    def until(self, condition, within):
        """wait() on a condition of the page's snapshot; returns (ok, snapshot, seconds)."""
        def probe():
            snap = self.snapshot()
            return condition(snap), snap
        return self.wait(probe, within)

    def sleep(self, seconds):
        if time.monotonic() + seconds > self.deadline:
            raise CheckFailed(f"the overall --timeout {self.args.timeout} s ran out")
        time.sleep(seconds)

    def click(self, css):
        element = self.wd.find(css)
        if element is None:
            raise CheckFailed(f"no element {css} on the page")
        self.wd.click(element)

    def run(self, check, name, body):
        try:
            print(f"ok {check} {name}: {body()}", flush=True)
        except (CheckFailed, WebDriverError) as e:
            raise CheckFailed(f"FAIL check {check} ({name}): {e}") from None

    # 1
    def page_live(self):
        self.wd.navigate(self.args.url)
        loaded_at = time.monotonic()

        def probe():
            nonlocal loaded_at
            snap = self.snapshot()
            if snap["conn"] is None and time.monotonic() - loaded_at > 1.0:
                self.wd.navigate(self.args.url)   # an error page: the station may be starting
                loaded_at = time.monotonic()
            return snap["conn"] == "live", snap
        ok, snap, waited = self.wait(probe, 15)
        if not ok and snap["conn"] is None:
            raise CheckFailed(f"the station's page did not load in {waited:.1f} s: "
                              f"at {snap['url']} (title {snap['title']!r})")
        if not ok:
            raise CheckFailed(f"#conn says {snap['conn']!r} after {waited:.1f} s")
        return f"#conn live after {waited:.1f} s, sim time {snap['simTimeText']}"

    # 2
    def nodes_alive(self):
        ok, snap, waited = self.until(lambda s: all(alive(s, n) for n in self.nodes), 10)
        if not ok:
            raise CheckFailed(f"after {waited:.1f} s: {describe_nodes(snap, self.nodes)} "
                              f"(rows on the page: {sorted(snap['nodes']) or 'none'})")
        return describe_nodes(snap, self.nodes)

    # 3
    def view_not_blank(self):
        def probe():
            s = self.wd.execute(VIEW_STATS_JS)
            return s["loaded"] and s["stddev"] > 10 and s["colours"] > 20, s
        ok, stats, waited = self.wait(probe, 20)
        if not stats["loaded"]:
            raise CheckFailed(f"#view has not loaded a frame after {waited:.1f} s "
                              f"({stats.get('why')}, src {stats.get('src')!r})")
        seen = (f"{stats['width']}x{stats['height']}, luminance stddev {stats['stddev']:.1f} "
                f"(need > 10), {stats['colours']} distinct colours (need > 20)")
        if not ok:
            raise CheckFailed(f"blank view after {waited:.1f} s: {seen}")
        return seen

    # 4
    def screenshot(self):
        png = self.wd.screenshot()
        if png[:8] != b"\x89PNG\r\n\x1a\n":
            raise CheckFailed(f"the screenshot is not a PNG (starts {png[:8]!r})")
        width, height = struct.unpack(">II", png[16:24])
        path = Path(self.args.screenshot)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(png)
        return f"{width}x{height}, {len(png)} bytes -> {path}"

    # 5
    def freeze_holds(self):
        self.click("#freeze")
        ok, snap, waited = self.until(lambda s: s["frozen"] == "FROZEN", 5)
        if not ok:
            raise CheckFailed(f"#frozen says {snap['frozen']!r} {waited:.1f} s after clicking "
                              f"#freeze (last ack {snap['lastAck']!r})")
        frozen_at = time.monotonic()
        self.sleep(0.5)   # a world state already on its way when the freeze landed
        t1 = sim_time(self.snapshot())
        if t1 is None:
            raise CheckFailed(f"no sim time on the page (#sim-time {snap['simTimeText']!r})")
        self.sleep(1.5)
        snap = self.snapshot()
        t2 = sim_time(snap)
        if t2 != t1 or snap["frozen"] != "FROZEN":
            raise CheckFailed(f"sim time {t1:.3f} s -> {t2} s over 1.5 s while #frozen says "
                              f"{snap['frozen']!r}: it must hold still")
        # node status keeps arriving while frozen: still alive past the station's stale limit
        self.sleep(max(0.0, frozen_at + ALIVE_WITHIN_S + 0.5 - time.monotonic()))
        snap = self.snapshot()
        t3 = sim_time(snap)
        if t3 != t1:
            raise CheckFailed(f"sim time {t1:.3f} s -> {t3} s while frozen")
        if not all(alive(snap, n) for n in self.nodes):
            raise CheckFailed("node status stopped while frozen: "
                              f"{describe_nodes(snap, self.nodes)}")
        held = time.monotonic() - frozen_at
        return (f"FROZEN {waited:.1f} s after the click; sim time {t1:.3f} s, still {t3:.3f} s "
                f"{held:.1f} s into the freeze; {describe_nodes(snap, self.nodes)}; "
                f"last ack {snap['lastAck']!r}")

    # 6
    def unfreeze_runs(self):
        t0 = sim_time(self.snapshot())
        self.click("#unfreeze")
        ok, snap, waited = self.until(
            lambda s: s["frozen"] == "RUNNING" and t0 is not None and (sim_time(s) or t0) > t0, 5)
        if not ok:
            raise CheckFailed(f"{waited:.1f} s after clicking #unfreeze: #frozen "
                              f"{snap['frozen']!r}, sim time {t0} s -> {sim_time(snap)} s")
        return (f"RUNNING, sim time {t0:.3f} s -> {sim_time(snap):.3f} s "
                f"{waited:.1f} s after the click")

    # 7
    def control_moves(self):
        controls = self.snapshot()["controls"]
        if self.args.control:
            rows = [c for c in controls if c["name"] == self.args.control]
        else:
            rows = [c for c in controls if len(c["buttons"]) >= 2]
        if not rows or len(rows[0]["buttons"]) < 2:
            raise CheckFailed(f"no control row {self.args.control or 'with two positions'} "
                              f"(rows: {[c['name'] for c in controls]})")
        row = rows[0]
        target = next((b for b in row["buttons"]
                       if not b["current"] and b["name"] != row["positionName"]), None)
        if target is None:
            raise CheckFailed(f"{row['name']}: no position other than {row['positionName']!r}")
        css = (f"#controls tr[data-control-id={json.dumps(row['id'])}] "
               f"button.set-position[data-position={json.dumps(target['position'])}]")
        self.click(css)

        def probe():
            for c in self.snapshot()["controls"]:
                if c["id"] == row["id"]:
                    return c["positionName"] == target["name"], c["positionName"]
            return False, None
        ok, seen, waited = self.wait(probe, 5)
        moved = f"{row['name']}: was {row['positionName']}, clicked {target['name']}"
        if not ok:
            raise CheckFailed(f"{moved}; .position-name says {seen!r} after {waited:.1f} s")
        return f"{moved}, the row shows {seen} after {waited:.1f} s"


@contextlib.contextmanager
def browser(args, url, prefix):
    """Headless Chromium under chromedriver, for a page at `url` (its host the only one that
    resolves); Skip when it cannot start here. Everything it started ends with the block."""
    for tool in (args.chromium, args.chromedriver):
        if not (os.path.isfile(tool) and os.access(tool, os.X_OK)):
            raise Skip(f"{tool} is not installed (or not executable)")
    workdir = Path(tempfile.mkdtemp(prefix=prefix))
    proc = driver = None
    try:
        port = args.driver_port or free_port()
        proc, driver = start_chromedriver(args.chromedriver, port, workdir)
        try:
            driver.start(args.chromium, chromium_args(workdir / "profile",
                                                      urllib.parse.urlsplit(url).hostname))
        except WebDriverError as e:
            if e.error == "session not created":
                raise Skip(f"chromium cannot start here: {e}"
                           f"{chromium_says(args.chromium, workdir)}") from None
            raise
        yield driver
    finally:
        if driver and driver.session:
            try:
                driver.quit()
            except (OSError, WebDriverError):
                pass
        if proc:
            stop_group(proc)
        shutil.rmtree(workdir, ignore_errors=True)


def run(args):
    deadline = time.monotonic() + args.timeout
    with browser(args, args.url, "vcockpit-instructor-browser-") as driver:
        station = Station(driver, args, deadline)
        station.run(1, "page live", station.page_live)
        station.run(2, "nodes alive", station.nodes_alive)
        station.run(3, "view not blank", station.view_not_blank)
        station.run(4, "screenshot", station.screenshot)
        station.run(5, "freeze holds sim time", station.freeze_holds)
        station.run(6, "unfreeze runs", station.unfreeze_runs)
        station.run(7, "control moves", station.control_moves)
        print("PASS: the instructor station's page passed all 7 checks")


# ---- self-test against the mock --------------------------------------------------------------

# (mock flags, expected exit status, the check that must be the one failing)
SCENARIOS = [([], PASS, None),
             (["--blank-view"], FAIL, 3),
             (["--stale-node", "image_generator"], FAIL, 2),
             (["--broken-freeze"], FAIL, 5),
             (["--silent-when-frozen"], FAIL, 5)]


def self_test(args):
    mock = Path(__file__).with_name("instructor_mock_server.py")
    workdir = Path(tempfile.mkdtemp(prefix="vcockpit-instructor-selftest-"))
    verdicts = []
    try:
        for flags, want, failing in SCENARIOS:
            server = subprocess.Popen([sys.executable, str(mock), "--port", "0", *flags],
                                      stdout=subprocess.PIPE, text=True)
            test = None
            try:
                url = server.stdout.readline().split()[-1]
                shot = args.screenshot if want == PASS and args.screenshot else workdir / "shot.png"
                cmd = [sys.executable, __file__, "--url", url, "--screenshot", str(shot),
                       "--chromium", args.chromium, "--chromedriver", args.chromedriver,
                       "--timeout", str(args.timeout), "--nodes", args.nodes]
                if args.control:
                    cmd += ["--control", args.control]
                label = " ".join(flags) or "well-behaved"
                print(f"--- mock {label}", flush=True)
                test = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                        text=True)
                output = []
                for line in test.stdout:
                    output.append(line)
                    print(f"    {line}", end="", flush=True)
                status = test.wait()
            finally:
                if test and test.poll() is None:   # interrupted: it cleans up on SIGTERM
                    test.terminate()
                    test.wait()
                server.terminate()
                server.wait()
            if status == SKIP:
                print(f"SKIP: the browser cannot run here (mock {label})")
                return SKIP
            good = status == want and (failing is None or
                                       any(l.startswith(f"FAIL check {failing} ") for l in output))
            expected = f"exit {want}" + (f", failing check {failing}" if failing else "")
            print(f"{'ok' if good else 'FAIL'} self-test, mock {label}: exit {status} "
                  f"(expected {expected})", flush=True)
            verdicts.append(good)
    finally:
        shutil.rmtree(workdir, ignore_errors=True)
    return PASS if all(verdicts) else FAIL


def main():
    ap = argparse.ArgumentParser(description="Headless-browser test of the instructor station.",
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__)
    ap.add_argument("--url", help="the station's page, e.g. http://127.0.0.1:8088/")
    ap.add_argument("--screenshot", help="where check 4 writes its PNG")
    ap.add_argument("--chromium", default="/usr/bin/chromium")
    ap.add_argument("--chromedriver", default="/usr/bin/chromedriver")
    ap.add_argument("--timeout", type=float, default=120.0, help="overall, seconds")
    ap.add_argument("--driver-port", type=int, default=0, help="default: a free loopback port")
    ap.add_argument("--nodes", default="physics_node,image_generator",
                    help="comma-separated nodes whose rows must be alive")
    ap.add_argument("--control", help="the control check 7 moves (default: the first with "
                                      "two positions or more)")
    ap.add_argument("--self-test", action="store_true",
                    help="run against instructor_mock_server.py, well-behaved and misbehaving")
    args = ap.parse_args()
    # SIGTERM (a test runner's timeout) unwinds like Ctrl-C: the session, chromedriver and the
    # temporary profile are cleaned up on the way out
    signal.signal(signal.SIGTERM, lambda signum, frame: sys.exit(128 + signum))
    if args.self_test:
        return self_test(args)
    if not args.url or not args.screenshot:
        ap.error("--url and --screenshot are required (or --self-test)")
    host = urllib.parse.urlsplit(args.url).hostname or ""
    try:
        loopback = host == "localhost" or ipaddress.ip_address(host).is_loopback
    except ValueError:
        loopback = False
    if not loopback:
        ap.error(f"--url must be on loopback (127.0.0.0/8 or localhost), not {host!r}")
    try:
        run(args)
        return PASS
    except Skip as e:
        print(f"SKIP: {e}")
        return SKIP
    except CheckFailed as e:
        print(e)
        return FAIL
    except (OSError, WebDriverError) as e:
        print(f"FAIL: the browser session broke: {e}")
        return FAIL


if __name__ == "__main__":
    sys.exit(main())
