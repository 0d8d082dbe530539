#!/usr/bin/env bash
# The include half of the layering (the link half is cmake/forbid_links.cmake): no node folder
# includes a header of another node folder, and the pure libraries include no DDS or YAML header.
# Usage: check_includes.sh SOURCE_DIR. Prints every offending line and exits 1 if there is one.
set -u
cd "$1" || exit 2
status=0
offend() { echo "layering: $*"; status=1; }

nodes=(glove_driver physics_node image_generator launcher instructor)
for a in "${nodes[@]}"; do
  for b in "${nodes[@]}"; do
    [ "$a" = "$b" ] && continue
    while IFS= read -r hit; do offend "$hit (a node includes another node's header)"; done \
      < <(grep -rnE "#include \"$b/" "$a" --include='*.cpp' --include='*.hpp')
  done
done
# below the nodes: the hand library, common and the topics layer include no node folder
for lower in hand common idl; do
  while IFS= read -r hit; do offend "$hit (a lower layer includes a node)"; done \
    < <(grep -rnE '#include "(glove_driver|physics_node|image_generator|launcher|instructor)/' "$lower" \
          --include='*.cpp' --include='*.hpp')
done
# the pure parts: no DDS, no generated IDL types, no YAML
pure=(hand physics_node/physics physics_node/io physics_node/fit glove_driver/glove glove_driver/degrade image_generator/render)
for dir in "${pure[@]}"; do
  while IFS= read -r hit; do offend "$hit (a pure library includes DDS or YAML)"; done \
    < <(grep -rnE '#include [<"](fastdds/|fastrtps/|fastcdr/|yaml-cpp/|cockpit\.h|cockpitPubSubTypes|common/dds_|common/yaml_config|idl/)' \
          "$dir" --include='*.cpp' --include='*.hpp' | grep -v '^hand/hand_yaml\.' | grep -v '^glove_driver/glove/gesture_script\.cpp')
done
[ $status -eq 0 ] && echo "layering: every include goes down the layers"
exit $status
