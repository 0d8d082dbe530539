#pragma once
// A CLI11 check that a number option is finite. CLI11's Range, PositiveNumber and
// NonNegativeNumber let "nan" and "inf" through (every comparison with NaN is false), so each
// floating-point option adds `& kFinite` to its check.

#include <CLI/CLI.hpp>

#include <cmath>
#include <exception>
#include <string>

namespace vcockpit {

inline const CLI::Validator kFinite(
    [](std::string& text) -> std::string {
      try {
        if (std::isfinite(std::stod(text))) return {};
      } catch (const std::exception&) {
      }
      return "'" + text + "' is not a finite number";
    },
    "FINITE");

}  // namespace vcockpit
