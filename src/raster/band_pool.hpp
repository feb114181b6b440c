// A small pool of worker threads for the rasterizer's bands: one fill's rows are cut into bands, and the calling
// thread and the workers take bands until none is left (dynamic claiming, so a slow band or a busy core does not
// hold the others back). Fills follow each other quickly within a frame, so a worker spins briefly before it
// sleeps: handing it the next fill costs a cache-line transfer, not a system call.
#pragma once

#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace vraster::detail {

class BandPool {
 public:
  /// `threads` counts the calling thread: threads - 1 workers are started (none for 1).
  explicit BandPool(int threads);
  ~BandPool();
  BandPool(const BandPool&) = delete;
  BandPool& operator=(const BandPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  /// Calls job(band, worker) once for every band in [0, bands) (at most kMaxBands), on this thread (worker 0) and
  /// the workers (1 .. threads - 1), and returns when every call has returned. Not reentrant: one run at a time.
  template <class Job>
  void run(int bands, Job& job) {
    start(bands, job);
    finish();
  }
  /// run() in two halves: start() hands the bands to the workers and returns at once (this thread takes none, and
  /// may do other work meanwhile); finish() takes what is left on this thread and returns when every call has
  /// returned. `job` must live until then, and every start() needs its finish() before the next start() or run().
  /// Without workers, start() makes every call itself.
  template <class Job>
  void start(int bands, Job& job) {
    start_erased(bands, &job, [](void* j, int band, int worker) { (*static_cast<Job*>(j))(band, worker); });
  }
  /// Returns how many of the run's bands this thread took (all of them: no worker got to the run before it).
  int finish();
  static constexpr int kMaxBands = 0xFFFF;

 private:
  using Call = void (*)(void* job, int band, int worker);
  void start_erased(int bands, void* job, Call call);
  int take_bands(int worker);  // returns how many it took
  void worker_loop(int worker);

  // The claim word: generation (32 bits) | band count (16) | next band (16). A worker claims band i of the run it
  // saw by a compare-exchange from (gen, bands, i) to (gen, bands, i + 1): that fails once the run is over, so a
  // late worker never touches the next run's job with this one's numbers.
  std::atomic<std::uint64_t> claim_{0};
  std::atomic<std::uint32_t> wake_{0};  // the generation again, for sleeping workers (futex-style wait / notify)
  std::atomic<int> sleepers_{0};
  std::atomic<int> done_{0};            // bands of the current run finished
  int bands_ = 0;                       // bands of the current run (0: none started since the last finish)
  std::atomic<bool> stop_{false};
  std::uint32_t generation_ = 0;
  void* job_ = nullptr;                 // written before a run is published, read only by whoever claimed a band
  Call call_ = nullptr;
  std::vector<std::thread> workers_;
};

}  // namespace vraster::detail
