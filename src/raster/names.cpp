// Names of fill rules and antialiasing modes, as the CLI and files spell them.
#include <array>
#include <utility>

#include "vraster/raster.hpp"

namespace vraster {
namespace {

constexpr std::array<std::pair<std::string_view, FillRule>, 6> kRules{{
    {"evenodd", FillRule::EvenOdd},
    {"nonzero", FillRule::NonZero},
    {"nonexterior", FillRule::NonExterior},
    {"positive", FillRule::Positive},
    {"negative", FillRule::Negative},
    {"abs-geq-2", FillRule::AbsGeq2},
}};

constexpr std::array<std::pair<std::string_view, AntiAlias>, 10> kModes{{
    {"none", AntiAlias::None},
    {"analytic", AntiAlias::Analytic},
    {"exact", AntiAlias::Exact},
    {"ssaa-2", AntiAlias::Ssaa2},
    {"ssaa-4", AntiAlias::Ssaa4},
    {"ssaa-8", AntiAlias::Ssaa8},
    {"ssaa-16", AntiAlias::Ssaa16},
    {"msaa-4", AntiAlias::Msaa4},
    {"msaa-8", AntiAlias::Msaa8},
    {"msaa-16", AntiAlias::Msaa16},
}};

}  // namespace

bool parse_fill_rule(std::string_view name, FillRule& out) {
  for (const auto& [n, r] : kRules) {
    if (n == name) {
      out = r;
      return true;
    }
  }
  return false;
}

std::string_view to_string(FillRule rule) {
  for (const auto& [n, r] : kRules) {
    if (r == rule) return n;
  }
  return "?";
}

bool parse_anti_alias(std::string_view name, AntiAlias& out) {
  for (const auto& [n, m] : kModes) {
    if (n == name) {
      out = m;
      return true;
    }
  }
  return false;
}

std::string_view to_string(AntiAlias aa) {
  for (const auto& [n, m] : kModes) {
    if (m == aa) return n;
  }
  return "?";
}

}  // namespace vraster
