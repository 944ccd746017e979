// Deterministic parallel loops. Work items are claimed dynamically, but every item
// writes only its own output, so the result does not depend on the thread count or
// on which thread ran which item: that is how the renderer stays bit-identical.
#pragma once

#include <algorithm>
#include <atomic>
#include <cfenv>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "renderer/util/simd.hpp"

namespace hsr {

// 0 means "all cores".
inline int resolveThreadCount(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// Threads kept from one parallel loop to the next: starting a thread for every loop
// cost about 45 microseconds a loop on this machine kind, and a frame runs several loops
// (the z-buffer's visibility pass four: a twentieth of counters' pass on two threads).
// One loop at a time uses the pool; a loop started while it is busy (from inside a loop's
// body, or from another thread) starts threads of its own, as every loop once did.
//
// Waking a sleeping thread costs about as much as starting one on a virtual machine (its
// idle core has to be woken too), and loops come in bursts, so a thread that has
// finished, and the caller waiting for the helpers, first spin a short while.
class ThreadPool {
 public:
  static ThreadPool& shared() {
    static ThreadPool pool;
    return pool;
  }

  // Runs work(worker) for worker in [1, helpers] on the pool's threads, each in the
  // caller's floating-point environment (as a thread started by the caller would be:
  // the tests trap exceptions by it), while the caller runs work(0); returns when all
  // have returned. False, having run nothing, when the pool is busy.
  template <typename Work>
  bool run(int helpers, Work& work) {
    std::unique_lock busy(busy_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    {
      std::lock_guard lock(mutex_);
      while (int(threads_.size()) < helpers) threads_.emplace_back([this, worker = int(threads_.size()) + 1] { serve(worker); });
      fegetenv(&environment_);
      job_ = {&work, [](void* context, int worker) { (*static_cast<Work*>(context))(worker); }};
      helpers_ = helpers;
      unfinished_ = helpers;
      ++generation_;
    }
    jobReady_.notify_all();
    struct WaitForHelpers {  // also when work(0) throws: the helpers still use `work`
      ThreadPool& pool;
      ~WaitForHelpers() {
        spinWhile([&] { return pool.unfinished_ != 0; });
        std::unique_lock lock(pool.mutex_);
        pool.jobDone_.wait(lock, [&] { return pool.unfinished_ == 0; });
      }
    } waitForHelpers{*this};
    work(0);
    return true;
  }

  ~ThreadPool() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    jobReady_.notify_all();
    for (std::thread& thread : threads_) thread.join();  // while the rest of the pool still lives
  }

 private:
  ThreadPool() = default;

  // Spins while `busy()` holds, up to kSpin.
  template <typename Busy>
  static void spinWhile(Busy&& busy) {
    constexpr auto kSpin = std::chrono::microseconds(50);
    const auto until = std::chrono::steady_clock::now() + kSpin;
    while (busy() && std::chrono::steady_clock::now() < until) spinWaitHint();
  }

  void serve(int worker) {
    std::uint64_t served = 0;
    std::unique_lock lock(mutex_);
    for (;;) {
      lock.unlock();
      spinWhile([&] { return generation_ == served && !stopping_; });
      lock.lock();
      jobReady_.wait(lock, [&] { return stopping_ || generation_ != served; });
      if (stopping_) return;
      served = generation_;
      if (worker > helpers_) continue;
      const Job job = job_;
      const fenv_t environment = environment_;
      lock.unlock();
      fesetenv(&environment);
      job.run(job.context, worker);
      lock.lock();
      if (--unfinished_ == 0) jobDone_.notify_one();
    }
  }

  struct Job {
    void* context = nullptr;
    void (*run)(void*, int) = nullptr;
  };
  std::mutex busy_;   // held by the loop using the pool
  std::mutex mutex_;  // guards everything below
  std::condition_variable jobReady_, jobDone_;
  Job job_;
  fenv_t environment_{};
  int helpers_ = 0;
  // Written under mutex_, and also read without it while spinning.
  std::atomic<int> unfinished_ = 0;
  std::atomic<std::uint64_t> generation_ = 0;  // one more for every job
  std::atomic<bool> stopping_ = false;
  std::vector<std::thread> threads_;  // joined by the destructor (std::jthread is not in every standard library yet)
};

// The time spent in parallel loops, so that a pass can say how much of it ran on one
// thread: its serial time, which by Amdahl's law caps its speed-up on any number of
// cores. Only a thread's outermost loop counts (a loop inside a loop's body is part of
// it). Two sums: the loops' wall time, and what they would take on kAmdahlCores cores:
// a loop that ran on W workers, spread over min(its items, kAmdahlCores) instead (a loop
// of 4 tiles uses at most 4; one cut into a part per thread, all of them). Taken by every
// loop, not only under --stats: two clock reads a loop.
class ParallelTime {
 public:
  static constexpr int kAmdahlCores = 16;  // the cores of the machines students and instructors use

  struct Totals {
    double seconds = 0;               // in loops, start to end
    double secondsOnAmdahlCores = 0;  // the same loops, spread over kAmdahlCores cores
  };
  static Totals totals() {
    return {double(loopNanoseconds_.load(std::memory_order_relaxed)) * 1e-9,
            double(amdahlNanoseconds_.load(std::memory_order_relaxed)) * 1e-9};
  }
  // Whether this thread runs inside a parallel loop (its time is already counted there).
  static bool insideLoop() { return insideLoop_; }

  // Marks its lifetime as inside a loop on this thread; a mark made with workers > 0
  // outside any loop also times the loop, which runs on that many workers.
  class Loop {
   public:
    Loop(std::size_t items, int workers)
        : timed_(!insideLoop_ && workers > 0),
          wasInside_(insideLoop_),
          width_(std::max<std::int64_t>(1, std::min<std::int64_t>(kAmdahlCores, std::int64_t(items)))),
          workers_(workers) {
      insideLoop_ = true;
      if (timed_) start_ = std::chrono::steady_clock::now();
    }
    ~Loop() {
      insideLoop_ = wasInside_;
      if (!timed_) return;
      const std::int64_t elapsed = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_).count();
      loopNanoseconds_.fetch_add(elapsed, std::memory_order_relaxed);
      amdahlNanoseconds_.fetch_add(elapsed * workers_ / width_, std::memory_order_relaxed);
    }
    Loop(const Loop&) = delete;
    Loop& operator=(const Loop&) = delete;

   private:
    bool timed_, wasInside_;
    std::int64_t width_;  // the most cores the loop could spread over
    int workers_;
    std::chrono::steady_clock::time_point start_{};
  };

 private:
  static inline std::atomic<std::int64_t> loopNanoseconds_{0}, amdahlNanoseconds_{0};
  static inline thread_local bool insideLoop_ = false;
};

// How many workers parallelFor(count, threads, ...) runs: its bodies see worker numbers
// [0, parallelWorkers(count, threads)), so per-worker state can be made in advance.
inline int parallelWorkers(std::size_t count, int threads) {
  return std::max(1, std::min<int>(resolveThreadCount(threads), static_cast<int>(count)));
}

// Calls body(item, worker) for item in [0, count), worker in [0, threads).
template <typename Body>
void parallelFor(std::size_t count, int threads, Body&& body) {
  const int workers = parallelWorkers(count, threads);
  // A loop cut into one part per thread asked for (bands of rows, say) is cut into as many
  // on more cores: for Amdahl's estimate its items are not a limit.
  const bool cutPerThread = count == std::size_t(resolveThreadCount(threads));
  const ParallelTime::Loop timed(cutPerThread ? std::size_t(ParallelTime::kAmdahlCores) : count, workers);
  if (workers <= 1) {
    for (std::size_t item = 0; item < count; ++item) body(item, 0);
    return;
  }
  std::atomic<std::size_t> next{0};
  auto work = [&](int worker) {
    const ParallelTime::Loop inside(count, 0);  // untimed: a loop a helper starts is this loop's time
    for (std::size_t item = next++; item < count; item = next++) body(item, worker);
  };
  if (ThreadPool::shared().run(workers - 1, work)) return;
  std::vector<std::thread> pool;
  struct JoinAll {  // also when work(0) throws: the others still use `work`
    std::vector<std::thread>& threads;
    ~JoinAll() {
      for (std::thread& thread : threads) thread.join();
    }
  } joinAll{pool};
  for (int worker = 1; worker < workers; ++worker) pool.emplace_back(work, worker);
  work(0);
}

// Calls body(index) for index in [0, count), the indices claimed `chunk` at a time: for
// loops whose items are too small to be claimed one by one. As with parallelFor, each
// item must write only its own output.
template <typename Body>
void parallelForEach(std::size_t count, std::size_t chunk, int threads, Body&& body) {
  parallelFor((count + chunk - 1) / chunk, threads, [&](std::size_t part, int) {
    for (std::size_t index = part * chunk; index < std::min(count, (part + 1) * chunk); ++index) body(index);
  });
}

// Sets a plain flag from 0 to 1 atomically and says whether this call did: among threads
// racing to claim the same item, exactly one wins (std::atomic_ref's load and exchange,
// as GCC and clang give them, since not every standard library has atomic_ref yet).
inline bool claimFlag(std::uint32_t& flag) {
  return __atomic_load_n(&flag, __ATOMIC_RELAXED) == 0 && __atomic_exchange_n(&flag, 1u, __ATOMIC_RELAXED) == 0;
}

// Splits [0, count) into `parts` contiguous ranges, as even as possible.
inline std::pair<std::size_t, std::size_t> partRange(std::size_t count, std::size_t parts, std::size_t part) {
  return {count * part / parts, count * (part + 1) / parts};
}

}  // namespace hsr
