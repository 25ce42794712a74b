#include "core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace gacompare::core {
namespace {

thread_local bool t_in_item = false;  // detail::in_item()

// One loop at a time: the stages call for_each_index from the run's own
// thread, never from inside an item. A chunk is claimed by a compare-and-swap
// on one word holding the loop's generation and its next chunk, so a worker
// that wakes late, after its loop is over, claims nothing of the next one:
// the caller waits only for the chunks taken, never for a sleeping worker.
// A waiting thread spins a while before it sleeps: a collision step posts
// its loops a millisecond or so apart (the world's blocks, the narrowphase),
// and waking a sleeping thread takes tens of microseconds each time: with
// 10^5 polls the worker slept between steps, and the 1,000-body box's
// blocks took 0.045 s of its 0.5 s where 10^6 polls take 0.024.
class Pool {
 public:
  explicit Pool(int workers) {
    for (int k = 0; k < workers; ++k) threads_.emplace_back([this] { work(); });
  }
  ~Pool() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
      generation_.fetch_add(1);
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
  }

  void run(std::size_t n, std::size_t grain, void* context, void (*call)(void*, std::size_t, std::size_t)) {
    grain = std::max<std::size_t>(grain, n >> 31);  // chunks fit the word's low 32 bits
    Loop loop{0, n, grain, (n + grain - 1) / grain, context, call};
    {
      std::lock_guard lock(mutex_);
      loop.generation = generation_.load() + 1;
      loop_ = loop;
      done_.store(0);
      error_ = nullptr;
      next_.store((loop.generation & 0xffffffffu) << 32);
      generation_.store(loop.generation);
    }
    wake_.notify_all();
    take_chunks(loop);
    const auto all_done = [&] { return done_.load() == loop.chunks; };
    if (!spin(all_done)) {
      std::unique_lock lock(mutex_);
      finished_.wait(lock, all_done);
    }
    if (error_) std::rethrow_exception(error_);
  }

 private:
  struct Loop {
    std::uint64_t generation;
    std::size_t n, grain, chunks;
    void* context;
    void (*call)(void*, std::size_t, std::size_t);
  };
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  std::atomic<std::uint64_t> generation_{0};
  bool stop_ = false;
  Loop loop_{};                          // the current loop, written under mutex_
  std::atomic<std::uint64_t> next_{0};   // the generation's low 32 bits << 32 | the next chunk
  std::atomic<std::size_t> done_{0};     // chunks finished
  std::exception_ptr error_;

  // Whether ready() came true within some 10^6 polls (a few milliseconds),
  // yielding the core every 256 polls: on a machine whose other core is
  // taken, a spinning thread would otherwise hold the one the work needs.
  template <class Ready>
  static bool spin(Ready&& ready) {
    for (int k = 1; k <= 1000000; ++k) {
      if (ready()) return true;
      if (k % 256 == 0) std::this_thread::yield();
    }
    return false;
  }

  void take_chunks(const Loop& loop) {
    for (std::uint64_t cur = next_.load();;) {
      if (cur >> 32 != (loop.generation & 0xffffffffu) || (cur & 0xffffffffu) >= loop.chunks) return;
      if (!next_.compare_exchange_weak(cur, cur + 1)) continue;  // cur now holds the newer word
      const std::size_t c = cur & 0xffffffffu;
      const std::size_t begin = c * loop.grain, end = std::min(loop.n, begin + loop.grain);
      t_in_item = true;
      try {
        loop.call(loop.context, begin, end);
      } catch (...) {
        std::lock_guard lock(mutex_);
        if (!error_) error_ = std::current_exception();
      }
      t_in_item = false;
      if (done_.fetch_add(1) + 1 == loop.chunks) {
        std::lock_guard lock(mutex_);  // so a caller about to sleep cannot miss it
        finished_.notify_all();
      }
      cur = next_.load();
    }
  }

  void work() {
    std::uint64_t seen = 0;
    for (;;) {
      if (!spin([&] { return generation_.load() != seen; })) {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return generation_.load() != seen; });
      }
      Loop loop;
      {
        std::lock_guard lock(mutex_);
        if (stop_) return;
        loop = loop_;
        seen = loop.generation;
      }
      take_chunks(loop);
    }
  }
};

int g_threads = 1;
bool g_fine_grains = false;
std::unique_ptr<Pool> g_pool;

}  // namespace

void set_threads(int n) {
  if (n < 1 || n > 256) throw std::invalid_argument("threads: expected 1 to 256, got " + std::to_string(n));
  if (n == g_threads) return;
  g_pool.reset();
  g_threads = n;
  if (n > 1) g_pool = std::make_unique<Pool>(n - 1);
}

int threads() { return g_threads; }

bool detail::in_item() { return t_in_item; }

void set_fine_grains(bool on) { g_fine_grains = on; }
bool fine_grains() { return g_fine_grains; }

void detail::run_chunks(std::size_t n, std::size_t grain, void* context,
                        void (*call)(void*, std::size_t, std::size_t)) {
  g_pool->run(n, grain, context, call);
}

}  // namespace gacompare::core
