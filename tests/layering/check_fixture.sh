#!/usr/bin/env bash
# The layering check catches what it says it does: on a copy of the source folders it passes,
# and each of these, added to the copy on its own, fails it with the file and line named:
# an include up the shared layers, one node including another, a pure folder including YAML or
# DDS, a node's folder including one above it, and a new folder placed in no layer.
# Usage: check_fixture.sh SOURCE_DIR WORK_DIR
set -u
src=$1
work=$2/layering_fixture
check="$src/tests/layering/check_includes.py"
status=0
fail() { echo "FAIL: $*"; status=1; }

fresh_copy() {
  rm -rf "$work" && mkdir -p "$work"
  for d in common hand idl dds glove_driver physics_node image_generator launcher instructor; do
    (cd "$src" && find "$d" -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.c' -o -name '*.h' \) \
       -exec cp --parents {} "$work" \;)
  done
}

# expect_caught FILE LINE-TEXT EXPECTED-OUTPUT: appends the line to FILE in a fresh copy
expect_caught() {
  local file=$1 line=$2 expected=$3 out
  fresh_copy
  mkdir -p "$(dirname "$work/$file")"
  echo "$line" >> "$work/$file"
  if out=$("$check" "$work" 2>&1); then
    fail "not caught: '$line' in $file"
  elif ! grep -qF -- "$expected" <<< "$out"; then
    fail "'$line' in $file: expected '$expected' in: $out"
  else
    echo "caught: $(grep -F -- "$expected" <<< "$out" | head -1)"
  fi
}

fresh_copy
out=$("$check" "$work" 2>&1) || fail "the unchanged copy fails: $out"

n=$(wc -l < "$work/common/clock.hpp")
expect_caught common/clock.hpp '#include "dds/dds_participant.hpp"' \
  "common/clock.hpp:$((n + 1)): #include \"dds/dds_participant.hpp\" (a layer above)"
expect_caught idl/topics/topic_traits.hpp '#include "dds/dds_options.hpp"' "(a layer above)"
expect_caught hand/tracker.cpp '#include "hand/config/hand_yaml.hpp"' \
  "(a pure folder includes DDS, IDL or YAML)"
expect_caught physics_node/physics/world.cpp '#include <yaml-cpp/yaml.h>' \
  "(a pure folder includes DDS, IDL or YAML)"
expect_caught physics_node/io/offline_runner.cpp '#include "dds/dds_participant.hpp"' \
  "(a pure folder includes DDS, IDL or YAML)"
expect_caught glove_driver/node/recorder.cpp '#include "physics_node/physics/world.hpp"' \
  "(another node's folder)"
expect_caught physics_node/config/scene_config.cpp '#include "physics_node/node/node_loop.hpp"' \
  "(a layer above)"
expect_caught launcher/extra/new_thing.cpp '#include "common/clock.hpp"' \
  "launcher/extra/: a folder of source files in no layer"

rm -rf "$work"
[ $status -eq 0 ] && echo "the layering check caught every fixture"
exit $status
