#include "backend/cpu/thread_pool.h"

#if defined(__x86_64__) || defined(_M_X64)
#include <immintrin.h>
#define DRAPE_CPU_RELAX() _mm_pause()
#elif defined(__aarch64__)
#define DRAPE_CPU_RELAX() asm volatile("yield")
#else
#define DRAPE_CPU_RELAX() ((void)0)
#endif

#ifdef DRAPE_POOL_TRACE  // measurement build (thread_pool.h), x86-64 and two threads only
#if !defined(__x86_64__)
#error "DRAPE_POOL_TRACE reads the TSC (x86-64)"
#endif
#include <dlfcn.h>
#include <unistd.h>
#include <x86intrin.h>
#include <cstdio>
#include <cstdlib>
#endif

namespace drape {
namespace {
// Waiting: spin this many rounds (the gap between passes of one step is µs), then yield the
// core this many times (so an oversubscribed machine still runs the thread that has work),
// then sleep (the gap between frames is ms).
constexpr int kSpinRounds = 2000;
constexpr int kYieldRounds = 200;
}  // namespace

ThreadPool::ThreadPool(uint32_t threads) : chunk_(threads), cursor_(threads) {
#ifdef DRAPE_POOL_TRACE
    trace_.reserve(size_t(1) << 20);
    solo_ = std::getenv("DRAPE_POOL_SOLO") && std::atoi(std::getenv("DRAPE_POOL_SOLO")) == 1;
#endif
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
#ifdef DRAPE_POOL_TRACE
    static std::atomic<int> pools{0};
    const char* path = std::getenv("DRAPE_POOL_TRACE");
    if (path && !trace_.empty()) {
        char name[512];
        std::snprintf(name, sizeof name, "%s.%d.%d", path, int(getpid()), pools.fetch_add(1));
        for (TraceRecord& r : trace_) {  // as offsets in the library (addr2line -e libdrape.so)
            Dl_info info{};
            if (dladdr(r.fn, &info)) r.fn = reinterpret_cast<const void*>(static_cast<const char*>(r.fn) - static_cast<const char*>(info.dli_fbase));
        }
        if (FILE* f = std::fopen(name, "wb")) {
            std::fwrite(trace_.data(), sizeof(TraceRecord), trace_.size(), f);
            std::fclose(f);
        }
    }
#endif
}

void ThreadPool::run(JobFn fn, void* ctx) {
#ifdef DRAPE_POOL_TRACE
    if (trace_.size() == trace_.capacity()) trace_.clear();
    trace_.push_back(TraceRecord{reinterpret_cast<const void*>(fn), __rdtsc(), 0, 0, {0, 0}, {0, 0}, {9, 9}});
#endif
    job_ = fn;
    job_ctx_ = ctx;
    done_.store(0, std::memory_order_relaxed);
    const uint32_t gen = generation_.fetch_add(1) + 1;  // publishes job_ and done_ (seq_cst)
    if (sleepers_.load() > 0) {
        std::lock_guard<std::mutex> lock(mutex_);
        wake_.notify_all();
    }
    take_chunks(gen, 0);
#ifdef DRAPE_POOL_TRACE
    trace_.back().caller_done = __rdtsc();
#endif
    for (int spins = 0; done_.load(std::memory_order_acquire) != size(); ++spins) {
        if (spins < kSpinRounds)
            DRAPE_CPU_RELAX();
        else
            std::this_thread::yield();
    }
#ifdef DRAPE_POOL_TRACE
    trace_.back().all_done = __rdtsc();
#endif
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
#ifdef DRAPE_POOL_TRACE
        TraceRecord& rec = trace_.back();  // the caller pushed it before publishing
        rec.start[c & 1] = __rdtsc();
        rec.thread[c & 1] = own;  // the thread: 0 = caller
#endif
        job_(job_ctx_, c);
#ifdef DRAPE_POOL_TRACE
        rec.end[c & 1] = __rdtsc();
#endif
        done_.fetch_add(1, std::memory_order_release);
    }
}

void ThreadPool::worker_main(uint32_t index) {
#ifdef DRAPE_POOL_TRACE
    if (solo_) {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stop_.load(); });
        return;
    }
#endif
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
