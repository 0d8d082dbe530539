#pragma once
// A degradation that cannot be applied as asked (bad parameters, gaps that do not fit the log).

#include <stdexcept>

namespace vcockpit::degrade {

class DegradeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace vcockpit::degrade
