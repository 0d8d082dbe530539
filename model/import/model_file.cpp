#include "model/import/model_file.hpp"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <filesystem>
#include <functional>

#include "model/import/isolated_reader.hpp"

namespace vcockpit::model {
namespace {

constexpr unsigned kReadFlags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                aiProcess_SortByPType | aiProcess_ValidateDataStructure;

// "gltf", "glb", "obj" or "ac" (lower case, no dot), else refused naming `path`.
std::string supported_extension(const std::string& path, std::string ext) {
  if (!ext.empty() && ext.front() == '.') ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != "gltf" && ext != "glb" && ext != "obj" && ext != "ac")
    throw MeshError(path +
                    ": unsupported model format (glTF .gltf/.glb, Wavefront .obj, AC3D .ac)");
  return ext;
}

void prepare(Assimp::Importer& importer) {
  // points and lines dropped: only triangles collide and draw
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
}

const aiScene* checked(const aiScene* scene, const Assimp::Importer& importer,
                       const std::string& path) {
  if (scene == nullptr || scene->mRootNode == nullptr)
    throw MeshError(path + ": not a readable model: " + importer.GetErrorString());
  return scene;
}

const aiScene* read_scene(Assimp::Importer& importer, const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw MeshError(path + ": no such file");
  supported_extension(path, std::filesystem::path(path).extension().string());
  prepare(importer);
  return checked(importer.ReadFile(path, kReadFlags), importer, path);
}

void node_names(const aiNode* node, std::vector<std::string>& out) {
  out.emplace_back(node->mName.C_Str());
  for (unsigned i = 0; i < node->mNumChildren; ++i)
    node_names(node->mChildren[i], out);
}

std::array<float, 4> base_color(const aiScene* scene, const aiMesh* mesh) {
  std::array<float, 4> rgba{0.6f, 0.6f, 0.6f, 1.0f};
  if (mesh->mMaterialIndex >= scene->mNumMaterials) return rgba;
  const aiMaterial* material = scene->mMaterials[mesh->mMaterialIndex];
  aiColor4D c;
  if (material->Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS ||
      material->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS)
    rgba = {c.r, c.g, c.b, c.a};
  return rgba;
}

TriangleMesh mesh_of(const aiScene* scene, const ModelRequest& request);

}  // namespace

TriangleMesh load_model_mesh(const ModelRequest& request) {
  return read_isolated(
      [&] {
        Assimp::Importer importer;
        return mesh_of(read_scene(importer, request.path), request);
      },
      request.path);
}

TriangleMesh load_model_mesh_from_memory(std::string_view bytes, const std::string& extension,
                                         const ModelRequest& request) {
  const std::string hint = supported_extension(request.path, extension);
  if (bytes.empty()) throw MeshError(request.path + ": not a readable model: no bytes");
  return read_isolated(
      [&] {
        Assimp::Importer importer;
        prepare(importer);
        const aiScene* scene =
            importer.ReadFileFromMemory(bytes.data(), bytes.size(), kReadFlags, hint.c_str());
        return mesh_of(checked(scene, importer, request.path), request);
      },
      request.path);
}

namespace {

TriangleMesh mesh_of(const aiScene* scene, const ModelRequest& request) {
  TriangleMesh mesh;
  mesh.source = request.path + (request.node.empty() ? "" : " node '" + request.node + "'");
  const aiNode* top = scene->mRootNode;
  if (!request.node.empty()) {
    top = scene->mRootNode->FindNode(request.node.c_str());
    if (top == nullptr) {
      std::vector<std::string> names;
      node_names(scene->mRootNode, names);
      std::string list;
      for (std::size_t i = 0; i < names.size() && i < 20; ++i)
        list += (i ? ", '" : "'") + names[i] + "'";
      if (names.size() > 20) list += ", ...";
      throw MeshError(request.path + ": no node '" + request.node + "' (its nodes: " + list + ")");
    }
  }
  if (!(request.scale > 0.0) || !std::isfinite(request.scale))
    throw MeshError(mesh.source + ": scale must be a positive number");
  // every mesh of the node and its children, placed by the transforms below the node
  const std::function<void(const aiNode*, const aiMatrix4x4&)> visit = [&](const aiNode* node,
                                                                           const aiMatrix4x4& X) {
    aiMatrix3x3 normal_X(X);
    normal_X.Inverse().Transpose();
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      const aiMesh* part = scene->mMeshes[node->mMeshes[m]];
      if ((part->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
      const std::array<float, 4> rgba = base_color(scene, part);
      const auto base = static_cast<uint32_t>(mesh.vertices_m.size());
      for (unsigned v = 0; v < part->mNumVertices; ++v) {
        const aiVector3D p = X * part->mVertices[v];
        mesh.vertices_m.emplace_back(p.x, p.y, p.z);
        mesh.colors_rgba.push_back(rgba);
        if (part->HasNormals()) {
          aiVector3D n = normal_X * part->mNormals[v];
          n.Normalize();
          mesh.normals.emplace_back(n.x, n.y, n.z);
        }
      }
      // a mirroring placement (negative determinant) turns the winding inside out: undone
      const bool mirrored = X.Determinant() < 0.0f;
      for (unsigned f = 0; f < part->mNumFaces; ++f) {
        const aiFace& face = part->mFaces[f];
        if (face.mNumIndices != 3) continue;
        const uint32_t a = base + face.mIndices[0], b = base + face.mIndices[1],
                       c = base + face.mIndices[2];
        mesh.triangles.push_back(mirrored ? std::array<uint32_t, 3>{a, c, b}
                                          : std::array<uint32_t, 3>{a, b, c});
      }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c)
      visit(node->mChildren[c], X * node->mChildren[c]->mTransformation);
  };
  // the named node's own frame; the whole file in the root's
  visit(top, request.node.empty() ? top->mTransformation : aiMatrix4x4());
  // normals only when every part had them, all of them usable (a zero normal normalised is NaN)
  const bool usable = std::all_of(mesh.normals.begin(), mesh.normals.end(),
                                  [](const Eigen::Vector3f& n) { return n.allFinite(); });
  if (mesh.normals.size() != mesh.vertices_m.size() || !usable) mesh.normals.clear();
  for (Eigen::Vector3d& v : mesh.vertices_m) {
    if (request.up == UpAxis::kY) v = Eigen::Vector3d(v.x(), -v.z(), v.y());
    v *= request.scale;
  }
  if (request.up == UpAxis::kY)
    for (Eigen::Vector3f& n : mesh.normals)
      n = Eigen::Vector3f(n.x(), -n.z(), n.y());
  drop_degenerate_triangles(mesh);
  check_mesh(mesh);
  return mesh;
}

}  // namespace

}  // namespace vcockpit::model
