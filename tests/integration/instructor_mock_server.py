#!/usr/bin/python3
"""A stand-in for the instructor station's HTTP server, with a fake simulation behind it.

It serves instructor/web/ and the station's JSON API (docs in instructor/web/app.js) so the page
and tests/integration/instructor_browser_test.py can be developed and checked without the rig:

  /usr/bin/python3 tests/integration/instructor_mock_server.py --port 8088
  # open http://127.0.0.1:8088/ ; --port 0 picks a free port, printed on the first line

The fake: sim time advances 1 s/s unless frozen; commands are acknowledged 0.15 s later, control
moves land 0.3 s later (as they would through the rig); the right hand grasps and releases the
cup every 4 s of sim time; three nodes report status twice a second; the view is a drawn
cockpit (a hand that moves with sim time), 503 for the first 0.5 s.

Misbehaviours the browser test must catch:
  --broken-freeze       says FROZEN but sim time keeps advancing
  --blank-view          the view is a uniform grey frame
  --stale-node NAME     that node's last status is 10 s old from the start
  --silent-when-frozen  no node status arrives while frozen (the nodes go stale)
"""
import argparse
import json
import math
import struct
import sys
import threading
import time
import zlib
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from urllib.parse import parse_qs, urlsplit

WEB_DIR = Path(__file__).resolve().parents[2] / "instructor" / "web"
STATIC = {"/": ("index.html", "text/html; charset=utf-8"),
          "/app.js": ("app.js", "text/javascript; charset=utf-8"),
          "/style.css": ("style.css", "text/css; charset=utf-8")}
COMMANDS = ("freeze", "unfreeze", "reset_start", "save_checkpoint", "reset_checkpoint",
            "restart_replay")
ACK_DELAY_S = 0.15
CONTROL_DELAY_S = 0.3
STATUS_PERIOD_S = 0.5
ALIVE_WITHIN_S = 3.0
GRASP_EVERY_S = 4.0
VIEW_W, VIEW_H = 640, 360


def png(width, height, rgb):
    """An 8-bit RGB PNG of the packed rows in rgb."""
    def chunk(tag, data):
        return (struct.pack(">I", len(data)) + tag + data
                + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF))
    stride = width * 3
    raw = b"".join(b"\0" + bytes(rgb[y * stride:(y + 1) * stride]) for y in range(height))
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)   # 8-bit RGB
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header)
            + chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b""))


class Canvas:
    """Just enough drawing for a recognisable cockpit: filled rectangles on an RGB buffer."""

    def __init__(self, w, h, colour=(0, 0, 0)):
        self.w, self.h = w, h
        self.px = bytearray(bytes(colour) * (w * h))

    def rect(self, x0, y0, x1, y1, colour):
        x0, x1 = max(0, int(x0)), min(self.w, int(x1))
        y0, y1 = max(0, int(y0)), min(self.h, int(y1))
        if x1 <= x0:
            return
        row = bytes(colour) * (x1 - x0)
        for y in range(y0, y1):
            start = (y * self.w + x0) * 3
            self.px[start:start + len(row)] = row


def draw_cockpit(sim_time_s):
    c = Canvas(VIEW_W, VIEW_H)
    for y in range(150):  # sky through the windscreen, darker at the top
        f = y / 150
        c.rect(0, y, VIEW_W, y + 1, (int(40 + 110 * f), int(70 + 110 * f), int(120 + 90 * f)))
    c.rect(0, 150, VIEW_W, 175, (28, 30, 34))                    # glareshield
    c.rect(0, 175, VIEW_W, 290, (62, 66, 72))                    # instrument panel
    for i in range(6):                                           # instruments with needles
        x = 40 + i * 95
        c.rect(x, 190, x + 70, 260, (12, 12, 14))
        c.rect(x + 33, 200 + (i * 7) % 40, x + 37, 225 + (i * 7) % 40, (235, 235, 235))
    for i, colour in enumerate([(40, 200, 90), (240, 170, 30), (220, 50, 40), (60, 140, 230)]):
        c.rect(60 + i * 40, 270, 90 + i * 40, 282, colour)       # annunciators
    c.rect(0, 290, 400, VIEW_H, (34, 36, 42))                    # floor
    c.rect(40, 300, 150, VIEW_H, (70, 70, 78))                   # throttle pedestal
    c.rect(80, 305, 92, 335, (20, 20, 20))                       # the throttle lever
    c.rect(400, 290, VIEW_W, VIEW_H, (90, 72, 55))               # centre console
    c.rect(470, 300, 500, 340, (225, 225, 215))                  # the cup
    hx = 300 + 120 * math.sin(sim_time_s * 0.8)                  # the right hand, moving
    c.rect(hx, 250, hx + 60, 320, (214, 170, 140))
    c.rect(hx + 10, 240, hx + 50, 250, (190, 150, 120))
    return png(VIEW_W, VIEW_H, c.px)


def grey_frame():
    return png(VIEW_W, VIEW_H, Canvas(VIEW_W, VIEW_H, (128, 128, 128)).px)


class FakeSim:
    """The station's view of the rig, advanced lazily on each request (under one lock)."""

    def __init__(self, args):
        self.args = args
        self.lock = threading.Lock()
        self.t0 = time.monotonic()
        self.sim_base, self.sim_since, self.frozen = 0.0, self.t0, False
        self.frozen_since = None
        self.seq = 0
        self.pending = []          # (due, seq, kind, payload)
        self.last_ack = None
        self.checkpoints = {}
        self.events = []
        self.grasp_slot = 0
        self.holding = None
        self.controls = [
            {"control_id": 0, "name": "landing_gear", "kind": "LEVER", "positions": ["UP", "DOWN"]},
            {"control_id": 1, "name": "landing_lights", "kind": "TOGGLE",
             "positions": ["OFF", "TAXI", "LAND"]},
            {"control_id": 2, "name": "fuel_pump", "kind": "TOGGLE", "positions": ["OFF", "ON"]},
        ]
        for c in self.controls:
            self._set_position(c, 0)
        self.nodes = [("physics_node", 1000.0, 250.0), ("image_generator", 30.0, 1000.0),
                      ("glove_driver_right", 250.0, None)]
        self.view_cache = (None, None)

    # --- time ---------------------------------------------------------------------------------
    def _sim_time(self, now):
        rate = 0.0 if self.frozen and not self.args.broken_freeze else 1.0
        return self.sim_base + (now - self.sim_since) * rate

    def _set_sim_time(self, now, t):
        self.sim_base, self.sim_since = t, now

    def _advance(self, now):
        self._grasp_cycle(self._sim_time(now))
        for item in [p for p in self.pending if p[0] <= now]:
            self.pending.remove(item)
            self._apply(now, *item[1:])

    def _grasp_cycle(self, t):
        """The right hand takes the cup at one multiple of 4 s sim time, lets go at the next."""
        slot = int(t // GRASP_EVERY_S)
        if slot < self.grasp_slot:      # sim time went back (a reset)
            self.grasp_slot = slot
        while self.grasp_slot < slot:
            self.grasp_slot += 1
            at = self.grasp_slot * GRASP_EVERY_S
            if self.holding is None:
                self.holding = "cup"
                self._event("grasp", at, "GRASP cup (right hand): force and torque balance, "
                            "3 contacts, gesture holds")
            else:
                self.holding = None
                self._event("release", at, "RELEASE cup (right hand): the grip opened")

    def _event(self, kind, sim_time_s, text):
        self.events.append({"seq": len(self.events), "kind": kind,
                            "sim_time_s": round(sim_time_s, 3), "text": text})

    # --- commands -----------------------------------------------------------------------------
    def submit(self, kind, payload):
        with self.lock:
            now = time.monotonic()
            self._advance(now)
            self.seq += 1
            delay = ACK_DELAY_S if kind == "sim" else CONTROL_DELAY_S
            self.pending.append((now + delay, self.seq, kind, payload))
            return self.seq

    def _apply(self, now, seq, kind, payload):
        t = self._sim_time(now)
        if kind == "control":
            c = self.controls[payload["control_id"]]
            self._set_position(c, payload["position"])
            self._event("control", t, f"CONTROL {c['name']} -> {c['position_name']} (instructor)")
            return
        command, name = payload["command"], payload.get("checkpoint", "default")
        accepted, detail = True, ""
        if command == "freeze":
            self._set_sim_time(now, t)
            self.frozen, self.frozen_since = True, now
            detail = f"frozen at {t:.3f} s"
        elif command == "unfreeze":
            self._set_sim_time(now, t)
            self.frozen, self.frozen_since = False, None
            detail = f"running from {t:.3f} s"
        elif command in ("reset_start", "restart_replay"):
            self._set_sim_time(now, 0.0)
            self.holding = None
            for c in self.controls:
                self._set_position(c, 0)
            detail = "back to the start" if command == "reset_start" else "replay restarted"
        elif command == "save_checkpoint":
            self.checkpoints[name] = (t, [c["position"] for c in self.controls], self.holding)
            detail = f"checkpoint '{name}' at {t:.3f} s"
        elif name in self.checkpoints:   # reset_checkpoint
            at, positions, self.holding = self.checkpoints[name]
            self._set_sim_time(now, at)
            for c, p in zip(self.controls, positions):
                self._set_position(c, p)
            detail = f"back to checkpoint '{name}' at {at:.3f} s"
        else:
            accepted, detail = False, f"no checkpoint '{name}'"
        self.last_ack = {"seq": seq, "command": command, "accepted": accepted, "detail": detail}
        self._event("sim", self._sim_time(now), f"SIM {command}: "
                    f"{'accepted' if accepted else 'refused'}, {detail}")

    @staticmethod
    def _set_position(c, p):
        c.update(position=p, position_name=c["positions"][p],
                 coordinate=round(p / (len(c["positions"]) - 1), 3),
                 lit=c["name"] == "landing_gear" and p == 1, held_by=-1)

    # --- replies ------------------------------------------------------------------------------
    def state(self):
        with self.lock:
            now = time.monotonic()
            self._advance(now)
            t = self._sim_time(now)
            nodes = []
            for name, loop_hz, input_hz in self.nodes:
                age = (now - self.t0) % STATUS_PERIOD_S
                if name == self.args.stale_node:
                    age = 10.0 + now - self.t0
                elif self.args.silent_when_frozen and self.frozen_since is not None:
                    age = now - self.frozen_since
                nodes.append({"name": name, "state": "RUNNING", "detail": "tracking",
                              "loop_rate_hz": loop_hz, "input_rate_hz": input_hz,
                              "late_steps": 0, "rejected": 0, "glove_lost": 0,
                              "age_s": round(age, 3), "alive": age < ALIVE_WITHIN_S})
            up = now - self.t0
            view = None if up < 0.5 else {"frame_seq": int(up * 30), "sim_time_s": round(t, 3),
                                          "width_px": VIEW_W, "height_px": VIEW_H, "age_s": 0.03}
            return {"stamp_s": round(now, 3),
                    "sim": {"sim_time_s": round(t, 3), "frozen": self.frozen,
                            "checkpoints": sorted(self.checkpoints), "last_ack": self.last_ack},
                    "nodes": nodes,
                    "hands": [{"hand_id": 0, "side": "right", "tracking": True,
                               "holding": self.holding},
                              {"hand_id": 1, "side": "left", "tracking": False, "holding": None}],
                    "controls": [dict(c) for c in self.controls],
                    "view": view,
                    "events_next": len(self.events)}

    def events_after(self, after):
        with self.lock:
            self._advance(time.monotonic())
            chosen = (self.events[-200:] if after < 0 else self.events[after + 1:after + 201])
            return {"events": chosen, "next": len(self.events)}

    def view_png(self):
        """The newest frame, or None before the first (the server's 503)."""
        with self.lock:
            now = time.monotonic()
            if now - self.t0 < 0.5:
                return None
            t = round(self._sim_time(now), 1)   # a new picture only when the scene moved
            if self.view_cache[0] != t:
                self.view_cache = (t, grey_frame() if self.args.blank_view else draw_cockpit(t))
            return self.view_cache[1]


class Handler(BaseHTTPRequestHandler):
    protocol_version = "HTTP/1.1"
    sim = None      # set in main()
    verbose = False

    def log_message(self, fmt, *args):
        if self.verbose:
            super().log_message(fmt, *args)

    def _send(self, status, body, ctype="application/json"):
        if not isinstance(body, bytes):
            body = json.dumps(body).encode()
        self.send_response(status)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        self.end_headers()
        self.wfile.write(body)

    def do_GET(self):
        url = urlsplit(self.path)
        if url.path in STATIC:
            name, ctype = STATIC[url.path]
            return self._send(200, (WEB_DIR / name).read_bytes(), ctype)
        if url.path == "/api/state":
            return self._send(200, self.sim.state())
        if url.path == "/api/events":
            try:
                after = int(parse_qs(url.query).get("after", ["-1"])[0])
            except ValueError:
                return self._send(400, {"error": "after must be an integer"})
            return self._send(200, self.sim.events_after(after))
        if url.path == "/view.png":
            frame = self.sim.view_png()
            if frame is None:
                return self._send(503, {"error": "no view yet"})
            return self._send(200, frame, "image/png")
        self._send(404, {"error": "not found"})

    def do_POST(self):
        try:
            body = json.loads(self.rfile.read(int(self.headers.get("Content-Length", 0))))
        except (ValueError, json.JSONDecodeError):
            return self._send(400, {"error": "body is not JSON"})
        if not isinstance(body, dict):
            return self._send(400, {"error": "body is not a JSON object"})
        path = urlsplit(self.path).path
        if path == "/api/sim":
            if body.get("command") not in COMMANDS:
                return self._send(400, {"error": f"unknown command {body.get('command')!r}"})
            if not isinstance(body.get("checkpoint", "default"), str):
                return self._send(400, {"error": "checkpoint must be a string"})
            return self._send(200, {"seq": self.sim.submit("sim", body)})
        if path == "/api/control":
            cid, pos = body.get("control_id"), body.get("position")
            controls = self.sim.controls
            if (type(cid) is not int or not 0 <= cid < len(controls) or type(pos) is not int
                    or not 0 <= pos < len(controls[cid]["positions"])):
                return self._send(400, {"error": "unknown control or position"})
            return self._send(200, {"seq": self.sim.submit("control", body)})
        self._send(404, {"error": "not found"})


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--host", default="127.0.0.1")
    ap.add_argument("--port", type=int, default=8088, help="0: any free port")
    ap.add_argument("--broken-freeze", action="store_true")
    ap.add_argument("--blank-view", action="store_true")
    ap.add_argument("--stale-node", metavar="NAME")
    ap.add_argument("--silent-when-frozen", action="store_true")
    ap.add_argument("--verbose", action="store_true", help="log every request")
    args = ap.parse_args()
    Handler.sim, Handler.verbose = FakeSim(args), args.verbose
    server = ThreadingHTTPServer((args.host, args.port), Handler)
    server.daemon_threads = True
    print(f"instructor mock listening on http://{args.host}:{server.server_address[1]}/",
          flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()


if __name__ == "__main__":
    sys.exit(main())
