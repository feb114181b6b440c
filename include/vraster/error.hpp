// vraster: the one exception type the library throws, and the helper that makes input text safe in messages.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace vraster {

/// Thrown for bad input the caller can fix: non-finite coordinates, malformed files, sizes out of range.
/// The message names the problem (and, for files, where it is).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// How much of an input value a message echoes by default (bytes of input).
inline constexpr std::size_t kMaxEchoedBytes = 40;

/// `text` made safe to print: control characters (C0, DEL, C1), bidirectional overrides and bytes that are not
/// UTF-8 become \xNN or \u{NNNN}, so echoed input cannot drive a terminal; cut after `max_bytes` of input with
/// "..." appended (so a 100 KB number stays a short message). Every message that echoes input goes through it.
std::string printable(std::string_view text, std::size_t max_bytes = kMaxEchoedBytes);

/// printable(text, max_bytes) in single quotes: the form messages use for values.
std::string quoted(std::string_view text, std::size_t max_bytes = kMaxEchoedBytes);

/// Longest message a command-line tool prints for one error (bytes of the original message).
inline constexpr std::size_t kMaxMessageBytes = 4096;

/// The message for the exception being handled (call it inside a catch block): what() of any std::exception
/// through printable(), "out of memory" for std::bad_alloc, a fixed text for anything else. The last-resort
/// handler of every command-line entry point uses it, so no exception escapes to std::terminate.
std::string describe_current_exception();

}  // namespace vraster
