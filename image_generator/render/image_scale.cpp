#include "image_generator/render/image_scale.hpp"

#include <cstddef>
#include <cstring>
#include <stdexcept>

namespace vcockpit::render {

// src_stride_px: pixels from one source row to the next (0: src_w), so one eye of a
// side-by-side frame is scaled where it is, without cutting it out first.
void downscale_rgba(const uint8_t* src, int src_w, int src_h, int factor,
                    std::vector<uint8_t>& out, int src_stride_px) {
  if (factor < 1) throw std::invalid_argument("downscale_rgba: factor must be >= 1");
  const int out_w = src_w / factor;
  const int out_h = src_h / factor;
  if (!src || out_w <= 0 || out_h <= 0) {
    throw std::invalid_argument("downscale_rgba: image smaller than the factor");
  }
  if (src_stride_px != 0 && src_stride_px < src_w)
    throw std::invalid_argument("downscale_rgba: a row stride shorter than the row");
  const std::size_t src_row = static_cast<std::size_t>(src_stride_px != 0 ? src_stride_px : src_w) * 4;
  const std::size_t out_row = static_cast<std::size_t>(out_w) * 4;
  out.resize(out_row * static_cast<std::size_t>(out_h));
  if (factor == 1) {
    for (int y = 0; y < out_h; ++y)
      std::memcpy(out.data() + static_cast<std::size_t>(y) * out_row,
                  src + static_cast<std::size_t>(y) * src_row, out_row);
    return;
  }
  const unsigned area = static_cast<unsigned>(factor * factor);
  for (int oy = 0; oy < out_h; ++oy) {
    const uint8_t* block_row = src + static_cast<std::size_t>(oy) * factor * src_row;
    uint8_t* o = out.data() + static_cast<std::size_t>(oy) * out_row;
    if (factor == 2) {  // the common case, unrolled: four pixels per output pixel
      const uint8_t* a = block_row;
      const uint8_t* b = block_row + src_row;
      for (int ox = 0; ox < out_w; ++ox, a += 8, b += 8, o += 4) {
        for (int ch = 0; ch < 4; ++ch) {
          o[ch] = static_cast<uint8_t>((a[ch] + a[ch + 4] + b[ch] + b[ch + 4] + 2u) >> 2);
        }
      }
      continue;
    }
    for (int ox = 0; ox < out_w; ++ox, o += 4) {
      unsigned sum[4] = {0, 0, 0, 0};
      for (int dy = 0; dy < factor; ++dy) {
        const uint8_t* p = block_row + static_cast<std::size_t>(dy) * src_row +
                           static_cast<std::size_t>(ox) * factor * 4;
        for (int dx = 0; dx < factor; ++dx, p += 4) {
          for (int ch = 0; ch < 4; ++ch)
            sum[ch] += p[ch];
        }
      }
      for (int ch = 0; ch < 4; ++ch)
        o[ch] = static_cast<uint8_t>((sum[ch] + area / 2) / area);
    }
  }
}

void rgba_to_rgb(const uint8_t* rgba, int src_w, int width, int height, uint8_t* rgb) {
  const std::size_t src_row = static_cast<std::size_t>(src_w) * 4;
  for (int y = 0; y < height; ++y) {
    const uint8_t* s = rgba + static_cast<std::size_t>(y) * src_row;
    for (int x = 0; x < width; ++x, s += 4, rgb += 3) {
      rgb[0] = s[0];
      rgb[1] = s[1];
      rgb[2] = s[2];
    }
  }
}

}  // namespace vcockpit::render
