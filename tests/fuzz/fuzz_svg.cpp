// libFuzzer target: the SVG document reader (XML, presentation attributes and style, transforms, viewBox, units,
// references such as clip-path or href) through svg_subset's public API, then rendering what it read.
// Any input either parses or throws a ParseError whose what() starts with "fuzz.svg:LINE:COLUMN: "; warnings read
// "LINE:COLUMN: message" (or "... and K more"); a parsed document renders (possibly with a vraster::Error that
// names its element) without crashing.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "svg_subset/svg.hpp"

namespace {

// "N:N: ..." with N decimal, or the summary line.
bool well_formed_position(const std::string& text) {
  if (text.rfind("... and ", 0) == 0) return true;
  std::size_t i = 0;
  for (int part = 0; part < 2; ++part) {
    const std::size_t start = i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) ++i;
    if (i == start || i >= text.size() || text[i] != ':') return false;
    ++i;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 16384) return 0;  // size cap: documents beyond this only repeat what short ones reach
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  vraster::svg::Document doc;
  try {
    doc = vraster::svg::parse_svg(text, "fuzz.svg");
  } catch (const vraster::svg::ParseError& e) {
    const std::string what = e.what();
    if (what.rfind("fuzz.svg:", 0) != 0 || !well_formed_position(what.substr(9))) std::abort();
    return 0;
  } catch (const vraster::Error&) {
    return 0;
  }
  for (const std::string& w : doc.warnings) {
    if (!well_formed_position(w)) std::abort();
  }
  if (doc.width <= 0 || doc.height <= 0) std::abort();
  // Render small: a large document is scaled down to at most 96 px a side (the reader is the target here; huge
  // outputs are the CLI's limits to test).
  const int w = std::min(doc.width, 96), h = std::min(doc.height, 96);
  if (w != doc.width || h != doc.height) vraster::svg::scale_to(doc, w, h);
  vraster::Image image(w, h);
  vraster::svg::RenderSettings settings;
  settings.aa = size % 3 == 0 ? vraster::AntiAlias::None : vraster::AntiAlias::Analytic;
  vraster::Renderer renderer;
  try {
    vraster::svg::render(doc, image, settings, renderer);
  } catch (const vraster::Error&) {
  }
  for (std::size_t i = 0; i < image.data.size(); i += 4) {
    const auto* p = &image.data[i];
    if (p[0] > p[3] || p[1] > p[3] || p[2] > p[3]) std::abort();  // premultiplied: no channel above alpha
  }
  return 0;
}
