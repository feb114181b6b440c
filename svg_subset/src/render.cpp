// svg_subset: drawing a parsed Document with vraster.
#include <cstdint>

#include "svg_subset/svg.hpp"

namespace vraster::svg {

template <class T>
void render(const Document& doc, BasicImage<T>& image, const RenderSettings& settings, Renderer& renderer) {
  for (const FillItem& item : doc.fills) {
    const FillOptions options{settings.rule_override.value_or(item.rule), settings.aa, settings.tolerance};
    renderer.fill(image, item.path, item.transform, item.color, options);
  }
}

template void render<std::uint8_t>(const Document&, Image&, const RenderSettings&, Renderer&);
template void render<std::uint16_t>(const Document&, Image16&, const RenderSettings&, Renderer&);

}  // namespace vraster::svg
