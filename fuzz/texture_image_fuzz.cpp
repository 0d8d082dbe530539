// A model's texture image (model/import/texture_image.hpp: PNG through libpng, JPEG through
// libjpeg-turbo, in the image generator's process and the model reader's): any bytes are either
// an RGBA image of the size it says, at most kMaxTextureSide on a side, or a MeshError naming
// the texture. libjpeg's errors come back through a longjmp: none may leak or crash.

#include <string>

#include "fuzz/fuzz_support.hpp"
#include "model/import/texture_image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace vcockpit;
  const std::string_view bytes = fuzz::as_text(data, size);
  try {
    const model::TextureImage image = model::decode_texture_image(bytes, "fuzz.png");
    fuzz::require(image.width > 0 && image.height > 0 && image.width <= model::kMaxTextureSide &&
                      image.height <= model::kMaxTextureSide,
                  "an image's size is within the limit");
    fuzz::require(image.rgba.size() == std::size_t{image.width} * image.height * 4,
                  "four bytes a pixel");
  } catch (const model::MeshError& e) {
    fuzz::require(std::string(e.what()).rfind("texture 'fuzz.png'", 0) == 0,
                  "a texture error names the texture first");
  }
  return 0;
}
