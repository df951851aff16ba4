// packed-decimal's count words (core/shared/packed_sums.h) as a table dump keeps them: split into the 24-bit counts
// and the frame counters, and packed back. One place for the backends' read-back and loads, the capture reader and
// the capture's rerun; each call takes a range of slots, so a caller on a per-frame path splits the table in
// parallel chunks (core/parallel_for.h) and core itself needs no thread pool.
#ifndef HPSF_CORE_COUNT_WORDS_H
#define HPSF_CORE_COUNT_WORDS_H

#include <cstdint>
#include <span>

namespace hpsf {

// counts[s] and frame_counters[s] from words[s], for every s of `words` (the spans are equally long).
void SplitCountWords(std::span<const std::uint32_t> words, std::span<std::uint64_t> counts,
                     std::span<std::uint32_t> frame_counters);

// words[s] from counts[s] (its low 24 bits: a dump's count never exceeds them) and frame_counters[s].
void PackCountWords(std::span<const std::uint64_t> counts, std::span<const std::uint32_t> frame_counters,
                    std::span<std::uint32_t> words);

}  // namespace hpsf

#endif  // HPSF_CORE_COUNT_WORDS_H
