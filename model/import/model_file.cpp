#include "model/import/model_file.hpp"

#include <assimp/GltfMaterial.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <assimp/Importer.hpp>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>

#include "model/import/isolated_reader.hpp"
#include "model/import/texture_image.hpp"

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

TextureWrap wrap_of(aiTextureMapMode mode) {
  switch (mode) {
    case aiTextureMapMode_Clamp:
    case aiTextureMapMode_Decal:  // (outside [0, 1] nothing; the edge is the nearest to that)
      return TextureWrap::kClampToEdge;
    case aiTextureMapMode_Mirror:
      return TextureWrap::kMirroredRepeat;
    default:
      return TextureWrap::kRepeat;
  }
}

// glTF's filter numbers (the OpenGL enums): NEAREST 9728 and NEAREST_MIPMAP_NEAREST 9984 keep a
// texel's edges; the LINEAR ones, and none given, blend.
TextureFilter filter_of(int gl_filter) {
  return gl_filter == 9728 || gl_filter == 9984 ? TextureFilter::kNearest : TextureFilter::kLinear;
}

// The texture a part samples: its base colour texture (glTF) or diffuse map (OBJ map_Kd, AC3D
// texture) and how to sample it. path is "" when it has none or no texture coordinates.
struct PartTexture {
  std::string path;
  TextureSampler sampler;
};

PartTexture texture_of(const aiScene* scene, const aiMesh* part) {
  if (part->mMaterialIndex >= scene->mNumMaterials || !part->HasTextureCoords(0)) return {};
  const aiMaterial* material = scene->mMaterials[part->mMaterialIndex];
  for (const aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE}) {
    aiString path;
    aiTextureMapMode wrap[2] = {aiTextureMapMode_Wrap, aiTextureMapMode_Wrap};
    if (material->GetTextureCount(type) == 0 ||
        material->GetTexture(type, 0, &path, nullptr, nullptr, nullptr, nullptr, wrap) !=
            AI_SUCCESS ||
        path.length == 0)
      continue;
    PartTexture texture{path.C_Str(), {}};
    texture.sampler.wrap_u = wrap_of(wrap[0]);
    texture.sampler.wrap_v = wrap_of(wrap[1]);
    int filter = 0;
    if (material->Get(AI_MATKEY_GLTF_MAPPINGFILTER_MAG(type, 0), filter) == AI_SUCCESS)
      texture.sampler.magnify = filter_of(filter);
    if (material->Get(AI_MATKEY_GLTF_MAPPINGFILTER_MIN(type, 0), filter) == AI_SUCCESS)
      texture.sampler.minify = filter_of(filter);
    return texture;
  }
  return {};
}

constexpr std::uintmax_t kMaxTextureFileBytes = 64u << 20;
// The pixels a model part's images may have together (256 MiB as RGBA): past it, an image is
// left out like a missing one.
constexpr uint64_t kMaxModelTexturePixels = uint64_t{64} << 20;

// The images a mesh's parts name, each decoded once into mesh.textures: embedded in the file
// ("*0", or a .glb's named image), or (read_files) a file found by its path from the model's
// directory, or failing that by its name there (a path from the author's machine). One not
// found, or not a PNG or JPEG it can decode, is left out and counted, and its triangles keep
// their colour: a cockpit is still drawn whole for one bad image.
class TextureTable {
 public:
  TextureTable(const aiScene* scene, const std::string& model_path, bool read_files, TriangleMesh& mesh)
      : scene_(scene), dir_(std::filesystem::path(model_path).parent_path()), read_files_(read_files),
        mesh_(mesh) {}

  // (one image sampled two ways is two textures: the sampler travels with the image)
  int32_t index_of(const std::string& path, const TextureSampler& sampler) {
    const std::string key = path + '\n' + sampler_key(sampler);
    const auto known = known_.find(key);
    if (known != known_.end()) return known->second;
    int32_t& index = known_[key];
    index = -1;
    std::optional<TextureImage> image;
    try {
      image = embedded(path);
      if (!image && read_files_) {
        // the same file named two ways ("a.png", "./a.png") is decoded once
        const std::optional<std::filesystem::path> file = find_file(path);
        if (file) {
          std::error_code error;
          const std::filesystem::path canonical = std::filesystem::weakly_canonical(*file, error);
          const std::string file_key =
              (error ? *file : canonical).string() + '\n' + sampler_key(sampler);
          if (const auto same = by_file_.find(file_key); same != by_file_.end())
            return index = same->second;
          image = from_file(*file);
          by_file_[file_key] = static_cast<int32_t>(mesh_.textures.size());
        }
      }
      if (!image) throw MeshError("texture '" + path + "' not found");
    } catch (const MeshError& e) {
      if (mesh_.textures_left_out++ == 0) mesh_.first_texture_left_out = e.what();
      return index;
    }
    pixels_left_ -= uint64_t{image->width} * image->height;
    image->sampler = sampler;
    index = static_cast<int32_t>(mesh_.textures.size());
    mesh_.textures.push_back(std::move(*image));
    return index;
  }

 private:
  static std::string sampler_key(const TextureSampler& k) {
    return {static_cast<char>('0' + static_cast<int>(k.wrap_u)),
            static_cast<char>('0' + static_cast<int>(k.wrap_v)),
            static_cast<char>('0' + static_cast<int>(k.magnify)),
            static_cast<char>('0' + static_cast<int>(k.minify))};
  }

  std::optional<TextureImage> embedded(const std::string& path) const {
    const aiTexture* texture = scene_->GetEmbeddedTexture(path.c_str());
    if (texture == nullptr) return std::nullopt;
    if (texture->mHeight == 0)  // compressed: mWidth bytes of a PNG or JPEG
      return decode_texture_image(
          std::string_view(reinterpret_cast<const char*>(texture->pcData), texture->mWidth), path,
          pixels_left_);
    check_texture_size(texture->mWidth, texture->mHeight, pixels_left_, path);
    TextureImage image;  // raw BGRA texels
    image.name = path;
    image.width = texture->mWidth;
    image.height = texture->mHeight;
    image.rgba.reserve(std::size_t{image.width} * image.height * 4);
    for (std::size_t i = 0; i < std::size_t{image.width} * image.height; ++i) {
      const aiTexel& t = texture->pcData[i];
      image.rgba.insert(image.rgba.end(), {t.r, t.g, t.b, t.a});
    }
    return image;
  }

  // The file an image path names: from the model's directory, else by its name there.
  std::optional<std::filesystem::path> find_file(std::string path) const {
    std::replace(path.begin(), path.end(), '\\', '/');
    const std::filesystem::path given(path);
    std::vector<std::filesystem::path> tries;
    if (given.is_relative()) tries.push_back(dir_ / given);
    tries.push_back(dir_ / given.filename());
    for (const std::filesystem::path& file : tries) {
      std::error_code error;
      if (std::filesystem::is_regular_file(file, error)) return file;
    }
    return std::nullopt;
  }

  TextureImage from_file(const std::filesystem::path& file) const {
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(file, error);
    if (error || size > kMaxTextureFileBytes)
      throw MeshError("texture '" + file.string() + "' is larger than " +
                      std::to_string(kMaxTextureFileBytes >> 20) + " MiB");
    std::ifstream in(file, std::ios::binary);
    std::string bytes(static_cast<std::size_t>(size), '\0');
    if (!in.read(bytes.data(), static_cast<std::streamsize>(size)))
      throw MeshError("texture '" + file.string() + "' cannot be read");
    return decode_texture_image(bytes, file.string(), pixels_left_);
  }

  const aiScene* scene_;
  std::filesystem::path dir_;
  bool read_files_;
  TriangleMesh& mesh_;
  std::map<std::string, int32_t> known_;    // by the name the file gives, and the sampler
  std::map<std::string, int32_t> by_file_;  // by the image file's canonical path, and the sampler
  uint64_t pixels_left_ = kMaxModelTexturePixels;
};

// `beside_file`: the model is a file, and textures it names by path may be read beside it.
TriangleMesh mesh_of(const aiScene* scene, const ModelRequest& request, bool beside_file);

std::atomic<uint64_t> g_file_reads{0};

// The parts each live ModelPrefetch read, by request_key.
std::mutex g_prefetch_mutex;
std::vector<const std::map<std::string, ModelPart>*> g_prefetched;

std::string request_key(const ModelRequest& r) {
  char scale[32];
  std::snprintf(scale, sizeof scale, "%a", r.scale);  // exact
  return r.path + '\n' + r.node + '\n' + scale + (r.up == UpAxis::kZ ? " z" : " y") +
         (r.textures ? " t" : " -");
}

}  // namespace

ModelPrefetch::ModelPrefetch(const std::vector<ModelRequest>& requests) {
  auto parts = std::make_unique<std::map<std::string, ModelPart>>();
  std::map<std::string, std::vector<ModelRequest>> by_file;
  std::set<std::string> asked;  // each request once, whoever asks for it twice
  for (const ModelRequest& r : requests)
    if (asked.insert(request_key(r)).second) by_file[r.path].push_back(r);
  for (const auto& [path, file_requests] : by_file) {
    if (file_requests.size() < 2) continue;  // read alone as it is asked for: no saving
    std::vector<ModelPart> read;
    try {
      read = load_model_parts(file_requests);
    } catch (const MeshError& e) {
      // the file itself (missing, unreadable, the reader crashed or hung): each part reports
      // it as reading it alone would, without trying (and waiting on) the file again
      read.assign(file_requests.size(), ModelPart{std::nullopt, e.what()});
    }
    for (std::size_t i = 0; i < file_requests.size(); ++i)
      (*parts)[request_key(file_requests[i])] = std::move(read[i]);
  }
  parts_ = std::move(parts);
  const std::lock_guard<std::mutex> lock(g_prefetch_mutex);
  g_prefetched.push_back(parts_.get());
}

ModelPrefetch::~ModelPrefetch() {
  const std::lock_guard<std::mutex> lock(g_prefetch_mutex);
  g_prefetched.erase(std::find(g_prefetched.begin(), g_prefetched.end(), parts_.get()));
}

uint64_t model_file_reads() { return g_file_reads.load(); }

TriangleMesh load_model_mesh(const ModelRequest& request) {
  {
    const std::lock_guard<std::mutex> lock(g_prefetch_mutex);
    for (const auto* parts : g_prefetched) {
      const auto found = parts->find(request_key(request));
      if (found != parts->end()) {
        if (!found->second.mesh) throw MeshError(found->second.error);
        return *found->second.mesh;  // (a copy: two objects may be the same part)
      }
    }
  }
  ++g_file_reads;
  return read_isolated(
      [&] {
        Assimp::Importer importer;
        return mesh_of(read_scene(importer, request.path), request, true);
      },
      request.path);
}

std::vector<ModelPart> load_model_parts(const std::vector<ModelRequest>& requests) {
  if (requests.empty()) return {};
  const std::string& path = requests.front().path;
  for (const ModelRequest& r : requests)
    if (r.path != path)
      throw std::invalid_argument("load_model_parts: '" + r.path + "' is not '" + path + "'");
  ++g_file_reads;
  std::vector<ModelPart> parts = read_isolated_parts(
      [&] {
        Assimp::Importer importer;
        const aiScene* scene = read_scene(importer, path);
        std::vector<ModelPart> parts(requests.size());
        for (std::size_t i = 0; i < requests.size(); ++i) {
          try {
            parts[i].mesh = mesh_of(scene, requests[i], true);
          } catch (const MeshError& e) {
            parts[i].error = e.what();
          }
        }
        return parts;
      },
      path);
  if (parts.size() != requests.size())
    throw MeshError(path + ": the model reader's answer was cut short");
  return parts;
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
        return mesh_of(checked(scene, importer, request.path), request, false);
      },
      request.path);
}

namespace {

TriangleMesh mesh_of(const aiScene* scene, const ModelRequest& request, bool beside_file) {
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
  TextureTable textures(scene, request.path, beside_file, mesh);
  // every mesh of the node and its children, placed by the transforms below the node
  const std::function<void(const aiNode*, const aiMatrix4x4&)> visit = [&](const aiNode* node,
                                                                           const aiMatrix4x4& X) {
    aiMatrix3x3 normal_X(X);
    normal_X.Inverse().Transpose();
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      const aiMesh* part = scene->mMeshes[node->mMeshes[m]];
      if ((part->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;
      const std::array<float, 4> rgba = base_color(scene, part);
      const PartTexture texture_file = request.textures ? texture_of(scene, part) : PartTexture{};
      const int32_t texture =
          texture_file.path.empty() ? -1 : textures.index_of(texture_file.path, texture_file.sampler);
      const auto base = static_cast<uint32_t>(mesh.vertices_m.size());
      for (unsigned v = 0; v < part->mNumVertices; ++v) {
        const aiVector3D p = X * part->mVertices[v];
        mesh.vertices_m.emplace_back(p.x, p.y, p.z);
        mesh.colors_rgba.push_back(rgba);
        // (assimp gives every format's coordinates with v up from the image's bottom)
        mesh.uv.push_back(texture < 0 ? Eigen::Vector2f::Zero()
                                      : Eigen::Vector2f(part->mTextureCoords[0][v].x,
                                                        part->mTextureCoords[0][v].y));
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
        mesh.triangle_texture.push_back(texture);
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
  if (std::all_of(mesh.triangle_texture.begin(), mesh.triangle_texture.end(),
                  [](int32_t t) { return t < 0; })) {
    mesh.uv.clear();
    mesh.triangle_texture.clear();
  }
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
