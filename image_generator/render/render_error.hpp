#pragma once
// The one exception type the renderer throws: any OSMesa or OpenGL failure at start-up.

#include <stdexcept>

namespace vcockpit::render {

class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace vcockpit::render
