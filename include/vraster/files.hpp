// vraster: reading input files with a size cap, and output files that appear whole or not at all.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace vraster {

/// Largest SVG file vraster reads (64 MiB).
inline constexpr std::size_t kMaxSvgFileBytes = std::size_t{64} << 20;
/// Largest font file vraster reads (256 MiB: big CJK collections stay well below).
inline constexpr std::size_t kMaxFontFileBytes = std::size_t{256} << 20;

/// Reads a whole file (any kind: regular, pipe, device) but never more than `max_bytes`: a bigger input
/// (/dev/zero included) throws vraster::Error "WHAT 'PATH' is larger than the limit of N MiB" after reading
/// max_bytes + 1. Also throws naming the file when it cannot be opened or read, or is a directory.
std::vector<std::uint8_t> read_file_limited(const std::string& path, std::size_t max_bytes, const std::string& what);

/// A file being written: the data goes to a new temporary file beside the target, created exclusively under a
/// unique name (O_CREAT | O_EXCL | O_NOFOLLOW: an existing file or link of that name is never opened), and
/// commit() renames it over the target with the target's permission bits (new files: 0666 minus the umask).
/// A target that exists and is not a regular file (a device such as /dev/stdout or /dev/full, a FIFO) is
/// written through instead of being replaced. Until commit(), the temporary is registered for removal by the
/// handlers of install_output_cleanup_handlers(); the destructor removes it when commit() was not reached.
class OutputFile {
 public:
  /// Creates the temporary (or opens a non-regular target). Throws vraster::Error naming `path` on failure.
  explicit OutputFile(std::string path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  /// The stream to write to (binary, buffered).
  std::FILE* stream() { return file_; }
  /// Flushes and closes the stream, then renames the temporary over the target. Throws vraster::Error (and
  /// removes the temporary) when a write failed or the rename does.
  void commit();
  /// Throws away what was written (the temporary is removed; a written-through target keeps what it got).
  void abandon();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::string temp_;  // empty when writing through
  std::FILE* file_ = nullptr;
  int slot_ = -1;     // cleanup registration
  unsigned mode_ = 0;
  bool keep_mode_ = false;
};

/// Installs handlers for SIGINT, SIGTERM, SIGHUP and SIGQUIT that remove every registered temporary output file
/// (async-signal-safe: unlink of paths stored beforehand) and then die of the same signal, and ignores SIGXFSZ
/// so that exceeding a file size limit makes writes fail (reported as an error, temporary removed) instead of
/// killing the process. For programs (the vraster command calls it first); a library never installs them.
void install_output_cleanup_handlers();

}  // namespace vraster
