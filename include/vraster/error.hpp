// vraster: the one exception type the library throws.
#pragma once

#include <stdexcept>
#include <string>

namespace vraster {

/// Thrown for bad input the caller can fix: non-finite coordinates, malformed files, sizes out of range.
/// The message names the problem (and, for files, where it is).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace vraster
