#include "model/import/texture_image.hpp"

#include <jpeglib.h>
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>

namespace vcockpit::model {
namespace {

bool starts_with(std::string_view bytes, std::string_view magic) {
  return bytes.size() >= magic.size() && bytes.substr(0, magic.size()) == magic;
}

void check_size(uint32_t width, uint32_t height, const std::string& name) {
  if (width == 0 || height == 0 || width > kMaxTextureSide || height > kMaxTextureSide)
    throw MeshError("texture '" + name + "' is " + std::to_string(width) + " x " +
                    std::to_string(height) + " pixels: at most " + std::to_string(kMaxTextureSide) +
                    " on a side");
}

TextureImage decode_png(std::string_view bytes, const std::string& name) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()) == 0)
    throw MeshError("texture '" + name + "' is not a readable PNG: " + image.message);
  TextureImage out;
  out.name = name;
  out.width = image.width;
  out.height = image.height;
  try {
    check_size(out.width, out.height, name);
  } catch (...) {
    png_image_free(&image);
    throw;
  }
  image.format = PNG_FORMAT_RGBA;
  out.rgba.resize(PNG_IMAGE_SIZE(image));
  if (png_image_finish_read(&image, nullptr, out.rgba.data(), 0, nullptr) == 0)
    throw MeshError("texture '" + name + "' is not a readable PNG: " + image.message);
  return out;
}

// libjpeg reports errors through error_exit, which must not return: back to decode_jpeg's
// setjmp, with the message kept.
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

TextureImage decode_jpeg(std::string_view bytes, const std::string& name) {
  // nothing with a destructor is made between setjmp and a longjmp back to it
  TextureImage out;
  out.name = name;
  jpeg_decompress_struct info;
  JpegErrors errors;
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = jpeg_error_exit;
  errors.manager.output_message = jpeg_silent;
  errors.message[0] = '\0';
  bool size_ok = true;
  if (setjmp(errors.back) != 0) {
    jpeg_destroy_decompress(&info);
    throw MeshError("texture '" + name + "' is not a readable JPEG: " + errors.message);
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, reinterpret_cast<const unsigned char*>(bytes.data()),
               static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  size_ok = info.image_width > 0 && info.image_height > 0 && info.image_width <= kMaxTextureSide &&
            info.image_height <= kMaxTextureSide;
  if (size_ok) {
    info.out_color_space = JCS_EXT_RGBA;  // (libjpeg-turbo: greyscale and YCbCr to RGBA)
    jpeg_start_decompress(&info);
    out.width = info.output_width;
    out.height = info.output_height;
    out.rgba.resize(std::size_t{out.width} * out.height * 4);
    while (info.output_scanline < info.output_height) {
      JSAMPROW row = out.rgba.data() + std::size_t{info.output_scanline} * out.width * 4;
      jpeg_read_scanlines(&info, &row, 1);
    }
    jpeg_finish_decompress(&info);
  } else {
    out.width = info.image_width;
    out.height = info.image_height;
  }
  jpeg_destroy_decompress(&info);
  check_size(out.width, out.height, name);
  return out;
}

}  // namespace

TextureImage decode_texture_image(std::string_view bytes, const std::string& name) {
  if (starts_with(bytes, "\x89PNG\r\n\x1a\n")) return decode_png(bytes, name);
  if (starts_with(bytes, "\xff\xd8\xff")) return decode_jpeg(bytes, name);
  throw MeshError("texture '" + name + "' is not a PNG or JPEG image" +
                  (bytes.empty() ? " (no bytes)" : ""));
}

}  // namespace vcockpit::model
