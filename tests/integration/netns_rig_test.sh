#!/usr/bin/env bash
# The rig across three network namespaces (scripts/netns-rig): the lockstep results on loopback
# and across the bridge both equal the offline runner's, the latency is printed, and nothing is
# left behind (namespaces, /dev/shm files). Skips (77) where namespaces cannot be made.
set -uo pipefail
src=${VCOCKPIT_SOURCE_DIR:?}
build=${VCOCKPIT_BUILD_DIR:?}
out=${VCOCKPIT_TEST_TMP:?}/netns_rig
# under the sanitizers the physics steps slower than real time: replay slower (lockstep keeps
# the results)
rate=1
[ "${VCOCKPIT_SANITIZED:-0}" = 1 ] && rate=0.4
shm_before=$(ls /dev/shm | sort)
ns_before=$(ip netns list 2>/dev/null | sort)
"$src/scripts/netns-rig" --no-build --build-dir "$build" --out "$out" --domain "${VCOCKPIT_DOMAIN:?}" --rate "$rate" \
  > "$out.log" 2>&1
status=$?
cat "$out.log"
[ $status -eq 77 ] && exit 77
fail=0
[ $status -eq 0 ] || { echo "FAIL: scripts/netns-rig exited $status"; fail=1; }
for run in loopback netns; do
  for f in trajectories.csv events.jsonl; do
    grep -q "netns-rig: $run: $f equals the offline runner's" "$out.log" ||
      { echo "FAIL: $run $f not equal to the offline runner's"; fail=1; }
  done
  grep -qE "netns-rig: $run: glove -> physics DDS transit p50 [0-9.]+ us" "$out.log" ||
    { echo "FAIL: no $run latency"; fail=1; }
done
# the image generator across the bridge got the world and rendered it
[ -f "$out/netns/frames/frame_000000.png" ] || { echo "FAIL: no frame rendered in the namespace"; fail=1; }
ns_after=$(ip netns list 2>/dev/null | sort)
[ "$ns_before" = "$ns_after" ] || { echo "FAIL: namespaces left: $ns_after"; fail=1; }
shm_after=$(ls /dev/shm | sort)
left=$(comm -13 <(echo "$shm_before") <(echo "$shm_after") | grep -E '^(sem\.)?(fastrtps_|fast_datasharing_)' || true)
[ -z "$left" ] || { echo "FAIL: /dev/shm files left: $left"; fail=1; }
[ $fail -eq 0 ] && echo "netns_rig_test: passed"
exit $fail
