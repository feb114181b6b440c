// vraster command-line tool: shared helpers of the subcommands.
#pragma once

#include <string>
#include <string_view>

namespace vraster::cli {

/// A usage mistake on the command line (reported with exit status 2).
struct UsageError {
  std::string message;
};

/// The embedded demo scene (SVG text).
std::string_view demo_svg();

}  // namespace vraster::cli
