// SPDX-License-Identifier: MIT
// The host tools' thread fan-out: one function for "run this on every core, up to a
// bound" and one for "hand out the items 0..n-1 to such workers". Results that must not
// depend on the thread count are written per item (by index), never in completion order.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <functional>
#include <thread>
#include <vector>

namespace sbr_host {

// Threads to use: the hardware's count, at most max_threads, at least 1.
inline unsigned worker_count(unsigned max_threads) {
    return std::max(1u, std::min(max_threads, std::thread::hardware_concurrency()));
}

// `work` on worker_count(max_threads) threads at once, joined before it returns.
inline void run_workers(unsigned max_threads, const std::function<void()> &work) {
    std::vector<std::thread> th;
    const unsigned nt = worker_count(max_threads);
    for (unsigned t = 0; t < nt; ++t) th.emplace_back(work);
    for (auto &t : th) t.join();
}

// item(i) for every i in [0, n), the items handed out one at a time to
// worker_count(max_threads) threads. `Worker` is per-thread state (e.g. a workspace),
// default-constructed once in each thread and passed to every item that thread runs.
template <class Worker, class Item>
void parallel_for(size_t n, unsigned max_threads, Item item) {
    std::atomic<size_t> next{0};
    run_workers(max_threads, [&]() {
        Worker w{};
        for (size_t i; (i = next++) < n;) item(i, w);
    });
}

}  // namespace sbr_host
