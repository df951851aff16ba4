// The figures a team needs to size a table for its scene (`hpsf stats`): the load the batch's distinct keys put
// on the configured capacity, their probe lengths beside linear probing's theory (probe_theory), probe failures per
// probe limit under the table's scheme beside its theory, fingerprint aliases per width beside the prediction from the
// windows (alias_theory), records per cell, and the jitter tests' p-values (jitter_statistics). Each measured rate is
// held to its theory: it exceeds it when the theory lies below the rate's Clopper-Pearson interval, whose level is
// Sidak-corrected so that all the rates together hold at 0.001.
#ifndef HPSF_VERIFIER_THEORY_TABLE_STATISTICS_H
#define HPSF_VERIFIER_THEORY_TABLE_STATISTICS_H

#include <cstdint>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/filter_config.h"
#include "core/key_batch.h"
#include "core/record.h"
#include "verifier/theory/jitter_statistics.h"

namespace hpsf {

// A measured rate of `events` in `trials` beside its theory.
struct RateFigure {
  std::uint64_t events = 0, trials = 0;
  double theory = 0.0;
  double low = 0.0, high = 1.0;  // the measured rate's Clopper-Pearson interval (family level 0.001)
  bool judged = true;            // false where no theory is known: the rate is reported, never held to one
  double Rate() const { return trials == 0 ? 0.0 : double(events) / double(trials); }
  bool ExceedsTheory() const { return judged && theory < low; }
};

struct ProbeLimitFigure {
  std::uint32_t probe_limit = 0;
  // Keys inserted in the batch's order, under the table's probing scheme, that found their candidates full. The
  // theory is an upper bound: it counts failed keys as inserted, so the table it assumes is fuller. Linear probing's
  // is Knuth's (probe_theory), aligned buckets' the binomial overflow; bucket-window has none (not judged).
  RateFigure failures;
};

struct AliasFigure {
  std::uint32_t fingerprint_bits = 0;
  RateFigure aliases;  // keys that joined another key's slot; theory: the prediction from the windows
};

struct TableStatistics {
  std::uint64_t records = 0, keyed_records = 0, distinct_keys = 0;
  std::uint32_t capacity = 0, probe_limit = 0, fingerprint_bits = 0;
  // With full keys the table aliases nothing: the alias rates are what fingerprints of each width would give.
  KeyIdentity key_identity = KeyIdentity::kFingerprint;
  ProbeKind probing = ProbeKind::kLinear;
  double load = 0.0;  // distinct keys / capacity
  // Probes of a successful search per key, inserted without a limit (empty when the keys fill the table).
  std::vector<double> probe_histogram, probe_histogram_theory;  // [k]: share of keys found after k + 1 probes
  double mean_probes = 0.0, mean_probes_theory = 0.0;
  std::vector<ProbeLimitFigure> probe_limits;
  std::vector<AliasFigure> fingerprints;
  double extrapolated_alias_rate_32 = 0.0;      // aliases per key at 32 bits, from the widths measured
  std::vector<std::uint64_t> records_per_cell;  // [k]: keys with 2^k .. 2^(k+1) - 1 records
  std::uint64_t max_records_per_cell = 0;
  // With --levels L > 1: [k - 1][b], the cells k levels above the records' own (core/shared/levels.h) that
  // 2^b .. 2^(b+1) - 1 records reach at that level, k = 1 .. L - 1.
  std::vector<std::vector<std::uint64_t>> records_per_coarser_cell;
  // The fallbacks the resolve takes, from the reference's exact map: with --levels, [k] the records that read their
  // cell k levels up; with --neighbour-search, the records that searched and the neighbour cells they read.
  std::vector<std::uint64_t> resolved_at_level;
  std::uint64_t records_searched = 0, neighbours_read = 0;
  std::vector<JitterVerdict> jitter;
  double jitter_alpha = 0.0;  // each jitter test's level (Sidak, family 0.001)

  bool ExceedsTheory() const;  // any rate above its theory, or a jitter test rejected
  nlohmann::json ToJson() const;
};

// The records-per-cell histogram of each coarser level (TableStatistics::records_per_coarser_cell), its keys derived
// from the records' own by `params`.
std::vector<std::vector<std::uint64_t>> RecordsPerCoarserCell(std::span<const KeyResult> keys, const KeyParams& params,
                                                              std::uint32_t levels);

// The distinct full keys among the keyed results, in the order they first come, and how many results carry each.
std::vector<KeyResult> DistinctKeys(std::span<const KeyResult> keys,
                                    std::vector<std::uint64_t>* results_per_key = nullptr);

TableStatistics MeasureTableStatistics(std::span<const Record> records, std::span<const KeyResult> keys,
                                       const FilterConfig& config);

// The same for keys that are not hpsf's (a team's, from a capture, verifier/contract/capture_judgement.h): the key
// words, home slots and identities as given. Aliases are measured at the declared width only, with the identities
// given (no other width can be recomputed without the team's hash), and no jitter test runs (the jitter is hpsf's).
// Against uniform hashing's theory, as for hpsf's keys: a home slot or identity that is not uniform shows here.
TableStatistics MeasureGivenKeyStatistics(std::uint64_t records, std::span<const KeyResult> keys,
                                          const FilterConfig& config);

}  // namespace hpsf

#endif  // HPSF_VERIFIER_THEORY_TABLE_STATISTICS_H
