// Reading an hpsf capture (docs/reference/capture-format.md; written by core/capture_writer.h): every chunk in its
// order, each checksum, and every length against the frame's header before anything is allocated. A capture is
// untrusted input: a file that is not one, truncated, corrupt or inconsistent is an InputError naming the file and
// the byte offset or chunk. What the values mean (a slot beyond the table, a tag that is the empty marker) is the
// judge's question, not the reader's.
#ifndef HPSF_CORE_CAPTURE_FILE_H
#define HPSF_CORE_CAPTURE_FILE_H

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/record.h"

namespace hpsf {

struct CapturedTable {
  std::vector<std::uint64_t> tags;                       // 64-bit full keys, or 32-bit identities widened
  std::vector<std::array<std::uint64_t, 3>> fixed_sums;  // fixed64, or packed-decimal's 32-bit words widened
  std::vector<std::array<float, 3>> float_sums;          // float32
  std::vector<std::uint64_t> counts;                     // packed-decimal: the count words' counts
  std::vector<std::uint32_t> last_seen;                  // with the last-seen flag
  std::vector<std::uint32_t> frame_counters;             // packed-decimal: the count words' frame counters
};

struct CapturedRecords {  // the RECD chunk: hpsf's records and the camera their keys need
  std::uint32_t width = 0, height = 0, samples_per_pixel = 0;
  double fov_y_radians = 0.0;
  std::vector<Record> records;
};

struct Capture {
  std::string path;
  std::uint32_t frame = 0;
  std::uint32_t capacity = 0;
  std::uint32_t key_words = 0;
  std::int32_t fixed_point_bits = 0;
  bool float32_sums = false;
  bool last_seen = false;
  bool full_keys = false;    // identities and tags were written as 64-bit words
  bool packed_sums = false;  // packed-decimal sums and count words
  std::string declaration;   // JSON text
  std::vector<std::array<float, 3>> contributions;
  std::vector<std::uint32_t> keys;  // key_words per record
  std::vector<std::uint32_t> home_slots, statuses, placements;
  std::vector<std::uint64_t> identities;  // 64-bit full keys, or 32-bit identities widened
  std::optional<CapturedRecords> hpsf_records;
  std::optional<CapturedTable> before;
  CapturedTable after;
  std::optional<std::vector<std::uint32_t>> occupied;  // the OCCL chunk: the list of occupied slots after the frame
  std::optional<std::vector<std::uint32_t>> occupied_before;  // OCCB: the list before it (with TBEF and OCCL)
  std::size_t record_count() const { return home_slots.size(); }
};

// The largest capture hpsf reads: a table of 2^31 slots, 2^28 records.
inline constexpr std::uint32_t kMaxCapturedRecords = 1u << 28;

Capture ReadCapture(const std::string& path);
// The same from bytes in memory; `source` names them in errors (the fuzz target reads this way).
Capture ReadCaptureBytes(const std::string& bytes, const std::string& source);

}  // namespace hpsf

#endif  // HPSF_CORE_CAPTURE_FILE_H
