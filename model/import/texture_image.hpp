#pragma once
// A model's texture image decoded from its bytes (a file next to the model, or embedded in a
// .glb): PNG through libpng, JPEG through libjpeg-turbo, the two formats glTF 2.0 allows and
// the ones OBJ and AC3D cockpits use. Anything else, a corrupt image, or one larger than
// kMaxTextureSide on a side is refused with a MeshError naming `name`.

#include <cstdint>
#include <string>
#include <string_view>

#include "model/triangle_mesh.hpp"

namespace vcockpit::model {

inline constexpr uint32_t kMaxTextureSide = 8192;

// 8-bit RGBA, rows from the top; greyscale and palette images expanded, 16-bit ones reduced.
// An image of more than `max_pixels` is refused on its header, before it is decoded (a few kB
// of JPEG can claim 8192 x 8192: 256 MiB).
TextureImage decode_texture_image(std::string_view bytes, const std::string& name,
                                  uint64_t max_pixels = uint64_t{kMaxTextureSide} *
                                                        kMaxTextureSide);

// Throws the MeshError decode_texture_image gives an image of this size: a side of 0 or past
// kMaxTextureSide, or more than `max_pixels`.
void check_texture_size(uint64_t width, uint64_t height, uint64_t max_pixels,
                        const std::string& name);

}  // namespace vcockpit::model
