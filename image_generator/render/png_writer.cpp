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

// Appends libpng's output to a vector. bad_alloc is caught here and turned into a libpng error
// after the catch block ends, so the longjmp crosses no live C++ object.
void write_to_memory(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::vector<uint8_t>*>(png_get_io_ptr(png));
  bool appended = true;
  try {
    out->insert(out->end(), data, data + length);
  } catch (...) {
    appended = false;
  }
  if (!appended) png_error(png, "out of memory");
}

void flush_memory(png_structp) {}

// Where encode writes: a file (libpng's own stdio output) or memory.
struct PngSink {
  std::FILE* file = nullptr;
  std::vector<uint8_t>* memory = nullptr;
};

// Plain C on purpose: libpng reports errors by longjmp, which must not cross C++ objects with
// destructors. Returns false with error->message set on failure.
bool encode(PngSink sink, const uint8_t* rgba, int width, int height, int level, PngError* error) {
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
  if (sink.file) {
    png_init_io(png, sink.file);
  } else {
    png_set_write_fn(png, sink.memory, write_to_memory, flush_memory);
  }
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

void check_arguments(const char* what, const uint8_t* rgba, int width, int height,
                     int compression_level) {
  if (!rgba || width <= 0 || height <= 0) {
    throw std::invalid_argument(std::string(what) + ": empty image");
  }
  if (compression_level < 0 || compression_level > 9) {
    throw std::invalid_argument(std::string(what) + ": compression_level must be 0..9");
  }
}

}  // namespace

void write_png(const std::string& path, const uint8_t* rgba, int width, int height,
               int compression_level) {
  check_arguments(("write_png " + path).c_str(), rgba, width, height, compression_level);
  const std::string partial = path + ".partial";
  std::FILE* file = std::fopen(partial.c_str(), "wb");
  if (!file) fail(path, "cannot open " + partial + ": " + std::strerror(errno));
  PngError error{"libpng could not start"};
  const bool encoded = encode({file, nullptr}, rgba, width, height, compression_level, &error);
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

std::vector<uint8_t> encode_png(const uint8_t* rgba, int width, int height, int compression_level) {
  check_arguments("encode_png", rgba, width, height, compression_level);
  std::vector<uint8_t> out;
  // a rendered frame compresses to a few percent of its raw size: start at 1/16 of it
  out.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) / 4 + 1024);
  PngError error{"libpng could not start"};
  if (!encode({nullptr, &out}, rgba, width, height, compression_level, &error)) {
    throw std::runtime_error(std::string("encode_png: ") + error.message);
  }
  return out;
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
