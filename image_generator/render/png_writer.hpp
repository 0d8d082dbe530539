#pragma once
// Frame export: PNG files written atomically (or PNGs in memory), and one eye cut out of a
// side-by-side frame.

#include <cstdint>
#include <string>
#include <vector>

#include "image_generator/render/hmd_config.hpp"

namespace vcockpit::render {

// RGBA8, top-down rows, no row padding. Writes "<path>.partial" then renames it to path, so no
// reader ever sees half a PNG. No filtering; compression_level 0..9 (1: ~8-10 ms per 1280x720
// eye here). Throws std::invalid_argument for bad arguments and std::runtime_error naming the
// path on any I/O or libpng failure (the partial file is removed).
void write_png(const std::string& path, const uint8_t* rgba, int width, int height,
               int compression_level = 1);

// The same PNG (same libpng settings) in memory. Throws std::invalid_argument for bad arguments
// and std::runtime_error on a libpng failure.
std::vector<uint8_t> encode_png(const uint8_t* rgba, int width, int height,
                                int compression_level = 1);

// One eye of a side-by-side RGBA8 frame (2 * eye_width by height) into out, resized to
// eye_width * height * 4 (no allocation once out is big enough).
void copy_eye(const uint8_t* side_by_side, int eye_width, int height, Eye eye,
              std::vector<uint8_t>& out);

}  // namespace vcockpit::render
