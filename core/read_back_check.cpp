#include "core/read_back_check.h"

#include "core/shared/key.h"

namespace hpsf {
namespace {

std::string Joined(const std::string& shader, const std::vector<std::string>& faults) {
  std::string text = shader + " wrote invalid output";
  for (std::size_t f = 0; f < faults.size(); ++f) text += (f == 0 ? ": " : "; ") + faults[f];
  return text;
}

std::string RecordPrefix(std::size_t i) { return "record " + std::to_string(i) + ": "; }

}  // namespace

ShaderOutputError::ShaderOutputError(const std::string& shader, std::vector<std::string> faults,
                                     std::vector<KeyResult> keys)
    : std::runtime_error(Joined(shader, faults)), faults_(std::move(faults)), keys_(std::move(keys)) {}

std::vector<std::string> ReadBackFaults(const HashedRun& run, std::uint32_t frame, std::size_t limit) {
  std::vector<std::string> faults;
  auto fault = [&](std::string text) {
    if (faults.size() < limit) faults.push_back(std::move(text));
  };
  const HashTableDump& t = run.table;
  const shared::ProbeScheme scheme = ProbeSchemeOf(t);
  std::uint64_t placed = 0;
  for (std::size_t i = 0; i < run.placements.size() && faults.size() < limit; ++i) {
    const KeyResult& key = run.keys[i];
    if (key.status != shared::kKeyed && key.status != shared::kKeyNoVertex && key.status != shared::kKeyUnkeyable) {
      fault(RecordPrefix(i) + "key status " + std::to_string(key.status) +
            " is none of keyed (0), no vertex (1) and unkeyable (2)");
      continue;
    }
    if (key.status == shared::kKeyed && key.slot0 >= t.capacity) {
      fault(RecordPrefix(i) + "slot0 " + std::to_string(key.slot0) + " is not below the capacity " +
            std::to_string(t.capacity));
      continue;
    }
    const std::uint32_t slot = run.placements[i];
    if (slot == kProbeFailure || slot == kNotPlaced) continue;
    if (slot >= t.capacity) {
      fault(RecordPrefix(i) + "placement " + std::to_string(slot) + " is neither a slot below the capacity " +
            std::to_string(t.capacity) + " nor probe failure (" + std::to_string(kProbeFailure) + ") nor not placed (" +
            std::to_string(kNotPlaced) + ")");
      continue;
    }
    ++placed;
    if (key.slot0 >= t.capacity || shared::ProbeIndex(scheme, key.slot0, slot) == shared::kNoCandidate) {
      fault(RecordPrefix(i) + "placed in slot " + std::to_string(slot) + ", which is not one of its candidates (" +
            ToString(t.probing) + ":" + std::to_string(t.probe_limit) + " from slot0 " + std::to_string(key.slot0) +
            ", capacity " + std::to_string(t.capacity) + ")");
    }
  }
  // The coarser levels' placements (core/shared/levels.h): slots or the two markers. Whether a slot is among its
  // derived key's candidates is the table checker's to judge (its key is not the shader's word).
  const std::size_t n = run.placements.size();
  if (t.levels > 1 && run.coarser_placements.size() != std::size_t(t.levels - 1) * n) {
    fault("coarser placements: " + std::to_string(run.coarser_placements.size()) + " words for " +
          std::to_string(t.levels - 1) + " levels of " + std::to_string(n) + " records");
  }
  for (std::size_t at = 0; n > 0 && at < run.coarser_placements.size() && faults.size() < limit; ++at) {
    const std::uint32_t slot = run.coarser_placements[at];
    if (slot == kProbeFailure || slot == kNotPlaced) continue;
    if (slot >= t.capacity) {
      fault(RecordPrefix(at % n) + "placement " + std::to_string(at / n + 1) + " levels up " + std::to_string(slot) +
            " is neither a slot below the capacity " + std::to_string(t.capacity) + " nor a marker");
      continue;
    }
    ++placed;
  }
  if (!t.last_seen.empty()) {
    for (std::size_t s = 0; s < t.last_seen.size() && faults.size() < limit; ++s) {
      if (t.last_seen[s] > frame) {
        fault("slot " + std::to_string(s) + ": last seen in frame " + std::to_string(t.last_seen[s]) +
              ", after this frame " + std::to_string(frame));
      }
    }
  }
  const auto counter = [&](const char* name, std::uint64_t value, std::uint64_t most, const std::string& why) {
    if (value > most) {
      fault(std::string("stats: ") + name + " " + std::to_string(value) + " is more than the run can produce (" +
            std::to_string(most) + ", " + why + ")");
    }
  };
  if (faults.empty()) {  // the bounds below count placed records, which only make sense once placements are valid
    counter("fixed64 wraps", run.wraps, 3 * placed, "one per channel of each placed record and level");
    counter("count wraps", run.count_wraps, placed, "one per placed record and level");
    counter("evicted", run.evicted, t.capacity, "one per slot");
    counter("seeded", run.seeded, t.capacity, "one per slot");
  }
  return faults;
}

void FinishReadBack(HashedRun& run, std::uint32_t frame, const std::string& shader) {
  std::vector<std::string> faults = ReadBackFaults(run, frame);
  if (!faults.empty()) throw ShaderOutputError(shader, std::move(faults), std::move(run.keys));
  CountProbes(run);
  run.tombstones = 0;
  if (!run.table.last_seen.empty()) {
    for (std::size_t s = 0; s < run.table.capacity; ++s)
      run.tombstones += run.table.tags[s] != kEmptyTag && run.table.counts[s] == 0;
  }
}

}  // namespace hpsf
