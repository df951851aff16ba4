#include "verifier/contract/transport_check.h"

#include "core/footprint.h"
#include "core/input_check.h"
#include "core/level_seed.h"
#include "core/transport.h"

namespace hpsf {
namespace {

KeyParams ParamsOf(const RecordBatch& batch, const FilterConfig& config) {
  return MakeKeyParams(config, FootprintScale(config.filter_width_px, batch.fov_y_radians, batch.height),
                       std::uint32_t(batch.records.size()));
}

std::string ReadName(std::uint32_t read) {
  return read == kNothingTransported ? "nothing" : "slot " + std::to_string(read);
}

}  // namespace

RecordBatch JudgeTransportReads(const RecordBatch& batch, const FilterConfig& config, const HashTableDump* before,
                                const HashedRun& run, const std::string& prefix, LevelVerdict& tables) {
  if (!config.transport || !before) {
    // Without --transport nothing is looked up; without a table before the frame (forced on the first) nothing found.
    if (!config.transport && !run.transport_read.empty()) {
      tables.Fail(prefix + "transported light where no transport runs");
    }
    for (std::size_t i = 0; i < run.transport_read.size(); ++i) {
      if (run.transport_read[i] == kNothingTransported) continue;
      tables.Fail(prefix + "record " + std::to_string(i) + "'s transport read " + ReadName(run.transport_read[i]) +
                  ", with no table before the frame");
      break;
    }
    RecordBatch added = batch;
    added.scattered.clear();
    return added;
  }
  const TransportLookup lookup = [&](const shared::KeyWords& w) -> std::optional<FoundCell> {
    const std::optional<std::uint32_t> slot = FindSlotInTable(*before, w, config.normal_in_index);
    if (!slot) return std::nullopt;
    return FoundCell{*slot, StateOfSlot(*before, *slot)};
  };
  TransportResult expected =
      TransportBatch(batch, ParamsOf(batch, config), config.accumulation, before->fixed_point_bits, lookup);
  if (run.transport_read.size() != expected.read.size()) {
    tables.Fail(prefix + "the transport read " + std::to_string(run.transport_read.size()) + " vertices' cells, " +
                std::to_string(expected.read.size()) + " records were to be transported");
  } else {
    for (std::size_t i = 0; i < expected.read.size(); ++i) {
      if (run.transport_read[i] == expected.read[i]) continue;
      tables.Fail(prefix + "record " + std::to_string(i) + "'s transport read " + ReadName(run.transport_read[i]) +
                  ", the table before the frame holds its scattered vertex's cell at " + ReadName(expected.read[i]));
    }
  }
  return std::move(expected.batch);
}

TransportComparison CompareTransports(const RecordBatch& batch, const FilterConfig& config,
                                      const FilterResult& reference, const HashedRun& run,
                                      const ClassifiedSlots& classes, const std::string& prefix, LevelVerdict& ideal) {
  TransportComparison result;
  const std::size_t n = batch.records.size() + batch.deeper.size();
  result.fed.assign(n, false);
  // A read of any other shape, or a slot outside the table, is level 2's failure.
  if (batch.scattered.size() != n || run.transport_read.size() != n || reference.transport_read.size() != n) {
    return result;
  }
  const KeyParams params = ParamsOf(batch, config);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t slot = run.transport_read[i];
    const std::uint32_t cell = reference.transport_read[i];
    if (slot != kNothingTransported && slot >= run.table.capacity) continue;
    if (slot == kNothingTransported && cell == kNothingTransported) {
      ++result.compared;
      continue;
    }
    const shared::KeyWords w = shared::ComputeKey(params, batch.scattered[i]).words;
    const ClassifiedSlots::FullKey wanted{w.cell_x, w.cell_y, w.cell_z, w.level, w.normal, w.extra};
    const std::string record = prefix + "record " + std::to_string(i) + "'s transport";
    bool classified = false;
    if (slot != kNothingTransported) {
      classified = classes.Classified(slot) || classes.KeyOf(slot) != wanted;
    } else {
      classified = classes.Lost(wanted);
    }
    if (classified) {
      ++result.classified;
      result.fed[i] = true;
    } else if (slot == kNothingTransported) {
      ideal.Fail(record + " found no slot for a cell the reference read");
    } else if (cell == kNothingTransported) {
      ideal.Fail(record + " read " + ReadName(slot) + ", a cell the reference does not hold");
    } else {
      ++result.compared;
    }
  }
  return result;
}

}  // namespace hpsf
