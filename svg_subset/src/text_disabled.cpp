// Built without the text library (VRASTER_BUILD_TEXT=OFF): <text> draws nothing, with a warning.
#include "text.hpp"

namespace vraster::svg::detail {

std::shared_ptr<text::FontDb> default_font_db() { return nullptr; }

void build_text(pugi::xml_node text, const SpanStyle&, TextHost& host, text::FontDb*, Group&) {
  host.warn(text, "text is not drawn: vraster was built without its text library");
}

}  // namespace vraster::svg::detail
