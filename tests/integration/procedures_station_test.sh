#!/usr/bin/env bash
# The procedures trainer in a real browser: the rig of config/rig_procedures.yaml with the
# instructor station (rig_launcher --ui), its glove replaying procedures_right.csv at twice real
# time, on the test's domain; two runs of tests/integration/procedures_browser_test.py:
#   1. gear_unsafe: the instructor inserts "gear unsafe" from the page; the abnormal is scored;
#   2. reset: the run is frozen, reset to the start, restarted and scored again;
# then Ctrl-C: summary.json has the lesson's score and report.html (and report.png) are written;
# a bad failure command is refused with 400 naming it.
# Exit 77 (skip) only when Chromium cannot run here.
set -uo pipefail
src=${VCOCKPIT_SOURCE_DIR:?}
bin=${VCOCKPIT_BIN_DIR:?}
domain=${VCOCKPIT_DOMAIN:?}
tmp=${VCOCKPIT_TEST_TMP:?}/procedures_station
rm -rf "$tmp"; mkdir -p "$tmp/rigcfg"
py=/usr/bin/python3
fail=0
check() { if eval "$1"; then echo "ok: $2"; else echo "FAIL: $2"; fail=1; fi; }
rig_pid=""
cleanup() { [ -n "$rig_pid" ] && kill -9 "$rig_pid" 2>/dev/null; wait 2>/dev/null; }
trap cleanup EXIT
export VCOCKPIT_DOMAIN=$domain VCOCKPIT_QOS_FILE=$src/config/qos.xml
unset VCOCKPIT_PARTICIPANT VCOCKPIT_PKI_DIR VCOCKPIT_IDENTITY

port=$($py -c "import socket; s=socket.socket(); s.bind(('127.0.0.1', 0)); print(s.getsockname()[1])")
url=http://127.0.0.1:$port
for f in qos.xml cockpit.yaml models hmd.yaml hand.yaml aircraft.yaml instruments.yaml glove_logs lessons procedures; do
  ln -s "$src/config/$f" "$tmp/rigcfg/$f"
done
sed -e "s/^domain: .*/domain: $domain/" -e 's/--rate, "1"/--rate, "2"/' \
  "$src/config/rig_procedures.yaml" > "$tmp/rigcfg/rig.yaml"
grep -q -- '--rate, "2"' "$tmp/rigcfg/rig.yaml" || { echo "FAIL: no --rate to set in rig_procedures.yaml"; exit 1; }
"$bin/rig_launcher" "$tmp/rigcfg/rig.yaml" --ui --ui-port "$port" --out "$tmp/rig" --quiet \
  > "$tmp/rig.log" 2>&1 &
rig_pid=$!

source "$src/tests/integration/station_api.sh"  # api METHOD PATH [BODY]
for _ in $(seq 1 100); do
  api GET /api/state | grep -q '"failures":\[{' && break
  sleep 0.2
done
check "api GET /api/state | grep -q '\"failures\":\[{'" "the station knows the systems node's failures"
check "api POST /api/failure '{\"failure\": \"wing_fell_off\", \"inserted\": true}' | grep -q \"^400 .*unknown 'wing_fell_off'\"" \
  "an unknown failure: 400 naming it"
check "api POST /api/failure '{\"failure\": \"engine_fire\"}' | grep -q '^400 '" "a failure command without inserted: 400"

skipped=0
for scenario in gear_unsafe reset; do
  $py "$src/tests/integration/procedures_browser_test.py" --url "$url/" --scenario $scenario \
    --screenshot "$tmp/procedures_$scenario.png" --timeout 150 > "$tmp/browser_$scenario.log" 2>&1
  status=$?
  cat "$tmp/browser_$scenario.log"
  if [ $status -eq 77 ]; then
    skipped=1
    echo "SKIP: the browser checks (Chromium cannot run here)"
    break
  fi
  check "[ $status -eq 0 ]" "scenario $scenario in headless Chromium (exit $status)"
done
# every event the station keeps, page by page
$py - "$url" > "$tmp/events.txt" <<'PY'
import json, sys, urllib.request
opener = urllib.request.build_opener(urllib.request.ProxyHandler({}))
after = 0
while True:
    with opener.open(f"{sys.argv[1]}/api/events?after={after}", timeout=5) as r:
        reply = json.load(r)
    for e in reply["events"]:
        print(e["text"])
    if not reply["events"]:
        break
    after = reply["next"] - 1
PY
check "grep -q 'FAILURE gear_unsafe_left inserted' '$tmp/events.txt'" "the failure's insertion is an event on the page"
check "grep -q 'SIM reset_start by systems_node: systems and procedure scores back to the start' '$tmp/events.txt'" \
  "the systems node acknowledged the reset"

kill -INT "$rig_pid"
status=124
for _ in $(seq 1 300); do
  if ! kill -0 "$rig_pid" 2>/dev/null; then wait "$rig_pid"; status=$?; break; fi
  sleep 0.1
done
rig_pid=""
check "[ $status -eq 0 ]" "Ctrl-C ends the run (exit $status)"
check "$py -c \"import json,sys; s=json.load(open('$tmp/rig/summary.json')); p=s['procedures']; sys.exit(0 if p and len(p['list']) == 4 else 1)\"" \
  "summary.json has the lesson's four procedures"
check "grep -q 'data-complete=' '$tmp/rig/report.html'" "report.html written"
check "[ -s '$tmp/rig/report.png' ]" "report.png written"
[ $fail -ne 0 ] && { tail -n 40 "$tmp/rig.log"; exit 1; }
[ $skipped -eq 1 ] && exit 77
echo "procedures_station_test: passed"
exit 0
