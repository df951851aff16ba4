#include "emulated/broken_transport.h"

namespace hpsf {

std::string ToString(TransportDefect defect) {
  switch (defect) {
    case TransportDefect::kNone:
      return "none";
    case TransportDefect::kWeightTwice:
      return "weight-twice";
    case TransportDefect::kScatteredAtRecordLevel:
      return "scattered-at-record-level";
    case TransportDefect::kReadsCurrentTable:
      return "reads-current-table";
  }
  return "unknown";
}

RecordBatch WithWeightTwice(const RecordBatch& batch) {
  RecordBatch twice = batch;
  for (Record& s : twice.scattered) s.throughput *= s.throughput;
  return twice;
}

KeyResult KeyAtRecordLevel(const KeyParams& params, const Record& scattered, const Record& record) {
  if (!shared::RecordHasVertex(scattered)) return shared::EmptyKeyResult(shared::kKeyNoVertex);
  shared::KeyPosition at = shared::JitteredKeyPosition(params, scattered);
  const shared::KeyPosition own = shared::JitteredKeyPosition(params, record);
  at.level = own.level;
  at.inverse_size = own.inverse_size;
  return shared::KeyAtPosition(params, scattered, at);
}

}  // namespace hpsf
