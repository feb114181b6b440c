// Composite operator names (CSS / canvas globalCompositeOperation) and boundedness.
#include <array>
#include <string_view>

#include "vraster/composite.hpp"

namespace vraster {
namespace {

constexpr std::array<std::string_view, kCompositeOpCount> kNames = {
    "source-over", "copy", "source-in", "source-out", "source-atop",
    "destination-over", "destination-in", "destination-out", "destination-atop",
    "xor", "lighter", "clear",
    "multiply", "screen", "overlay", "darken", "lighten", "color-dodge", "color-burn", "hard-light", "soft-light",
    "difference", "exclusion", "hue", "saturation", "color", "luminosity",
};

}  // namespace

bool parse_composite_op(std::string_view css_name, CompositeOp& out) {
  if (css_name == "plus-lighter") {  // the CSS Compositing Level 2 name of "lighter"
    out = CompositeOp::Lighter;
    return true;
  }
  for (int i = 0; i < kCompositeOpCount; ++i) {
    if (kNames[static_cast<std::size_t>(i)] == css_name) {
      out = static_cast<CompositeOp>(i);
      return true;
    }
  }
  return false;
}

std::string_view to_string(CompositeOp op) {
  const auto i = static_cast<std::size_t>(op);
  return i < kNames.size() ? kNames[i] : std::string_view("unknown");
}

bool is_bounded(CompositeOp op) {
  switch (op) {
    case CompositeOp::Copy:
    case CompositeOp::Clear:
    case CompositeOp::SourceIn:
    case CompositeOp::SourceOut:
    case CompositeOp::DestinationIn:
    case CompositeOp::DestinationAtop:
      return false;
    default:
      return true;
  }
}

}  // namespace vraster
