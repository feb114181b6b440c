// vraster_text: the `vraster text` subcommand.
#pragma once

#include <string_view>

namespace vraster::text {

/// Runs `vraster text "TEXT" [--font FILE] [--size PX] [--width W] [--align left|center|right] [--color C]
/// [--aa none|analytic|exact] [--features F] [--lang L] [--dir auto|ltr|rtl] [--hinting none|light] -o OUT.png`.
/// argv[1] must be "text". Renders onto a transparent image sized to the text plus a margin.
/// Returns 0 on success; on bad arguments or input prints "vraster: message" to stderr and returns 2 without
/// writing the output file.
int run_text_command(int argc, char** argv);

/// The usage text of `vraster text` (what `vraster text --help` prints).
std::string_view text_command_usage();

}  // namespace vraster::text
