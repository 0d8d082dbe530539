// Models no one here made: every glTF, OBJ and AC3D file of Debian's assimp-testmodels (public
// sample models, and the malformed files assimp's own tests use) is either read into a mesh that
// passes check_mesh, or refused with a MeshError that names the file first. Nothing crashes,
// nothing hangs. Known ones pinned both ways: sample models that load (some with triangles of no
// area, left out and counted; with their texture images decoded), broken ones refused for what
// is wrong with them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "model/import/model_file.hpp"

namespace vcockpit::model {
namespace {

const std::filesystem::path kModels = "/usr/share/assimp/models";

TEST(PublicModels, EachLoadsOrIsRefusedNamingItsFile) {
  if (!std::filesystem::is_directory(kModels)) GTEST_SKIP() << "assimp-testmodels is not installed";
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kModels)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (entry.is_regular_file() &&
        (ext == ".gltf" || ext == ".glb" || ext == ".obj" || ext == ".ac"))
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 50u);
  std::map<std::string, std::string> refused;  // relative path -> message
  std::map<std::string, TriangleMesh> loaded;
  for (const auto& file : files) {
    const std::string relative = std::filesystem::relative(file, kModels).string();
    try {
      TriangleMesh mesh = load_model_mesh({file.string(), "", 1.0, UpAxis::kY, true});
      check_mesh(mesh);
      loaded.emplace(relative, std::move(mesh));
    } catch (const MeshError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(file.string() + ":", 0), 0u) << "names its file first: " << message;
      refused.emplace(relative, message);
    }
  }
  std::size_t triangles = 0, dropped = 0, textures = 0, textures_left_out = 0;
  for (const auto& [name, mesh] : loaded) {
    triangles += mesh.triangles.size();
    dropped += mesh.degenerate_dropped;
    textures += mesh.textures.size();
    textures_left_out += mesh.textures_left_out;
  }
  std::printf("%zu model files: %zu read (%zu triangles, %zu with no area left out; %zu textures "
              "decoded, %zu left out), %zu refused\n",
              files.size(), loaded.size(), triangles, dropped, textures, textures_left_out,
              refused.size());
  for (const auto& [name, mesh] : loaded)
    if (mesh.textures_left_out > 0)
      std::printf("  %s: %s\n", name.c_str(), mesh.first_texture_left_out.c_str());
  const auto expect_loaded = [&](const std::string& name, std::size_t min_triangles) {
    const auto it = loaded.find(name);
    ASSERT_NE(it, loaded.end()) << name << ": " << refused[name];
    EXPECT_GE(it->second.triangles.size(), min_triangles) << name;
  };
  expect_loaded("glTF2/BoxTextured-glTF-Binary/BoxTextured.glb", 12);
  expect_loaded("glTF/CesiumMilkTruck/CesiumMilkTruck.gltf", 3000);
  expect_loaded("AC/Wuson.ac", 3000);
  expect_loaded("OBJ/spider.obj", 1000);  // with triangles of no area among its others
  EXPECT_GT(loaded["OBJ/spider.obj"].degenerate_dropped, 0u);
  // their images, as the image generator asks for them: embedded in a .glb, beside a .gltf, an
  // OBJ's map_Kd and an AC3D texture, PNG and JPEG
  EXPECT_GE(textures, 20u);
  EXPECT_EQ(loaded["glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"].textures.size(), 1u);
  EXPECT_EQ(loaded["glTF/CesiumMilkTruck/CesiumMilkTruck.gltf"].textures.size(), 1u);
  EXPECT_EQ(loaded["OBJ/spider.obj"].textures.size(), 4u);
  EXPECT_EQ(loaded["AC/SphereWithLight.ac"].textures.size(), 1u);
  const auto expect_refused = [&](const std::string& name, const std::string& because) {
    const auto it = refused.find(name);
    ASSERT_NE(it, refused.end()) << name << " was read";
    EXPECT_NE(it->second.find(because), std::string::npos) << it->second;
  };
  expect_refused("glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb",
                 "is not a finite number");
  expect_refused("glTF2/RecursiveNodes/RecursiveNodes.gltf", "not a readable model");
  expect_refused("glTF2/MissingBin/BoxTextured.gltf", "BoxTextured0.bin");
  expect_refused("OBJ/point_cloud.obj", "not a readable model");
}

}  // namespace
}  // namespace vcockpit::model
