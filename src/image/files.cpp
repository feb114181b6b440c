// Output files written whole or not at all (see vraster/files.hpp).
//
// Temporary names are "<target>.<random>.partial" in the target's folder (so the final rename stays on one
// file system), created with O_EXCL | O_NOFOLLOW and retried on a collision. The signal handlers can only
// call async-signal-safe functions, so each open temporary's name sits in a fixed slot (a char array and an
// atomic state) that the handler reads without locks or allocation.
#include "vraster/files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <random>
#include <thread>
#include <chrono>

#include "vraster/error.hpp"

namespace vraster {
namespace {

constexpr int kCleanupSlots = 64;
constexpr std::size_t kMaxPathBytes = 4096;

struct CleanupSlot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 holds a path to remove on a signal
  char path[kMaxPathBytes];
};
CleanupSlot g_slots[kCleanupSlots];  // zero pages until used: 256 KiB of address space

/// Takes a free slot for a temporary about to be created (it holds no path yet, so a signal removes nothing).
/// When every slot is taken (more files being written at once than slots, e.g. `vraster render -j 100`), waits
/// for one to free: a partial file must never be left without its cleanup.
int reserve_cleanup_slot() {
  for (;;) {
    for (int i = 0; i < kCleanupSlots; ++i) {
      int expected = 0;
      if (g_slots[i].state.compare_exchange_strong(expected, 1)) return i;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

/// From now on a signal removes `path` (a file this process created); too long a path is just not removed.
void arm_cleanup_slot(int slot, const std::string& path) {
  if (path.size() + 1 > kMaxPathBytes) return;
  std::memcpy(g_slots[slot].path, path.c_str(), path.size() + 1);
  g_slots[slot].state.store(2);
}

void unregister(int slot) {
  if (slot >= 0) g_slots[slot].state.store(0);
}

extern "C" void remove_partial_files_and_die(int sig) {
  for (CleanupSlot& s : g_slots) {
    if (s.state.load() == 2) unlink(s.path);
  }
  std::signal(sig, SIG_DFL);
  raise(sig);
}

std::string describe(const std::string& path) { return quoted(path, 1024); }

[[noreturn]] void fail(const std::string& path, const std::string& reason) {
  throw Error("cannot write " + describe(path) + ": " + reason);
}

}  // namespace

std::vector<std::uint8_t> read_file_limited(const std::string& path, std::size_t max_bytes, const std::string& what) {
  const auto fail_read = [&](const std::string& reason) -> Error {
    return Error("cannot read " + what + " " + describe(path) + ": " + reason);
  };
  const int fd = open(path.c_str(), O_RDONLY | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) throw fail_read(std::strerror(errno));
  struct stat st {};
  if (fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
    close(fd);
    throw fail_read("it is a directory");
  }
  if (S_ISREG(st.st_mode) && static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    close(fd);
    throw Error(what + " " + describe(path) + " is larger than the limit of " + std::to_string(max_bytes >> 20) +
                " MiB");
  }
  std::vector<std::uint8_t> bytes;
  if (S_ISREG(st.st_mode)) bytes.reserve(static_cast<std::size_t>(st.st_size));
  std::uint8_t chunk[1 << 16];
  for (;;) {
    const ssize_t n = read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      close(fd);
      throw fail_read(std::strerror(e));
    }
    if (n == 0) break;
    if (bytes.size() + static_cast<std::size_t>(n) > max_bytes) {
      close(fd);
      throw Error(what + " " + describe(path) + " is larger than the limit of " + std::to_string(max_bytes >> 20) +
                  " MiB");
    }
    bytes.insert(bytes.end(), chunk, chunk + n);
  }
  close(fd);
  return bytes;
}

OutputFile::OutputFile(std::string path) : path_(std::move(path)) {
  if (path_.empty()) fail(path_, "empty file name");
  struct stat st {};
  if (stat(path_.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) fail(path_, "it is a directory");
    if (!S_ISREG(st.st_mode)) {
      // A device or FIFO: write into it. O_NONBLOCK so a FIFO without a reader fails instead of hanging.
      const int fd = open(path_.c_str(), O_WRONLY | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
      if (fd < 0) fail(path_, std::strerror(errno));
      fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
      file_ = fdopen(fd, "wb");
      if (!file_) {
        close(fd);
        fail(path_, std::strerror(errno));
      }
      return;
    }
    mode_ = st.st_mode & 07777;
    keep_mode_ = true;
  }
  std::random_device random;
  static constexpr char kLetters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  slot_ = reserve_cleanup_slot();  // before the file exists: no moment where it exists without its cleanup
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    std::string name = path_ + ".";
    for (int k = 0; k < 8; ++k) name += kLetters[random() % (sizeof kLetters - 1)];
    name += ".partial";
    fd = open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd >= 0) {
      temp_ = std::move(name);
    } else if (errno != EEXIST) {
      const int e = errno;
      abandon();  // frees the slot (a throwing constructor runs no destructor)
      fail(path_, std::strerror(e));
    }
  }
  if (fd < 0) {
    abandon();
    fail(path_, "no unused temporary file name");
  }
  arm_cleanup_slot(slot_, temp_);
  file_ = fdopen(fd, "wb");
  if (!file_) {
    const int e = errno;
    close(fd);
    abandon();
    fail(path_, std::strerror(e));
  }
}

OutputFile::~OutputFile() { abandon(); }

void OutputFile::abandon() {
  if (file_) {
    std::fclose(file_);
    file_ = nullptr;
  }
  if (!temp_.empty()) {
    unlink(temp_.c_str());
    temp_.clear();
  }
  unregister(slot_);
  slot_ = -1;
}

void OutputFile::commit() {
  if (!file_) fail(path_, "already closed");
  const bool write_error = std::ferror(file_) != 0;
  int e = errno;
  bool ok = !write_error && std::fflush(file_) == 0;
  if (!ok && !write_error) e = errno;
  if (ok && keep_mode_ && fchmod(fileno(file_), mode_) != 0) {
    ok = false;
    e = errno;
  }
  if (std::fclose(file_) != 0 && ok) {
    ok = false;
    e = errno;
  }
  file_ = nullptr;
  if (!ok) {
    abandon();
    fail(path_, e != 0 ? std::strerror(e) : "write failed");
  }
  if (temp_.empty()) return;  // written through
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    e = errno;
    abandon();
    fail(path_, std::strerror(e));
  }
  temp_.clear();
  unregister(slot_);
  slot_ = -1;
}

void install_output_cleanup_handlers() {
  struct sigaction action {};
  action.sa_handler = remove_partial_files_and_die;
  sigemptyset(&action.sa_mask);
  for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) sigaction(sig, &action, nullptr);
  std::signal(SIGXFSZ, SIG_IGN);
}

}  // namespace vraster
