// Work on every core for the host's passes over a big model (issue 52): a loop whose iterations
// write only their own elements, and a sort.
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <iterator>
#include <thread>
#include <vector>

namespace vitrum {

// `run(part)` for each part in [0, parts), one a thread, the calling thread taking part 0. The first
// exception a part throws (by part) is rethrown once all have ended; a thread that cannot start
// (no memory for its stack) throws once those started have ended.
template <class Run>
void onThreads(std::size_t parts, Run&& run) {
    if (parts <= 1) {
        if (parts == 1) run(std::size_t(0));
        return;
    }
    std::vector<std::exception_ptr> failed(parts);
    auto guarded = [&](std::size_t part) {
        try {
            run(part);
        } catch (...) {
            failed[part] = std::current_exception();
        }
    };
    std::vector<std::thread> threads;
    threads.reserve(parts - 1);
    try {
        for (std::size_t part = 1; part < parts; ++part) threads.emplace_back(guarded, part);
    } catch (...) {
        for (std::thread& t : threads) t.join();
        throw;
    }
    guarded(0);
    for (std::thread& t : threads) t.join();
    for (const std::exception_ptr& e : failed)
        if (e) std::rethrow_exception(e);
}

// `body(begin, end)` for chunks covering [0, count), one contiguous chunk a thread, the calling
// thread taking the first; ranges under `minChunk` a thread run on fewer threads. The first
// exception a chunk throws is rethrown once all have ended.
template <class Body>
void parallelFor(std::size_t count, Body&& body, std::size_t minChunk = std::size_t(1) << 15) {
    const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t chunks = std::clamp<std::size_t>(count / std::max<std::size_t>(minChunk, 1), 1, cores);
    onThreads(chunks, [&](std::size_t chunk) { body(count * chunk / chunks, count * (chunk + 1) / chunks); });
}

// std::sort(first, last, less) on `threads` threads (0: every core), in place and with no more
// memory: the range split around the median of an even sample (everything below it to the left),
// each side sorted by half the threads. The same order as std::sort wherever `less` is a strict
// total order.
template <class Iterator, class Less>
void parallelSort(Iterator first, Iterator last, Less less, unsigned threads = 0) {
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    constexpr std::ptrdiff_t kSmall = std::ptrdiff_t(1) << 16;  // not worth a thread
    constexpr std::ptrdiff_t kSample = 255;
    const std::ptrdiff_t count = last - first;
    if (threads < 2 || count < kSmall) {
        std::sort(first, last, less);
        return;
    }
    using Value = typename std::iterator_traits<Iterator>::value_type;
    std::vector<Value> sample;
    sample.reserve(kSample);
    for (std::ptrdiff_t k = 0; k < kSample; ++k) sample.push_back(first[count * k / kSample]);
    std::nth_element(sample.begin(), sample.begin() + kSample / 2, sample.end(), less);
    const Value pivot = sample[kSample / 2];
    Iterator middle = std::partition(first, last, [&](const Value& v) { return less(v, pivot); });
    if (middle == first) {  // the pivot is the smallest: nothing went left
        middle = std::partition(first, last, [&](const Value& v) { return !less(pivot, v); });  // equal ones left
        if (middle == last) return;  // all equal: sorted
    }
    const unsigned leftThreads = threads / 2;
    std::exception_ptr failed;
    std::thread left([&] {
        try {
            parallelSort(first, middle, less, leftThreads);
        } catch (...) {
            failed = std::current_exception();
        }
    });
    try {
        parallelSort(middle, last, less, threads - leftThreads);
    } catch (...) {
        left.join();
        throw;
    }
    left.join();
    if (failed) std::rethrow_exception(failed);
}

}  // namespace vitrum
