// The rasterizer's worker pool (band_pool.hpp).
#include "raster/band_pool.hpp"

#include <algorithm>
#include <chrono>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace vraster::detail {
namespace {

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

constexpr std::uint64_t pack(std::uint32_t generation, int bands, int next) {
  return std::uint64_t{generation} << 32 | static_cast<std::uint64_t>(bands) << 16 | static_cast<std::uint64_t>(next);
}
constexpr std::uint32_t generation_of(std::uint64_t word) { return static_cast<std::uint32_t>(word >> 32); }
constexpr int bands_of(std::uint64_t word) { return static_cast<int>(word >> 16 & 0xFFFF); }
constexpr int next_of(std::uint64_t word) { return static_cast<int>(word & 0xFFFF); }

// How long an idle worker keeps spinning for the next run before it sleeps: longer than the gap between two fills
// of a frame (flattening the next path, small fills drawn on one thread), short enough not to hold a core for long.
constexpr auto kSpinTime = std::chrono::microseconds(200);

}  // namespace

BandPool::BandPool(int threads) {
  const int workers = std::max(threads, 1) - 1;
  workers_.reserve(static_cast<std::size_t>(workers));
  for (int i = 1; i <= workers; ++i) workers_.emplace_back([this, i] { worker_loop(i); });
}

BandPool::~BandPool() {
  stop_.store(true);
  wake_.fetch_add(1);
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

// Claims bands of the published run one at a time and runs them.
int BandPool::take_bands(int worker) {
  int taken = 0;
  std::uint64_t word = claim_.load(std::memory_order_acquire);
  while (next_of(word) < bands_of(word)) {
    if (!claim_.compare_exchange_weak(word, word + 1, std::memory_order_acq_rel, std::memory_order_acquire)) continue;
    // The claim succeeded, so this run is not over: job_ and call_ are still this run's.
    call_(job_, next_of(word), worker);
    done_.fetch_add(1, std::memory_order_release);
    ++taken;
    word = claim_.load(std::memory_order_acquire);
  }
  return taken;
}

void BandPool::start_erased(int bands, void* job, Call call) {
  bands = std::min(bands, kMaxBands);
  if (bands <= 0) return;
  if (workers_.empty()) {
    for (int b = 0; b < bands; ++b) call(job, b, 0);
    return;
  }
  job_ = job;
  call_ = call;
  bands_ = bands;
  done_.store(0, std::memory_order_relaxed);
  ++generation_;
  claim_.store(pack(generation_, bands, 0), std::memory_order_release);
  wake_.store(generation_);
  if (sleepers_.load() > 0) wake_.notify_all();
}

int BandPool::finish() {
  if (bands_ == 0) return 0;
  const int taken = take_bands(0);
  // Bands claimed by workers may still be running.
  for (int spins = 0; done_.load(std::memory_order_acquire) < bands_; ++spins) {
    if (spins < 4096) {
      cpu_relax();
    } else {
      std::this_thread::yield();  // a worker was descheduled mid-band: let it run
    }
  }
  bands_ = 0;
  return taken;
}

void BandPool::worker_loop(int worker) {
  std::uint32_t seen = 0;
  for (;;) {
    // Wait for a new run: spin a little, then sleep until start() or the destructor wakes us.
    if (wake_.load() == seen) {
      const auto spin_until = std::chrono::steady_clock::now() + kSpinTime;
      int spins = 0;
      while (wake_.load(std::memory_order_relaxed) == seen && !stop_.load(std::memory_order_relaxed)) {
        // After a short busy spin, yield between checks: on a machine whose cores are all busy, a waiting worker
        // then hands its core to whoever can run (the thread drawing the frame, among others).
        if (++spins < 256) {
          cpu_relax();
        } else {
          std::this_thread::yield();
        }
        if (spins % 64 == 0 && std::chrono::steady_clock::now() > spin_until) {
          sleepers_.fetch_add(1);
          while (wake_.load() == seen && !stop_.load()) wake_.wait(seen);
          sleepers_.fetch_sub(1);
          break;
        }
      }
    }
    if (stop_.load()) return;
    seen = wake_.load();
    take_bands(worker);
  }
}

}  // namespace vraster::detail
