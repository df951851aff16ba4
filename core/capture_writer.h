// The writer of hpsf captures (docs/reference/capture-format.md): one frame of a team's hash table as its own engine
// holds it (per record its contribution, key words, home slot, stored identity and placement; the table's buffers
// before and after the frame; the table's declaration), for `hpsf judge CAPTURE` to judge offline with the table
// checker and the contract. Header-only and standard C++20 alone, so that an engine can include it without linking
// anything of hpsf's: copy the buffers back from the device, fill a FrameCapture, call WriteCapture.
#ifndef HPSF_CORE_CAPTURE_WRITER_H
#define HPSF_CORE_CAPTURE_WRITER_H

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <span>
#include <string>
#include <string_view>

namespace hpsf::capture {

static_assert(std::endian::native == std::endian::little, "captures are little-endian, as every GPU host is");

inline constexpr char kMagic[8] = {'H', 'P', 'S', 'F', 'C', 'A', 'P', 'T'};
inline constexpr std::uint32_t kVersion = 1;
inline constexpr std::uint32_t kMaxKeyWords = 6;
inline constexpr std::uint32_t kRecordBytes = 144;  // core/shared/record_layout.h

// A record's status word, as core/shared/key.h names them.
inline constexpr std::uint32_t kKeyed = 0;      // the record has a cell
inline constexpr std::uint32_t kNoVertex = 1;   // the record adds to no cell (a sky hit, a path that ended)
inline constexpr std::uint32_t kUnkeyable = 2;  // the record's cell could not be keyed (out of range)

// A record's placement: a slot, or one of these.
inline constexpr std::uint32_t kNotPlaced = 0xFFFFFFFFu;     // no key: never probed
inline constexpr std::uint32_t kProbeFailure = 0xFFFFFFFEu;  // probed every candidate without finding a slot

// FRAM flags.
inline constexpr std::uint32_t kFlagFloat32Sums = 1u << 0;  // sums are float32 (else fixed64 at 2^F)
inline constexpr std::uint32_t kFlagLastSeen = 1u << 1;     // each table carries a last-seen frame per slot
inline constexpr std::uint32_t kFlagFullKeys = 1u << 2;     // identities and tags are 64-bit words (full keys)
// Sums are packed-decimal (SHaRC's): 32-bit words at 1000, and 32-bit count words (the count in bits 0-23, the frames
// the cell has lived in bits 24-31) instead of 64-bit counts.
inline constexpr std::uint32_t kFlagPackedSums = 1u << 3;

// A chunk's type: four ASCII characters, the first in the lowest byte.
constexpr std::uint32_t ChunkType(const char (&name)[5]) {
  return std::uint32_t(std::uint8_t(name[0])) | std::uint32_t(std::uint8_t(name[1])) << 8 |
         std::uint32_t(std::uint8_t(name[2])) << 16 | std::uint32_t(std::uint8_t(name[3])) << 24;
}

// One state of the table, in the buffer interface's layout (docs/reference/buffer-interface.md).
struct TableBuffers {
  std::span<const std::uint32_t> tags;        // capacity: 0 empty, else the stored identity; empty with full keys
  std::span<const std::uint64_t> fixed_sums;  // 3 x capacity, fixed64 at 2^F; empty with float32 sums
  std::span<const float> float_sums;          // 3 x capacity, float32; empty with fixed64 sums
  std::span<const std::uint64_t> counts;      // capacity
  std::span<const std::uint32_t> last_seen;   // capacity with eviction (the frame a record last reached it), else empty
  std::span<const std::uint64_t> full_tags;   // capacity, with full keys (64-bit tags), instead of tags
  // With packed-decimal sums, instead of the sums and counts above:
  std::span<const std::uint32_t> packed_sums;  // 3 x capacity, 32-bit words at 1000
  std::span<const std::uint32_t> count_words;  // capacity: count | frames << 24
};

// What a team's camera made of the frame, for a record file's key inputs (hpsf's own key only).
struct RecordView {
  std::uint32_t width = 0, height = 0, samples_per_pixel = 0;
  double fov_y_radians = 0.0;          // the camera's vertical field of view, for hpsf's footprint scale
  std::span<const std::byte> records;  // kRecordBytes each, core/shared/record_layout.h
};

struct FrameCapture {
  std::string_view declaration;  // the table declaration's JSON text (docs/reference/table-declaration.md)
  std::uint32_t frame = 0;
  std::uint32_t capacity = 0;
  std::int32_t fixed_point_bits = 0;  // F of fixed64 sums; ignored with float32 and packed-decimal sums
  bool float32_sums = false;
  bool packed_sums = false;  // packed-decimal: the tables' packed_sums and count_words
  // A table that stores full keys (key.identity "full"): 64-bit identities and tags, in full_identities and
  // full_tags instead of identities and tags.
  bool full_keys = false;
  std::uint32_t key_words = 0;  // 1 to kMaxKeyWords words per key
  // Per record (n records):
  std::span<const float> contributions;       // 3 x n: what the record adds to its cell's sums
  std::span<const std::uint32_t> keys;        // key_words x n: the cell's key, opaque; records of one cell share it
  std::span<const std::uint32_t> home_slots;  // n: the slot its candidates start from
  std::span<const std::uint32_t> identities;  // n: what a slot holding its cell stores as its tag; or, with full keys,
  std::span<const std::uint64_t> full_identities;  // n of these
  std::span<const std::uint32_t> statuses;         // n: kKeyed, kNoVertex or kUnkeyable
  std::span<const std::uint32_t> placements;       // n: a slot, kNotPlaced or kProbeFailure
  const RecordView* hpsf_records = nullptr;        // optional: the records, when the key is hpsf's (judged at level 1)
  const TableBuffers* before = nullptr;            // optional: the table before the frame; none means it started empty
  TableBuffers after;                              // the table after the frame and its passes
  // With compaction (passes.compaction "occupied-list"): the list of occupied slots after the frame, in the engine's
  // order, at most capacity entries; the judge holds it to the table's occupied slots.
  const std::span<const std::uint32_t>* occupied = nullptr;
  // Optional, with `before` and `occupied`: the list the frame's passes started from, held to the table before.
  const std::span<const std::uint32_t>* occupied_before = nullptr;
};

namespace detail {

inline std::uint64_t Fnv1a(const void* data, std::size_t size, std::uint64_t hash) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull;
  return hash;
}

class ChunkStream {
 public:
  explicit ChunkStream(std::ofstream& out) : out_(out) {}
  void Begin(std::uint32_t type, std::uint64_t bytes) {
    const std::uint32_t reserved = 0;
    Raw(&type, 4);
    Raw(&reserved, 4);
    Raw(&bytes, 8);
    hash_ = 0xcbf29ce484222325ull;
  }
  template <typename T>
  void Add(std::span<const T> values) {
    Add(values.data(), values.size_bytes());
  }
  void Add(const void* data, std::size_t bytes) {
    hash_ = Fnv1a(data, bytes, hash_);
    Raw(data, bytes);
  }
  void End() { Raw(&hash_, 8); }

 private:
  void Raw(const void* data, std::size_t bytes) { out_.write(static_cast<const char*>(data), std::streamsize(bytes)); }
  std::ofstream& out_;
  std::uint64_t hash_ = 0;
};

inline std::string CheckTable(const TableBuffers& t, const FrameCapture& c, const char* which) {
  const std::size_t n = c.capacity;
  const std::string name(which);
  if (c.full_keys ? t.full_tags.size() != n || !t.tags.empty() : t.tags.size() != n || !t.full_tags.empty()) {
    return name + (c.full_keys ? ".full_tags" : ".tags") + ": not one per slot, or tags of the other width too";
  }
  if (c.packed_sums) {
    if (t.packed_sums.size() != 3 * n || !t.fixed_sums.empty() || !t.float_sums.empty()) {
      return name + ".packed_sums: not 3 x capacity, or sums of another encoding too";
    }
    if (t.count_words.size() != n || !t.counts.empty()) return name + ".count_words: not one per slot, or counts too";
  } else {
    if (!t.packed_sums.empty() || !t.count_words.empty()) return name + ": packed sums without packed_sums set";
    if (t.counts.size() != n) return name + ".counts: " + std::to_string(t.counts.size()) + " words, not the capacity";
    if (c.float32_sums ? t.float_sums.size() != 3 * n || !t.fixed_sums.empty()
                       : t.fixed_sums.size() != 3 * n || !t.float_sums.empty()) {
      return name + ": sums of the other encoding, or not 3 x capacity of them";
    }
  }
  if (!t.last_seen.empty() && t.last_seen.size() != n) return name + ".last_seen: not one per slot";
  return "";
}

inline std::uint64_t TableBytes(const FrameCapture& c, bool last_seen) {
  const bool narrow_sums = c.float32_sums || c.packed_sums;
  return std::uint64_t(c.capacity) *
         ((c.full_keys ? 8 : 4) + 3 * (narrow_sums ? 4 : 8) + (c.packed_sums ? 4 : 8) + (last_seen ? 4 : 0));
}

inline void WriteTable(ChunkStream& s, std::uint32_t type, const TableBuffers& t, const FrameCapture& c,
                       bool last_seen) {
  s.Begin(type, TableBytes(c, last_seen));
  if (c.full_keys) {
    s.Add(t.full_tags);
  } else {
    s.Add(t.tags);
  }
  if (c.packed_sums) {
    s.Add(t.packed_sums);
    s.Add(t.count_words);
  } else {
    if (c.float32_sums) {
      s.Add(t.float_sums);
    } else {
      s.Add(t.fixed_sums);
    }
    s.Add(t.counts);
  }
  if (last_seen) s.Add(t.last_seen);
  s.End();
}

}  // namespace detail

// Why `c` cannot be written (arrays of the wrong length, a key of no words), or "" when it can.
inline std::string CaptureProblem(const FrameCapture& c) {
  const std::size_t n = c.home_slots.size();
  if (c.key_words < 1 || c.key_words > kMaxKeyWords) return "key_words must be 1 to 6";
  if (c.capacity == 0) return "capacity is 0";
  if (c.float32_sums && c.packed_sums) return "float32_sums and packed_sums: one encoding of sums only";
  if (n > 0xFFFFFFFFu) return "more than 2^32 - 1 records";
  if (c.contributions.size() != 3 * n) return "contributions: not 3 per record";
  if (c.keys.size() != std::size_t(c.key_words) * n) return "keys: not key_words per record";
  if ((c.full_keys ? c.full_identities.size() != n || !c.identities.empty()
                   : c.identities.size() != n || !c.full_identities.empty()) ||
      c.statuses.size() != n || c.placements.size() != n) {
    return "identities (full_identities with full keys), statuses and placements: not one per record";
  }
  if (c.hpsf_records && c.hpsf_records->records.size() != std::size_t(kRecordBytes) * n) {
    return "hpsf_records: not 144 bytes per record";
  }
  if (std::string e = detail::CheckTable(c.after, c, "after"); !e.empty()) return e;
  if (c.before) {
    if (std::string e = detail::CheckTable(*c.before, c, "before"); !e.empty()) return e;
    if (c.before->last_seen.empty() != c.after.last_seen.empty()) return "before and after: last_seen in one only";
  }
  if (c.occupied && c.occupied->size() > c.capacity) return "occupied: more entries than the capacity";
  if (c.occupied_before) {
    if (!c.before || !c.occupied) return "occupied_before: without a table before the frame and a list after it";
    if (c.occupied_before->size() > c.capacity) return "occupied_before: more entries than the capacity";
  }
  return "";
}

// Writes `c` to `path`, through a temporary name beside it that is renamed at the end, so that a failure leaves no
// file. Returns "" on success, else what went wrong.
inline std::string WriteCapture(const std::string& path, const FrameCapture& c) {
  if (std::string problem = CaptureProblem(c); !problem.empty()) return path + ": " + problem;
  const std::string temporary = path + ".partial";
  const bool last_seen = !c.after.last_seen.empty();
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) return path + ": cannot write " + temporary;
    const std::uint32_t chunks =
        9 + (c.hpsf_records ? 1 : 0) + (c.before ? 1 : 0) + (c.occupied ? 1 : 0) + (c.occupied_before ? 1 : 0);
    out.write(kMagic, sizeof kMagic);
    out.write(reinterpret_cast<const char*>(&kVersion), 4);
    out.write(reinterpret_cast<const char*>(&chunks), 4);
    detail::ChunkStream s(out);
    const std::uint32_t n = std::uint32_t(c.home_slots.size());
    const std::uint32_t flags = (c.float32_sums ? kFlagFloat32Sums : 0u) | (last_seen ? kFlagLastSeen : 0u) |
                                (c.full_keys ? kFlagFullKeys : 0u) | (c.packed_sums ? kFlagPackedSums : 0u);
    const std::uint32_t frame[8] = {
        c.frame, n, c.capacity, c.key_words, std::bit_cast<std::uint32_t>(c.fixed_point_bits), flags, 0, 0};
    s.Begin(ChunkType("FRAM"), sizeof frame);
    s.Add(frame, sizeof frame);
    s.End();
    s.Begin(ChunkType("DECL"), c.declaration.size());
    s.Add(c.declaration.data(), c.declaration.size());
    s.End();
    auto words = [&](const char(&type)[5], auto values) {
      s.Begin(ChunkType(type), values.size_bytes());
      s.Add(values);
      s.End();
    };
    words("CONT", c.contributions);
    words("KEYW", c.keys);
    words("HOME", c.home_slots);
    if (c.full_keys) {
      words("IDEN", c.full_identities);
    } else {
      words("IDEN", c.identities);
    }
    words("STAT", c.statuses);
    words("PLAC", c.placements);
    if (c.hpsf_records) {
      const RecordView& r = *c.hpsf_records;
      const std::uint32_t camera[4] = {r.width, r.height, r.samples_per_pixel, 0};
      s.Begin(ChunkType("RECD"), sizeof camera + sizeof r.fov_y_radians + r.records.size());
      s.Add(camera, sizeof camera);
      s.Add(&r.fov_y_radians, sizeof r.fov_y_radians);
      s.Add(r.records.data(), r.records.size());
      s.End();
    }
    if (c.before) detail::WriteTable(s, ChunkType("TBEF"), *c.before, c, last_seen);
    detail::WriteTable(s, ChunkType("TAFT"), c.after, c, last_seen);
    if (c.occupied) words("OCCL", *c.occupied);
    if (c.occupied_before) words("OCCB", *c.occupied_before);
    out.close();
    if (!out) {
      std::remove(temporary.c_str());
      return path + ": writing failed";
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    return path + ": cannot rename " + temporary + " to it";
  }
  return "";
}

}  // namespace hpsf::capture

#endif  // HPSF_CORE_CAPTURE_WRITER_H
