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

ThreadPool::ThreadPool(uint32_t threads) {
    for (uint32_t i = 1; i < threads; ++i) workers_.emplace_back([this, i] { worker_main(i); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
        generation_.fetch_add(1);
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
}

void ThreadPool::run(JobFn fn, void* ctx) {
    job_ = fn;
    job_ctx_ = ctx;
    pending_.store(uint32_t(workers_.size()));
    generation_.fetch_add(1);  // publishes job_ (seq_cst)
    if (sleepers_.load() > 0) {
        std::lock_guard<std::mutex> lock(mutex_);
        wake_.notify_all();
    }
    fn(ctx, 0);
    for (int spins = 0; pending_.load(std::memory_order_acquire) != 0; ++spins) {
        if (spins < kSpinRounds)
            DRAPE_CPU_RELAX();
        else
            std::this_thread::yield();
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
        job_(job_ctx_, index);
        pending_.fetch_sub(1, std::memory_order_release);
    }
}

}  // namespace drape
