// Model textures (model/import/texture_image.hpp, model_file.cpp): the placard of
// tests/data/models (scripts/make_test_models.py) samples its image the same way from glTF (the
// image a file, or inline), OBJ (map_Kd) and AC3D (texture); PNG and JPEG decode to the pixels
// written, anything else is an error naming the texture; a model's texture that is not there or
// not an image is left out, counted and named, and its triangles keep their colour; the physics'
// requests (no textures) never read them.

#include <gtest/gtest.h>
#include <jpeglib.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "model/import/model_file.hpp"
#include "model/import/texture_image.hpp"
#include "model/triangle_mesh.hpp"

namespace vcockpit::model {
namespace {

namespace fs = std::filesystem;

std::string models_dir() {
  return std::string(std::getenv("VCOCKPIT_SOURCE_DIR")) + "/tests/data/models";
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::array<uint8_t, 4> texel(const TextureImage& image, uint32_t x, uint32_t y) {
  const std::size_t at = (std::size_t{y} * image.width + x) * 4;
  return {image.rgba[at], image.rgba[at + 1], image.rgba[at + 2], image.rgba[at + 3]};
}

// The image's texel at texture coordinate (u, v), v up from the bottom row, as a renderer reads it.
std::array<uint8_t, 4> sampled(const TextureImage& image, const Eigen::Vector2f& uv) {
  const auto x =
      static_cast<uint32_t>(std::clamp(uv.x(), 0.0f, 0.999f) * static_cast<float>(image.width));
  const auto y = static_cast<uint32_t>(std::clamp(1.0f - uv.y(), 0.0f, 0.999f) *
                                       static_cast<float>(image.height));
  return texel(image, x, y);
}

class EachTexturedFormat : public ::testing::TestWithParam<const char*> {};

TEST_P(EachTexturedFormat, ThePlacardSamplesItsImageTheWayUp) {
  const TriangleMesh placard =
      load_model_mesh({models_dir() + "/" + GetParam(), "placard", 1.0, UpAxis::kY, true});
  ASSERT_EQ(placard.textures.size(), 1u);
  const TextureImage& image = placard.textures[0];
  EXPECT_EQ(image.width, 64u);
  EXPECT_EQ(image.height, 32u);
  EXPECT_EQ(texel(image, 0, 0), (std::array<uint8_t, 4>{255, 0, 0, 255})) << "top left red";
  EXPECT_EQ(texel(image, 63, 31), (std::array<uint8_t, 4>{255, 255, 0, 255}))
      << "bottom right yellow";
  ASSERT_EQ(placard.triangle_texture.size(), placard.triangles.size());
  for (int32_t t : placard.triangle_texture)
    EXPECT_EQ(t, 0);
  ASSERT_EQ(placard.uv.size(), placard.vertices_m.size());
  EXPECT_EQ(placard.textures_left_out, 0u);
  // each corner, seen from -x (+y on the left, +z up), samples its quadrant's colour: the same
  // image the same way up whatever the file's own texture convention
  int corners = 0;
  for (std::size_t v = 0; v < placard.vertices_m.size(); ++v) {
    const Eigen::Vector3d& p = placard.vertices_m[v];
    const bool left = p.y() > 0, top = p.z() > 0;
    const std::array<uint8_t, 4> want = left && top    ? std::array<uint8_t, 4>{255, 0, 0, 255}
                                        : !left && top ? std::array<uint8_t, 4>{0, 200, 0, 255}
                                        : left         ? std::array<uint8_t, 4>{0, 0, 255, 255}
                                                       : std::array<uint8_t, 4>{255, 255, 0, 255};
    // a little inside the corner, toward the plate's middle: u grows to the right (-y)
    const Eigen::Vector2f uv =
        placard.uv[v] + Eigen::Vector2f(left ? 0.1f : -0.1f, top ? -0.1f : 0.1f);
    EXPECT_EQ(sampled(image, uv), want) << GetParam() << " corner " << p.transpose();
    ++corners;
  }
  EXPECT_GE(corners, 4);
}

INSTANTIATE_TEST_SUITE_P(Model, EachTexturedFormat,
                         ::testing::Values("placard.gltf", "placard_embedded.gltf", "placard.obj",
                                           "placard.ac"));

class TextureFiles : public ::testing::Test {
 protected:
  fs::path dir_ =
      fs::temp_directory_path() / ("vcockpit_texture_test_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string copy(const std::string& name) {
    fs::copy_file(models_dir() + "/" + name, dir_ / name, fs::copy_options::overwrite_existing);
    return (dir_ / name).string();
  }
};

TEST_F(TextureFiles, AMissingImageIsCountedAndItsTrianglesDrawnWithoutIt) {
  for (const char* model : {"placard.obj", "placard.gltf", "placard.ac"}) {
    copy("placard.mtl");
    const TriangleMesh mesh = load_model_mesh({copy(model), "", 1.0, UpAxis::kY, true});
    EXPECT_EQ(mesh.textures_left_out, 1u) << model;
    EXPECT_EQ(mesh.first_texture_left_out, "texture 'placard.png' not found") << model;
    EXPECT_TRUE(mesh.textures.empty()) << model;
    EXPECT_TRUE(mesh.triangle_texture.empty()) << model;
    EXPECT_EQ(mesh.triangles.size(), 2u) << model;
  }
}

TEST_F(TextureFiles, AnImageFoundByNameWhenItsPathIsTheAuthors) {
  const std::string obj = copy("placard.obj");
  copy("placard.png");
  std::ofstream(dir_ / "placard.mtl")
      << "newmtl placard\nKd 1 1 1\nmap_Kd C:\\Users\\pilot\\textures\\placard.png\n";
  const TriangleMesh mesh = load_model_mesh({obj, "", 1.0, UpAxis::kY, true});
  EXPECT_EQ(mesh.textures.size(), 1u);
  EXPECT_EQ(mesh.textures_left_out, 0u);
  // the physics' request reads no image at all
  const TriangleMesh bare = load_model_mesh({obj, ""});
  EXPECT_TRUE(bare.textures.empty());
  EXPECT_TRUE(bare.uv.empty());
  EXPECT_EQ(bare.textures_left_out, 0u);
}

// How an image is sampled comes with it: glTF's sampler (wrap along u and v, the filters) and
// OBJ's "-clamp on"; a file that says nothing gets glTF's defaults (repeat, linear).
TEST_F(TextureFiles, EachImageKeepsTheSamplerItsFileGives) {
  copy("placard.png");
  const TriangleMesh plain =
      load_model_mesh({copy("placard.gltf"), "", 1.0, UpAxis::kY, true});
  ASSERT_EQ(plain.textures.size(), 1u);
  EXPECT_EQ(plain.textures[0].sampler, TextureSampler{});

  std::string gltf = read_bytes(models_dir() + "/placard.gltf");
  const std::string texture = "\"source\": 0";
  const std::size_t at = gltf.find(texture);
  ASSERT_NE(at, std::string::npos);
  gltf.replace(at, texture.size(), "\"source\": 0, \"sampler\": 0");
  gltf.insert(gltf.rfind('}'),
              ", \"samplers\": [{\"magFilter\": 9728, \"minFilter\": 9984, \"wrapS\": 33071, "
              "\"wrapT\": 33648}]\n");
  std::ofstream(dir_ / "sampled.gltf") << gltf;
  const TriangleMesh sampled_gltf =
      load_model_mesh({(dir_ / "sampled.gltf").string(), "", 1.0, UpAxis::kY, true});
  ASSERT_EQ(sampled_gltf.textures.size(), 1u);
  const TextureSampler& k = sampled_gltf.textures[0].sampler;
  EXPECT_EQ(k.wrap_u, TextureWrap::kClampToEdge);
  EXPECT_EQ(k.wrap_v, TextureWrap::kMirroredRepeat);
  EXPECT_EQ(k.magnify, TextureFilter::kNearest);
  EXPECT_EQ(k.minify, TextureFilter::kNearest);

  const std::string obj = copy("placard.obj");
  std::ofstream(dir_ / "placard.mtl") << "newmtl placard\nKd 1 1 1\nmap_Kd -clamp on placard.png\n";
  const TriangleMesh clamped = load_model_mesh({obj, "", 1.0, UpAxis::kY, true});
  ASSERT_EQ(clamped.textures.size(), 1u);
  EXPECT_EQ(clamped.textures[0].sampler.wrap_u, TextureWrap::kClampToEdge);
  EXPECT_EQ(clamped.textures[0].sampler.wrap_v, TextureWrap::kClampToEdge);
  EXPECT_EQ(clamped.textures[0].sampler.magnify, TextureFilter::kLinear);
}

TEST_F(TextureFiles, AnImageThatIsNotOneIsLeftOutNamedWithWhy) {
  copy("placard.mtl");
  const std::string obj = copy("placard.obj");
  const ModelRequest request{obj, "", 1.0, UpAxis::kY, true};
  std::ofstream(dir_ / "placard.png") << "GIF89a not a png";
  const TriangleMesh gif = load_model_mesh(request);
  EXPECT_EQ(gif.textures_left_out, 1u);
  EXPECT_NE(gif.first_texture_left_out.find("placard.png' is not a PNG or JPEG image"),
            std::string::npos)
      << gif.first_texture_left_out;
  EXPECT_EQ(gif.triangles.size(), 2u) << "the plate itself is kept";
  // a PNG cut short
  std::string png = read_bytes(models_dir() + "/placard.png");
  std::ofstream(dir_ / "placard.png", std::ios::binary) << png.substr(0, png.size() / 2);
  const TriangleMesh cut = load_model_mesh(request);
  EXPECT_EQ(cut.textures_left_out, 1u);
  EXPECT_NE(cut.first_texture_left_out.find("is not a readable PNG"), std::string::npos)
      << cut.first_texture_left_out;
}

TEST(TextureImage, APngLargerThanTheLimitIsRefusedBeforeItsPixelsAreRead) {
  std::string png = read_bytes(models_dir() + "/placard.png");
  // IHDR's width (bytes 16-19, big-endian) made 9000: refused on the header
  png[16] = 0;
  png[17] = 0;
  png[18] = static_cast<char>(9000 >> 8);
  png[19] = static_cast<char>(9000 & 0xff);
  // and its CRC (over the chunk's type and data, bytes 12-28) made right again, so only the size
  // is wrong: CRC-32 as PNG defines it
  uint32_t crc = 0xffffffffu;
  for (std::size_t i = 12; i < 29; ++i) {
    crc ^= static_cast<uint8_t>(png[i]);
    for (int k = 0; k < 8; ++k)
      crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  crc ^= 0xffffffffu;
  for (int k = 0; k < 4; ++k)
    png[29 + k] = static_cast<char>(crc >> (24 - 8 * k));
  try {
    decode_texture_image(png, "huge.png");
    FAIL() << "a 9000-pixel-wide texture was decoded";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("at most 8192 on a side"), std::string::npos) << e.what();
  }
}

// A JPEG written by libjpeg: the left half red, the right half blue, 32 x 16.
std::string jpeg_of_halves() {
  jpeg_compress_struct info;
  jpeg_error_mgr errors;
  info.err = jpeg_std_error(&errors);
  jpeg_create_compress(&info);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&info, &buffer, &size);
  info.image_width = 32;
  info.image_height = 16;
  info.input_components = 3;
  info.in_color_space = JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, 95, TRUE);
  jpeg_start_compress(&info, TRUE);
  std::vector<unsigned char> row(32 * 3);
  for (int x = 0; x < 32; ++x) {
    row[3 * x] = x < 16 ? 230 : 0;
    row[3 * x + 2] = x < 16 ? 0 : 230;
  }
  while (info.next_scanline < info.image_height) {
    JSAMPROW r = row.data();
    jpeg_write_scanlines(&info, &r, 1);
  }
  jpeg_finish_compress(&info);
  std::string out(reinterpret_cast<const char*>(buffer), size);
  jpeg_destroy_compress(&info);
  std::free(buffer);
  return out;
}

TEST(TextureImage, AJpegDecodesToItsPixelsAndACutOneIsRefused) {
  const std::string jpeg = jpeg_of_halves();
  const TextureImage image = decode_texture_image(jpeg, "halves.jpg");
  ASSERT_EQ(image.width, 32u);
  ASSERT_EQ(image.height, 16u);
  const auto left = texel(image, 4, 8), right = texel(image, 28, 8);
  EXPECT_GT(left[0], 200);
  EXPECT_LT(left[2], 30);
  EXPECT_GT(right[2], 200);
  EXPECT_LT(right[0], 30);
  EXPECT_EQ(left[3], 255);
  try {
    decode_texture_image(jpeg.substr(0, 40), "cut.jpg");
    FAIL() << "a JPEG cut to its first 40 bytes was decoded";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("texture 'cut.jpg' is not a readable JPEG"),
              std::string::npos)
        << e.what();
  }
}

TEST(TextureImage, AnImagePastItsModelsPixelBudgetIsRefusedOnItsHeader) {
  const std::string jpeg = jpeg_of_halves();                          // 32 x 16
  const std::string png = read_bytes(models_dir() + "/placard.png");  // 64 x 32
  EXPECT_EQ(decode_texture_image(jpeg, "halves.jpg", 512).width, 32u) << "exactly the budget";
  for (const auto& [bytes, name] : {std::pair{jpeg, "halves.jpg"}, std::pair{png, "placard.png"}}) {
    try {
      decode_texture_image(bytes, name, 511);
      FAIL() << name << " was decoded past its budget";
    } catch (const MeshError& e) {
      EXPECT_NE(std::string(e.what()).find("more than the 511 left of its model's budget"),
                std::string::npos)
          << e.what();
    }
  }
}

// A triangle with no area dropped from a textured mesh takes its texture index with it: the
// others keep theirs.
TEST(TriangleMesh, DroppingADegenerateTriangleKeepsTheTexturesInStep) {
  TriangleMesh mesh;
  mesh.source = "test";
  mesh.vertices_m = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, 0, 1}};
  mesh.uv.assign(mesh.vertices_m.size(), Eigen::Vector2f::Zero());
  mesh.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}};  // the middle one has no area
  mesh.triangle_texture = {-1, 0, 0};
  mesh.textures.push_back({"white", 1, 1, {255, 255, 255, 255}, {}});
  drop_degenerate_triangles(mesh);
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangle_texture, (std::vector<int32_t>{-1, 0}));
  check_mesh(mesh);
  mesh.uv.pop_back();  // coordinates no longer one per vertex: named
  try {
    check_mesh(mesh);
    FAIL() << "4 texture coordinates for 5 vertices passed";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("4 texture coordinates for 5 vertices"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace vcockpit::model
