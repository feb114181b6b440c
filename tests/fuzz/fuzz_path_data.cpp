// libFuzzer target: SVG path data. Any input must either parse or throw PathDataError with an offset inside the
// input; the partial path must keep finite coordinates.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "svg_subset/svg.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;  // size cap: longer inputs only repeat what short ones reach
  const std::string_view d(reinterpret_cast<const char*>(data), size);
  vraster::Path path;
  try {
    vraster::svg::parse_path_data(d, path);
  } catch (const vraster::svg::PathDataError& e) {
    if (e.offset() > size) std::abort();
  }
  for (const vraster::Point& p : path.points()) {
    if (!vraster::is_finite(p)) std::abort();
  }
  return 0;
}
