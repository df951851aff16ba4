#include "core/count_words.h"

#include "core/shared/packed_sums.h"

namespace hpsf {

void SplitCountWords(std::span<const std::uint32_t> words, std::span<std::uint64_t> counts,
                     std::span<std::uint32_t> frame_counters) {
  for (std::size_t s = 0; s < words.size(); ++s) {
    counts[s] = shared::PackedCount(words[s]);
    frame_counters[s] = shared::PackedFrames(words[s]);
  }
}

void PackCountWords(std::span<const std::uint64_t> counts, std::span<const std::uint32_t> frame_counters,
                    std::span<std::uint32_t> words) {
  for (std::size_t s = 0; s < words.size(); ++s) {
    words[s] = shared::PackCountWord(std::uint32_t(counts[s]), frame_counters[s]);
  }
}

}  // namespace hpsf
