#include "model/import/texture_image.hpp"

#include <jpeglib.h>
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

namespace vcockpit::model {
namespace {

bool starts_with(std::string_view bytes, std::string_view magic) {
  return bytes.size() >= magic.size() && bytes.substr(0, magic.size()) == magic;
}

TextureImage decode_png(std::string_view bytes, const std::string& name, uint64_t max_pixels) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  // (libpng frees the image itself on each error it reports)
  if (png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()) == 0)
    throw MeshError("texture '" + name + "' is not a readable PNG: " + image.message);
  TextureImage out;
  try {
    check_texture_size(image.width, image.height, max_pixels, name);
    out.name = name;
    out.width = image.width;
    out.height = image.height;
    image.format = PNG_FORMAT_RGBA;
    out.rgba.resize(PNG_IMAGE_SIZE(image));
  } catch (...) {
    png_image_free(&image);
    throw;
  }
  if (png_image_finish_read(&image, nullptr, out.rgba.data(), 0, nullptr) == 0)
    throw MeshError("texture '" + name + "' is not a readable PNG: " + image.message);
  return out;
}

// libjpeg reports errors through error_exit, which must not return: it jumps back to
// run_jpeg's setjmp with the message kept.
struct JpegErrors {
  jpeg_error_mgr manager;
  std::jmp_buf back;
  char message[JMSG_LENGTH_MAX];
};

void jpeg_error_exit(j_common_ptr info) {
  auto* errors = reinterpret_cast<JpegErrors*>(info->err);
  (*info->err->format_message)(info, errors->message);
  std::longjmp(errors->back, 1);
}

void jpeg_silent(j_common_ptr) {}  // warnings (a truncated scan is decoded as far as it goes)

// One JPEG decode, all its state here (reached through the pointer, so a longjmp leaves it as
// it was): run_jpeg has no locals that change after its setjmp and nothing with a destructor.
struct JpegJob {
  jpeg_decompress_struct info;
  JpegErrors errors;
  const unsigned char* data = nullptr;
  unsigned long size = 0;
  uint64_t max_pixels = 0;
  uint32_t width = 0, height = 0;
  unsigned char* pixels = nullptr;  // malloc'd, width * height * 4; the caller frees it
  bool too_large = false;
};

// True with job->pixels decoded; false with job->errors.message, or job->too_large and the
// header's size in width and height.
bool run_jpeg(JpegJob* job) {
  std::memset(&job->info, 0, sizeof job->info);
  job->info.err = jpeg_std_error(&job->errors.manager);
  job->errors.manager.error_exit = jpeg_error_exit;
  job->errors.manager.output_message = jpeg_silent;
  job->errors.message[0] = '\0';
  if (setjmp(job->errors.back) != 0) {
    jpeg_destroy_decompress(&job->info);
    std::free(job->pixels);
    job->pixels = nullptr;
    return false;
  }
  jpeg_create_decompress(&job->info);
  jpeg_mem_src(&job->info, job->data, job->size);
  jpeg_read_header(&job->info, TRUE);
  job->width = job->info.image_width;
  job->height = job->info.image_height;
  if (job->width == 0 || job->height == 0 || job->width > kMaxTextureSide ||
      job->height > kMaxTextureSide || uint64_t{job->width} * job->height > job->max_pixels) {
    job->too_large = true;
    jpeg_destroy_decompress(&job->info);
    return false;
  }
  job->info.out_color_space = JCS_EXT_RGBA;  // (libjpeg-turbo: greyscale and YCbCr to RGBA)
  jpeg_start_decompress(&job->info);
  job->width = job->info.output_width;
  job->height = job->info.output_height;
  job->pixels = static_cast<unsigned char*>(std::malloc(std::size_t{job->width} * job->height * 4));
  if (job->pixels == nullptr) {
    std::strcpy(job->errors.message, "out of memory");
    jpeg_destroy_decompress(&job->info);
    return false;
  }
  while (job->info.output_scanline < job->info.output_height) {
    JSAMPROW row = job->pixels + std::size_t{job->info.output_scanline} * job->width * 4;
    jpeg_read_scanlines(&job->info, &row, 1);
  }
  jpeg_finish_decompress(&job->info);
  jpeg_destroy_decompress(&job->info);
  return true;
}

TextureImage decode_jpeg(std::string_view bytes, const std::string& name, uint64_t max_pixels) {
  auto job = std::make_unique<JpegJob>();
  job->data = reinterpret_cast<const unsigned char*>(bytes.data());
  job->size = static_cast<unsigned long>(bytes.size());
  job->max_pixels = max_pixels;
  if (!run_jpeg(job.get())) {
    if (job->too_large) check_texture_size(job->width, job->height, max_pixels, name);  // (throws)
    throw MeshError("texture '" + name + "' is not a readable JPEG: " + job->errors.message);
  }
  TextureImage out;
  out.name = name;
  out.width = job->width;
  out.height = job->height;
  try {
    out.rgba.assign(job->pixels, job->pixels + std::size_t{out.width} * out.height * 4);
  } catch (...) {
    std::free(job->pixels);
    throw;
  }
  std::free(job->pixels);
  return out;
}

}  // namespace

// Refused on the header, before any pixel is decoded: a side past kMaxTextureSide, or more
// pixels than the caller has left.
void check_texture_size(uint64_t width, uint64_t height, uint64_t max_pixels,
                        const std::string& name) {
  if (width == 0 || height == 0 || width > kMaxTextureSide || height > kMaxTextureSide)
    throw MeshError("texture '" + name + "' is " + std::to_string(width) + " x " +
                    std::to_string(height) + " pixels: at most " + std::to_string(kMaxTextureSide) +
                    " on a side");
  if (width * height > max_pixels)
    throw MeshError("texture '" + name + "' is " + std::to_string(width) + " x " +
                    std::to_string(height) + " pixels: more than the " +
                    std::to_string(max_pixels) + " left of its model's budget");
}

TextureImage decode_texture_image(std::string_view bytes, const std::string& name,
                                  uint64_t max_pixels) {
  if (starts_with(bytes, "\x89PNG\r\n\x1a\n")) return decode_png(bytes, name, max_pixels);
  if (starts_with(bytes, "\xff\xd8\xff")) return decode_jpeg(bytes, name, max_pixels);
  throw MeshError("texture '" + name + "' is not a PNG or JPEG image" +
                  (bytes.empty() ? " (no bytes)" : ""));
}

}  // namespace vcockpit::model
