#pragma once
// A model file read in a child process. Assimp 5.2 (Debian's) crashes on some malformed files
// (a fuzzed OBJ segfaults inside its importer within a few thousand inputs), and a physics node
// or image generator must not die of a bad file it was given: the reader runs in a forked child,
// which sends the mesh (or its error) back through a pipe, and a child that crashes, hangs past
// its time or says nothing becomes a MeshError naming the file. The child dies with its parent
// (PR_SET_PDEATHSIG) and has no more CPU time than the timeout. A parent with other threads may
// fork it: the child only reads the file and writes the pipe (glibc keeps malloc and stdio
// usable in a child of a threaded process), and the parent waits at most the timeout.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "model/triangle_mesh.hpp"

namespace vcockpit::model {

// One part of a model file as read: its mesh, or why there is none (a MeshError's message).
struct ModelPart {
  std::optional<TriangleMesh> mesh;
  std::string error;
};

// `read` in a child process; its MeshError (or any std::exception) comes back as a MeshError
// with the same message. `what` names the file in the errors made here.
TriangleMesh read_isolated(const std::function<TriangleMesh()>& read, const std::string& what,
                           int timeout_s = 30);

// The same for several parts of one file read in one go: each part's mesh or error comes back
// in its place; an exception `read` throws (the file itself unreadable) is the MeshError thrown.
std::vector<ModelPart> read_isolated_parts(const std::function<std::vector<ModelPart>()>& read,
                                          const std::string& what, int timeout_s = 30);

}  // namespace vcockpit::model
