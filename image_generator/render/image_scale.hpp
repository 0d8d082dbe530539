#pragma once
// Frame size and format changes for export: a box-filter downscale (a video of the run need not
// be full size) and RGBA to packed RGB (what the video encoder reads).

#include <cstdint>
#include <vector>

namespace vcockpit::render {

// Averages each factor x factor block of an RGBA8 image (top-down rows, no padding) into one
// pixel, rounding to nearest. out becomes (src_w / factor) x (src_h / factor) RGBA8; columns and
// rows left over at the right and bottom edges are dropped. No allocation once out is big
// enough. factor 1 copies. Throws std::invalid_argument for a factor < 1 or an empty result.
void downscale_rgba(const uint8_t* src, int src_w, int src_h, int factor,
                    std::vector<uint8_t>& out, int src_stride_px = 0);

// The top-left width x height of an RGBA8 image src_w pixels wide, as packed RGB8 into rgb
// (width * height * 3 bytes, preallocated by the caller); alpha is dropped.
void rgba_to_rgb(const uint8_t* rgba, int src_w, int width, int height, uint8_t* rgb);

}  // namespace vcockpit::render
