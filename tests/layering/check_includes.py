#!/usr/bin/env python3
"""The include half of the layering of docs/ARCHITECTURE.md (the link half is
cmake/forbid_links.cmake). Every folder of the product code is in exactly one layer; a file may
include its own folder and folders of lower layers, never one above or beside it:

  common < model < model/import < hand < hand/tracking < hand/config < systems < systems/config < idl/topics (and the generated IDL types) < dds < the nodes

A node's folders are ordered among themselves the same way, and no node includes another node.
The pure folders include no DDS, no IDL types and no YAML. A folder with source files that is in
no layer is an error too: a new folder has to be placed.

Usage: check_includes.py SOURCE_DIR. Prints every offending include as FILE:LINE and exits 1 if
there is one.
"""
import os
import re
import sys

# The shared layers, bottom up.
SHARED = ["common", "model", "model/import", "hand", "hand/tracking", "hand/config", "systems", "systems/config",
          "idl/topics", "dds"]
# Each node's folders, bottom up; the node's own top folder (its main) last.
NODES = {
    "glove_driver": ["glove_driver/degrade", "glove_driver/glove", "glove_driver/openxr",
                     "glove_driver/openxr/replay_runtime", "glove_driver/node", "glove_driver"],
    "physics_node": ["physics_node/physics", "physics_node/io", "physics_node/fit",
                     "physics_node/config", "physics_node/node", "physics_node"],
    "image_generator": ["image_generator/render", "image_generator/node", "image_generator"],
    "launcher": ["launcher"],
    "instructor": ["instructor"],
    "systems_node": ["systems_node/node", "systems_node"],
}
# No DDS, no IDL types, no YAML: what the offline runner and the tests drive on their own.
PURE = ["model", "model/import", "hand", "hand/tracking", "systems", "glove_driver/degrade", "glove_driver/openxr",
        "glove_driver/openxr/replay_runtime", "physics_node/physics", "physics_node/io",
        "physics_node/fit", "image_generator/render"]
PURE_MAY_NOT = re.compile(r"^(fastdds|fastrtps|fastcdr|yaml-cpp)/|^(idl|dds|hand/config|systems/config)/|"
                          r"^common/yaml_config\.hpp$|^(cockpit|systems)(PubSubTypes)?\.h$")
# fastddsgen's output, included by bare name: the IDL layer
GENERATED_IDL = {"cockpit.h", "cockpitPubSubTypes.h", "systems.h", "systemsPubSubTypes.h"}

SOURCE = re.compile(r".*\.(c|cc|cpp|h|hpp)$")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def layer_of(folder):
    """(node or None, rank) of a folder, or None when it is in no layer."""
    if folder in SHARED:
        return (None, SHARED.index(folder))
    for node, folders in NODES.items():
        if folder in folders:
            return (node, len(SHARED) + folders.index(folder))
    return None


def may_include(src, dst):
    """Whether a file in folder `src` may include a header of folder `dst`."""
    if src == dst:
        return True
    a, b = layer_of(src), layer_of(dst)
    if b is None:
        return False
    if b[0] is not None and b[0] != a[0]:
        return False  # another node's folder
    return b[1] < a[1]


def check(root):
    problems = []
    roots = SHARED[:1] + ["model", "hand", "systems", "idl", "dds"] + list(NODES)
    seen_folders = set()
    for top in sorted(set(roots)):
        for dirpath, _, names in os.walk(os.path.join(root, top)):
            folder = os.path.relpath(dirpath, root)
            sources = sorted(n for n in names if SOURCE.match(n))
            if not sources:
                continue
            if folder == "idl":  # cockpit.idl's folder: generated code only, built elsewhere
                continue
            if layer_of(folder) is None:
                problems.append(f"{folder}/: a folder of source files in no layer "
                                "(place it in tests/layering/check_includes.py)")
                continue
            seen_folders.add(folder)
            for name in sources:
                path = os.path.join(folder, name)
                with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
                    for number, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if not m:
                            continue
                        quoted, header = m.group(1) == '"', m.group(2)
                        where = f"{path}:{number}: #include {line.split('include', 1)[1].strip()}"
                        if folder in PURE and PURE_MAY_NOT.search(header):
                            problems.append(f"{where} (a pure folder includes DDS, IDL or YAML)")
                            continue
                        if not quoted:
                            continue  # a system or library header
                        if "/" not in header:
                            target = "idl/topics" if header in GENERATED_IDL else folder
                        else:
                            target = os.path.dirname(header)
                        if not may_include(folder, target):
                            a, b = layer_of(folder), layer_of(target)
                            why = ("a folder in no layer" if b is None else
                                   "another node's folder" if b[0] not in (None, a[0]) else
                                   "a layer above")
                            problems.append(f"{where} ({why})")
    return problems


def main():
    if len(sys.argv) != 2:
        print(__doc__.strip().splitlines()[-2], file=sys.stderr)
        return 2
    problems = check(sys.argv[1])
    for p in problems:
        print(f"layering: {p}")
    if problems:
        return 1
    print("layering: every include goes down the layers")
    return 0


if __name__ == "__main__":
    sys.exit(main())
