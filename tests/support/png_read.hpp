#pragma once
// Reads a PNG into RGBA8 (libpng's simplified API), for tests that look at rendered pixels.

#include <png.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vcockpit::test {

struct RgbaImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> pixels;  // top-down rows
  std::array<int, 4> at(int column, int row) const {
    const auto* p = &pixels[(static_cast<std::size_t>(row) * width + column) * 4];
    return {p[0], p[1], p[2], p[3]};
  }
};

inline bool read_png(const std::string& path, RgbaImage& out) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) return false;
  image.format = PNG_FORMAT_RGBA;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.pixels.resize(PNG_IMAGE_SIZE(image));
  const bool ok = png_image_finish_read(&image, nullptr, out.pixels.data(), 0, nullptr) != 0;
  png_image_free(&image);
  return ok;
}

}  // namespace vcockpit::test
