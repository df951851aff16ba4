// The parallel loops of the emulator's fast mode and of the tracer, on TBB. Under ThreadSanitizer they run on
// plain std::threads instead: Debian's libtbb is not instrumented, so TSan cannot see the synchronisation that
// hands a task to a worker and reports hundreds of false races in every loop body (docs/design/testing.md). On plain
// threads TSan sees every edge, and every report in hpsf's code is real. Header-only: its users link TBB::tbb.
#ifndef HPSF_CORE_PARALLEL_FOR_H
#define HPSF_CORE_PARALLEL_FOR_H

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#if defined(__SANITIZE_THREAD__)
#define HPSF_PLAIN_THREADS 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define HPSF_PLAIN_THREADS 1
#endif
#endif

namespace hpsf {

// body(begin, end) over chunks of `grain` that cover [0, n), on `threads` plain std::threads (0: all cores), the
// calling thread among them. The first exception a chunk throws stops the loop and is rethrown here.
template <typename Body>
void ParallelForOnPlainThreads(std::size_t n, std::size_t grain, const Body& body, int threads = 0) {
  grain = std::max<std::size_t>(grain, 1);
  const std::size_t chunks = (n + grain - 1) / grain;
  const std::size_t workers = threads > 0 ? std::size_t(threads) : std::max(1u, std::thread::hardware_concurrency());
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex failure_mutex;
  std::exception_ptr failure;
  const auto work = [&] {
    for (std::size_t chunk; !failed.load() && (chunk = next.fetch_add(1)) < chunks;) {
      try {
        body(chunk * grain, std::min(n, (chunk + 1) * grain));
      } catch (...) {
        std::lock_guard lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < std::min(workers, chunks); ++w) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

// body(begin, end) over chunks of about `grain` that cover [0, n), on `threads` threads (0: all cores): TBB's,
// or plain ones under TSan. The first exception a chunk throws stops the loop and is rethrown here.
template <typename Body>
void ParallelFor(std::size_t n, std::size_t grain, const Body& body, int threads = 0) {
#ifdef HPSF_PLAIN_THREADS
  ParallelForOnPlainThreads(n, grain, body, threads);
#else
  std::optional<tbb::global_control> limit;
  if (threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, std::max<std::size_t>(grain, 1)),
                    [&](const tbb::blocked_range<std::size_t>& range) { body(range.begin(), range.end()); });
#endif
}

// body(begin, end, partial) -> partial over chunks of [0, n) on plain threads, each chunk starting from
// `identity`; the partials are combined in chunk order by join(a, b) -> a + b.
template <typename T, typename Body, typename Join>
T ParallelReduceOnPlainThreads(std::size_t n, std::size_t grain, T identity, const Body& body, const Join& join) {
  grain = std::max<std::size_t>(grain, 1);
  std::vector<std::optional<T>> partials((n + grain - 1) / grain);
  ParallelForOnPlainThreads(
      n, grain, [&](std::size_t begin, std::size_t end) { partials[begin / grain] = body(begin, end, identity); });
  for (std::optional<T>& partial : partials) identity = join(std::move(identity), *partial);
  return identity;
}

// tbb::parallel_reduce, or the same on plain threads under TSan.
template <typename T, typename Body, typename Join>
T ParallelReduce(std::size_t n, std::size_t grain, T identity, const Body& body, const Join& join) {
#ifdef HPSF_PLAIN_THREADS
  return ParallelReduceOnPlainThreads(n, grain, std::move(identity), body, join);
#else
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, std::max<std::size_t>(grain, 1)), std::move(identity),
      [&](const tbb::blocked_range<std::size_t>& range, T partial) {
        return body(range.begin(), range.end(), std::move(partial));
      },
      join);
#endif
}

}  // namespace hpsf

#endif  // HPSF_CORE_PARALLEL_FOR_H
