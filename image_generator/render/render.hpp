#pragma once
// The render library in one include: HMD config, camera maths, instances, the stereo renderer
// and frame export (PNG, scaling, text labels). Pure: no DDS, no YAML.

#include "image_generator/render/camera.hpp"           // IWYU pragma: export
#include "image_generator/render/hmd_config.hpp"       // IWYU pragma: export
#include "image_generator/render/image_scale.hpp"      // IWYU pragma: export
#include "image_generator/render/instance.hpp"         // IWYU pragma: export
#include "image_generator/render/instrument_panel.hpp"  // IWYU pragma: export
#include "image_generator/render/png_writer.hpp"       // IWYU pragma: export
#include "image_generator/render/render_error.hpp"     // IWYU pragma: export
#include "image_generator/render/stereo_renderer.hpp"  // IWYU pragma: export
#include "image_generator/render/text_overlay.hpp"     // IWYU pragma: export
