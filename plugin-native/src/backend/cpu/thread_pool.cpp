#include "backend/cpu/thread_pool.h"

#if defined(__x86_64__) || defined(_M_X64)
#include <immintrin.h>
#define DRAPE_CPU_RELAX() _mm_pause()
#elif defined(__aarch64__)
#define DRAPE_CPU_RELAX() asm volatile("yield")
#else
#define DRAPE_CPU_RELAX() ((void)0)
#endif

namespace drape {
namespace {
// Waiting: spin this many rounds (the gap between passes of one step is µs), then yield the
// core this many times (so an oversubscribed machine still runs the thread that has work),
// then sleep (the gap between frames is ms).
constexpr int kSpinRounds = 2000;
constexpr int kYieldRounds = 200;
}  // namespace

ThreadPool::ThreadPool(uint32_t threads) : chunk_(threads) {
    for (uint32_t i = 1; i < threads; ++i) workers_.emplace_back([this, i] { worker_main(i); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
        generation_.fetch_add(1);  // its chunks stay unclaimable: they hold the generation before
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
}

void ThreadPool::run(JobFn fn, void* ctx) {
    job_ = fn;
    job_ctx_ = ctx;
    done_.store(0, std::memory_order_relaxed);
    const uint32_t gen = generation_.fetch_add(1) + 1;  // publishes job_ and done_ (seq_cst)
    if (sleepers_.load() > 0) {
        std::lock_guard<std::mutex> lock(mutex_);
        wake_.notify_all();
    }
    take_chunks(gen, 0);
    for (int spins = 0; done_.load(std::memory_order_acquire) != size(); ++spins) {
        if (spins < kSpinRounds)
            DRAPE_CPU_RELAX();
        else
            std::this_thread::yield();
    }
}

void ThreadPool::take_chunks(uint32_t gen, uint32_t own) {
    // Each chunk is claimed once per job by moving its generation from the previous job's to this
    // one's: the thread's own chunk first (the same data as in the last pass, still in its cache),
    // then any left, so a thread the OS has not run yet does not hold up the others.
    const uint32_t n = size();
    for (uint32_t k = 0; k < n; ++k) {
        const uint32_t c = own + k < n ? own + k : own + k - n;
        uint32_t expected = gen - 1;
        if (chunk_[c].load(std::memory_order_relaxed) != expected ||
            !chunk_[c].compare_exchange_strong(expected, gen, std::memory_order_acquire))
            continue;
        job_(job_ctx_, c);
        done_.fetch_add(1, std::memory_order_release);
    }
}

void ThreadPool::worker_main(uint32_t index) {
    uint32_t seen = 0;
    for (;;) {
        uint32_t gen = generation_.load();
        for (int spins = 0; gen == seen && spins < kSpinRounds + kYieldRounds; ++spins) {
            if (spins < kSpinRounds)
                DRAPE_CPU_RELAX();
            else
                std::this_thread::yield();
            gen = generation_.load();
        }
        if (gen == seen) {
            std::unique_lock<std::mutex> lock(mutex_);
            sleepers_.fetch_add(1);
            wake_.wait(lock, [&] { return generation_.load() != seen || stop_.load(); });
            sleepers_.fetch_sub(1);
            gen = generation_.load();
        }
        if (stop_.load()) return;
        seen = gen;
        take_chunks(gen, index);
    }
}

}  // namespace drape
