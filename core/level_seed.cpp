#include "core/level_seed.h"

#include <charconv>

#include "core/error.h"
#include "core/hash_table.h"
#include "core/shared/full_key.h"
#include "core/shared/level_seed.h"
#include "core/shared/lookup.h"

namespace hpsf {

std::string LevelSeed::ToString() const {
  if (!enabled) return "none";
  return shift == 0 ? "seed" : "seed:" + std::to_string(shift);
}

LevelSeed ParseLevelSeed(const std::string& text) {
  if (text == "none") return {};
  if (text == "seed") return {true, 0};
  const std::string prefix = "seed:";
  if (text.rfind(prefix, 0) == 0) {
    const char* first = text.data() + prefix.size();
    const char* last = text.data() + text.size();
    std::uint32_t shift = 0;
    auto [end, error] = std::from_chars(first, last, shift);
    if (error == std::errc() && end == last && first != last && shift <= 16) return {true, shift};
    throw ConfigError("--level-change", "seed needs a shift in [0, 16], as in seed:2; got '" + text + "'");
  }
  throw ConfigError("--level-change", "expected none, seed or seed:S; got '" + text + "'");
}

CellState SeedOf(const shared::KeyWords& cell, const LevelSeed& seed, bool fixed, const CellLookup& lookup) {
  CellState sum;
  if (!seed.enabled) return sum;
  for (std::uint32_t child = 0; child < shared::kLevelSeedChildren; ++child) {
    const std::optional<CellState> c = lookup(shared::ChildKeyWords(cell, child));
    if (!c) continue;
    sum.count += c->count;
    for (int k = 0; k < 3; ++k) {
      if (fixed) {
        sum.fixed_sum[k] += c->fixed_sum[k];
      } else {
        sum.float_sum[k] += c->float_sum[k];
      }
    }
  }
  if (sum.count > 0) return sum;
  const std::optional<CellState> parent = lookup(shared::ParentKeyWords(cell));
  if (!parent) return sum;
  sum.count = shared::ParentShareOfCount(parent->count, seed.shift);
  if (sum.count == 0) return sum;  // too few samples to share
  for (int k = 0; k < 3; ++k) {
    sum.fixed_sum[k] = fixed ? shared::ParentShareOfFixedSum(parent->fixed_sum[k], seed.shift) : 0;
    sum.float_sum[k] = fixed ? 0.0f : shared::ParentShareOfFloatSum(parent->float_sum[k], seed.shift);
  }
  return sum;
}

std::optional<std::uint32_t> FindSlotInTable(const HashTableDump& table, const shared::KeyWords& words,
                                             bool normal_in_index) {
  const std::uint32_t mask = table.capacity - 1u;
  const std::uint32_t slot0 = shared::IndexHash(words, normal_in_index ? 1u : 0u) & mask;
  const shared::StoredIdentity identity = shared::IdentityOfWords(
      words, table.key_identity == KeyIdentity::kFull ? shared::kIdentityFull : shared::kIdentityFingerprint,
      table.fingerprint_bits);
  if (!identity.fits) return std::nullopt;  // beyond a full key's range: no record has these words
  const SlotTag tag = shared::IdentityValue(identity.words);
  const shared::ProbeScheme scheme = ProbeSchemeOf(table);
  for (std::uint32_t probe = 0; probe < table.probe_limit; ++probe) {
    const std::uint32_t s = shared::CandidateSlot(scheme, slot0, probe);
    const std::uint32_t step = shared::LookupStep(table.tags[s], tag, table.counts[s]);
    if (step == shared::kLookupEnd) break;
    if (step == shared::kLookupFound) return s;
  }
  return std::nullopt;
}

CellState StateOfSlot(const HashTableDump& table, std::uint32_t slot) {
  CellState state;
  state.count = table.counts[slot];
  if (IntegerSums(table.accumulation)) {
    state.fixed_sum = table.fixed_sums[slot];
  } else {
    state.float_sum = table.float_sums[slot];
  }
  return state;
}

std::optional<CellState> FindInTable(const HashTableDump& table, const shared::KeyWords& words, bool normal_in_index) {
  const std::optional<std::uint32_t> s = FindSlotInTable(table, words, normal_in_index);
  if (!s) return std::nullopt;
  return StateOfSlot(table, *s);
}

}  // namespace hpsf
