// Persistent worker pool for CPU_THREADED. Workers spin briefly between the many short passes
// of a step (a step is tens of barriers), then sleep on a condition variable when idle, so an
// idle world costs no CPU. The paper woke four workers through a mutex per step; here a pass
// costs one atomic increment to start, one claim per chunk and one increment per chunk to finish.
// A pass is size() chunks; each thread takes its own chunk, then any not yet taken, so a worker
// that the OS has not run yet (a loaded machine, a phone's big.LITTLE cores) delays nobody: the
// others take its chunk. Which thread runs a chunk never changes what the chunk computes.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace drape {

class ThreadPool {
public:
    /// Below this many items a pass runs on the caller alone: a particle pass over fewer is a few
    /// microseconds, about what waking and joining the workers costs.
    static constexpr uint32_t kMinParallelCount = 2048;

    /// threads: total including the calling thread (>= 1).
    explicit ThreadPool(uint32_t threads);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    uint32_t size() const { return uint32_t(workers_.size()) + 1; }

    /// Chunks that parallel_chunks splits count items into: size(), or 1 (the caller alone) below
    /// kMinParallelCount.
    uint32_t chunks(uint32_t count) const { return count < kMinParallelCount ? 1u : size(); }

    /// Runs fn(k, begin, end) for each of the chunks(count) contiguous ranges of [0, count); returns
    /// when all are done. The split depends only on count and size().
    template <class Fn>
    void parallel_chunks(uint32_t count, Fn&& fn) {
        const uint32_t n = chunks(count);
        if (n == 1) {
            fn(0u, 0u, count);
            return;
        }
        auto job = [&](uint32_t t) {
            uint64_t b = uint64_t(count) * t / n, e = uint64_t(count) * (t + 1) / n;
            fn(t, uint32_t(b), uint32_t(e));
        };
        run(&invoke<decltype(job)>, &job);
    }

    /// parallel_chunks without the chunk's index: fn(begin, end).
    template <class Fn>
    void parallel_for(uint32_t count, Fn&& fn) {
        parallel_chunks(count, [&](uint32_t, uint32_t b, uint32_t e) { fn(b, e); });
    }

    /// Runs fn(begin, end) over [0, count) in ranges of at most grain items: each thread takes the
    /// ranges of its own share (parallel_chunks' split) in order, then those still left in the
    /// others' shares, so that a thread slowed down mid-pass (a busy core) holds the pass up by one
    /// range at most, not by the rest of its share. fn's result per item must not depend on the
    /// ranges.
    template <class Fn>
    void parallel_grains(uint32_t count, uint32_t grain, Fn&& fn) {
        const uint32_t n = size();
        for (uint32_t t = 0; t < n; ++t) cursor_[t].next.store(share(count, t), std::memory_order_relaxed);
        auto job = [&](uint32_t t) {
            for (uint32_t k = 0; k < n; ++k) {
                const uint32_t c = t + k < n ? t + k : t + k - n, end = share(count, c + 1);
                while (cursor_[c].next.load(std::memory_order_relaxed) < end) {
                    const uint32_t b = cursor_[c].next.fetch_add(grain, std::memory_order_relaxed);
                    if (b < end) fn(b, end - b < grain ? end : b + grain);
                }
            }
        };
        run(&invoke<decltype(job)>, &job);
    }

    /// Runs fn(k) once for each chunk k in [0, size()), each on whichever thread takes it (chunk k
    /// usually on thread k, 0 = caller); returns when all are done. fn must not depend on which
    /// thread runs it.
    template <class Fn>
    void run_on_all(Fn&& fn) {
        run(&invoke<Fn>, &fn);
    }

private:
    using JobFn = void (*)(void*, uint32_t);
    template <class F>
    static void invoke(void* f, uint32_t t) {
        (*static_cast<F*>(f))(t);
    }
    void run(JobFn fn, void* ctx);
    /// Start of thread t's share of count items.
    uint32_t share(uint32_t count, uint32_t t) const { return uint32_t(uint64_t(count) * t / size()); }
    /// Claims and runs the chunks of job gen still free, chunk own first.
    void take_chunks(uint32_t gen, uint32_t own);
    void worker_main(uint32_t index);

    std::vector<std::thread> workers_;
    JobFn job_ = nullptr;
    void* job_ctx_ = nullptr;
    std::atomic<uint32_t> generation_{0};  ///< of the last job published
    std::vector<std::atomic<uint32_t>> chunk_;  ///< per chunk: the generation of the last job that claimed it
    std::atomic<uint32_t> done_{0};        ///< chunks of the current job finished
    /// parallel_grains: per share the next item not yet taken, each on its own cache line (its
    /// thread takes from it alone until a thread that finished early comes for the rest).
    struct alignas(64) Cursor {
        std::atomic<uint32_t> next{0};
    };
    std::vector<Cursor> cursor_;
    std::atomic<uint32_t> sleepers_{0};
    std::atomic<bool> stop_{false};
    std::mutex mutex_;
    std::condition_variable wake_;
#ifdef DRAPE_POOL_TRACE
    // Measurement build only (-DDRAPE_POOL_TRACE; tests/bench/README.md, "Where two threads' wall time
    // goes"; two threads): per pass the TSC at publish, when the caller's chunks were done, when all
    // were; per chunk its start, end and thread. Written to $DRAPE_POOL_TRACE.<pid>.<n> when the pool
    // ends. DRAPE_POOL_SOLO=1: the worker never takes a chunk, so the caller runs every pass's chunks
    // alone (the same passes on one core).
    struct TraceRecord {
        const void* fn;
        uint64_t publish, caller_done, all_done;
        uint64_t start[2], end[2];
        uint32_t thread[2];
    };
    std::vector<TraceRecord> trace_;
    bool solo_ = false;
#endif
};

}  // namespace drape
