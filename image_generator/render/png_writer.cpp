#include "image_generator/render/png_writer.hpp"

#include <png.h>

#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace vcockpit::render {
namespace {

struct PngError {
  char message[256];
};

[[noreturn]] void on_png_error(png_structp png, png_const_charp message) {
  auto* error = static_cast<PngError*>(png_get_error_ptr(png));
  std::snprintf(error->message, sizeof(error->message), "%s", message);
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// Plain C on purpose: libpng reports errors by longjmp, which must not cross C++ objects with
// destructors. Returns false with error->message set on failure.
bool encode(std::FILE* file, const uint8_t* rgba, int width, int height, int level,
            PngError* error) {
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, error, on_png_error, on_png_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_compression_level(png, level);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE,
               PNG_FILTER_TYPE_BASE);
  png_write_info(png, info);
  const size_t row_bytes = static_cast<size_t>(width) * 4;
  for (int row = 0; row < height; ++row) {
    png_write_row(png, rgba + static_cast<size_t>(row) * row_bytes);
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw std::runtime_error("write_png " + path + ": " + why);
}

}  // namespace

void write_png(const std::string& path, const uint8_t* rgba, int width, int height,
               int compression_level) {
  if (!rgba || width <= 0 || height <= 0) {
    throw std::invalid_argument("write_png " + path + ": empty image");
  }
  if (compression_level < 0 || compression_level > 9) {
    throw std::invalid_argument("write_png " + path + ": compression_level must be 0..9");
  }
  const std::string partial = path + ".partial";
  std::FILE* file = std::fopen(partial.c_str(), "wb");
  if (!file) fail(path, "cannot open " + partial + ": " + std::strerror(errno));
  PngError error{"libpng could not start"};
  const bool encoded = encode(file, rgba, width, height, compression_level, &error);
  const bool closed = std::fclose(file) == 0;  // flushes: a full disk shows here
  std::error_code ignored;
  if (!encoded || !closed) {
    std::filesystem::remove(partial, ignored);
    fail(path, encoded ? std::string("cannot write ") + partial : error.message);
  }
  std::error_code renamed;
  std::filesystem::rename(partial, path, renamed);
  if (renamed) {
    std::filesystem::remove(partial, ignored);
    fail(path, "cannot rename " + partial + ": " + renamed.message());
  }
}

void copy_eye(const uint8_t* side_by_side, int eye_width, int height, Eye eye,
              std::vector<uint8_t>& out) {
  const size_t eye_row_bytes = static_cast<size_t>(eye_width) * 4;
  out.resize(eye_row_bytes * static_cast<size_t>(height));
  const uint8_t* source = side_by_side + (eye == Eye::kLeft ? 0 : eye_row_bytes);
  for (int row = 0; row < height; ++row) {
    std::memcpy(out.data() + static_cast<size_t>(row) * eye_row_bytes,
                source + static_cast<size_t>(row) * 2 * eye_row_bytes, eye_row_bytes);
  }
}

}  // namespace vcockpit::render
