#include "core/capture_file.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/capture_writer.h"
#include "core/count_words.h"
#include "core/error.h"
#include "core/fnv1a.h"

namespace hpsf {
namespace {

std::string TypeName(std::uint32_t type) {
  std::string name(4, ' ');
  for (int i = 0; i < 4; ++i) {
    const char c = char((type >> (8 * i)) & 0xFFu);
    name[std::size_t(i)] = c >= 0x20 && c < 0x7F ? c : '?';
  }
  return name;
}

constexpr std::size_t kCameraBytes = 24;  // RECD: width, height, spp, 0, then the field of view as a double

class CaptureParser {
 public:
  CaptureParser(const std::string& bytes, const std::string& source) : bytes_(bytes), source_(source) {}

  Capture Parse() {
    Capture c;
    c.path = source_;
    if (bytes_.size() < 16 || std::memcmp(bytes_.data(), capture::kMagic, 8) != 0) {
      throw Fail(0, "not an hpsf capture (no HPSFCAPT magic)");
    }
    const std::uint32_t version = Word(8), chunks = Word(12);
    if (version != capture::kVersion) {
      throw Fail(8, "capture version " + std::to_string(version) + "; this hpsf reads version 1");
    }
    offset_ = 16;
    std::uint32_t read = 0;
    auto next = [&](const char(&type)[5], bool optional) -> std::optional<std::string_view> {
      // An optional chunk may be the last one missing: the count of known chunks then names the header's excess.
      if (read == chunks || (optional && offset_ == bytes_.size()) || PeekType() != capture::ChunkType(type)) {
        if (optional) return std::nullopt;
        throw Fail(offset_, read == chunks
                                ? std::string("the header's ") + std::to_string(chunks) + " chunks end before the " +
                                      type + " chunk"
                                : std::string("a ") + type + " chunk expected, found " + TypeName(PeekType()));
      }
      ++read;
      return Chunk();
    };

    const std::string_view frame = *next("FRAM", false);
    if (frame.size() != 32) throw Fail(chunk_, "FRAM: 32 bytes, not " + std::to_string(frame.size()));
    std::uint32_t f[8];
    std::memcpy(f, frame.data(), sizeof f);
    c.frame = f[0];
    const std::uint32_t n = f[1];
    c.capacity = f[2];
    c.key_words = f[3];
    c.fixed_point_bits = std::bit_cast<std::int32_t>(f[4]);
    c.float32_sums = (f[5] & capture::kFlagFloat32Sums) != 0;
    c.last_seen = (f[5] & capture::kFlagLastSeen) != 0;
    c.full_keys = (f[5] & capture::kFlagFullKeys) != 0;
    c.packed_sums = (f[5] & capture::kFlagPackedSums) != 0;
    if (n > kMaxCapturedRecords) throw Fail(chunk_, "FRAM: " + std::to_string(n) + " records, more than 2^28");
    if (c.capacity == 0 || c.capacity > (1u << 31) || !std::has_single_bit(c.capacity)) {
      throw Fail(chunk_, "FRAM: capacity " + std::to_string(c.capacity) + " is not a power of two up to 2^31");
    }
    if (c.key_words < 1 || c.key_words > capture::kMaxKeyWords) {
      throw Fail(chunk_, "FRAM: " + std::to_string(c.key_words) + " key words, not 1 to 6");
    }
    if ((f[5] & ~(capture::kFlagFloat32Sums | capture::kFlagLastSeen | capture::kFlagFullKeys |
                  capture::kFlagPackedSums)) != 0 ||
        f[6] != 0 || f[7] != 0) {
      throw Fail(chunk_, "FRAM: unknown flags or reserved words set");
    }
    if (c.float32_sums && c.packed_sums) throw Fail(chunk_, "FRAM: float32 and packed-decimal sums both flagged");

    const std::string_view declaration = *next("DECL", false);
    c.declaration.assign(declaration);
    Values(*next("CONT", false), std::uint64_t(n) * 12, "CONT", c.contributions, n);
    Values(*next("KEYW", false), std::uint64_t(n) * 4 * c.key_words, "KEYW", c.keys, std::size_t(n) * c.key_words);
    Values(*next("HOME", false), std::uint64_t(n) * 4, "HOME", c.home_slots, n);
    Identities(*next("IDEN", false), c.full_keys, "IDEN", c.identities, n);
    Values(*next("STAT", false), std::uint64_t(n) * 4, "STAT", c.statuses, n);
    Values(*next("PLAC", false), std::uint64_t(n) * 4, "PLAC", c.placements, n);
    if (const auto records = next("RECD", true)) {
      if (records->size() != kCameraBytes + std::uint64_t(n) * capture::kRecordBytes) {
        throw Fail(chunk_, "RECD: " + std::to_string(records->size()) + " bytes, not 24 + 144 per record");
      }
      CapturedRecords& r = c.hpsf_records.emplace();
      std::uint32_t camera[4];
      std::memcpy(camera, records->data(), sizeof camera);
      r.width = camera[0];
      r.height = camera[1];
      r.samples_per_pixel = camera[2];
      if (camera[3] != 0) throw Fail(chunk_, "RECD: reserved word not 0");
      std::memcpy(&r.fov_y_radians, records->data() + 16, 8);
      r.records.resize(n);
      static_assert(sizeof(Record) == capture::kRecordBytes);
      if (n != 0) std::memcpy(r.records.data(), records->data() + kCameraBytes, std::size_t(n) * sizeof(Record));
    }
    if (const auto before = next("TBEF", true)) c.before = Table(*before, c, "TBEF");
    c.after = Table(*next("TAFT", false), c, "TAFT");
    if (const auto list = next("OCCL", true)) {
      if (list->size() % 4 != 0 || list->size() / 4 > c.capacity) {
        throw Fail(chunk_, "OCCL: " + std::to_string(list->size()) + " bytes, not a list of at most " +
                               std::to_string(c.capacity) + " slots");
      }
      Values(*list, list->size(), "OCCL", c.occupied.emplace(), list->size() / 4);
    }
    if (const auto list = next("OCCB", true)) {
      if (!c.before || !c.occupied) throw Fail(chunk_, "OCCB: a list before the frame without TBEF and OCCL");
      if (list->size() % 4 != 0 || list->size() / 4 > c.capacity) {
        throw Fail(chunk_, "OCCB: " + std::to_string(list->size()) + " bytes, not a list of at most " +
                               std::to_string(c.capacity) + " slots");
      }
      Values(*list, list->size(), "OCCB", c.occupied_before.emplace(), list->size() / 4);
    }
    if (read != chunks)
      throw Fail(offset_,
                 "the header announces " + std::to_string(chunks) + " chunks, " + std::to_string(read) + " are known");
    if (offset_ != bytes_.size()) throw Fail(offset_, "bytes after the last chunk");
    return c;
  }

 private:
  InputError Fail(std::uint64_t offset, const std::string& problem) const {
    return InputError(source_ + ": byte " + std::to_string(offset) + ": " + problem);
  }

  std::uint32_t Word(std::size_t at) const {
    std::uint32_t w;
    std::memcpy(&w, bytes_.data() + at, 4);
    return w;
  }

  std::uint32_t PeekType() const {
    if (bytes_.size() - offset_ < 4) throw Fail(offset_, "truncated: a chunk header expected");
    return Word(offset_);
  }

  // The next chunk's payload, its header and checksum checked.
  std::string_view Chunk() {
    chunk_ = offset_;
    if (bytes_.size() - offset_ < 16) throw Fail(offset_, "truncated chunk header");
    const std::string type = TypeName(Word(offset_));
    if (Word(offset_ + 4) != 0) throw Fail(offset_ + 4, type + ": reserved word not 0");
    std::uint64_t size;
    std::memcpy(&size, bytes_.data() + offset_ + 8, 8);
    offset_ += 16;
    if (size > bytes_.size() - offset_ || bytes_.size() - offset_ - size < 8) {
      throw Fail(chunk_, type + ": " + std::to_string(size) + " bytes announced, the file ends before them");
    }
    const std::string_view payload(bytes_.data() + offset_, std::size_t(size));
    offset_ += std::size_t(size);
    std::uint64_t checksum;
    std::memcpy(&checksum, bytes_.data() + offset_, 8);
    if (checksum != Fnv1a(payload.data(), payload.size())) throw Fail(offset_, type + ": checksum mismatch");
    offset_ += 8;
    return payload;
  }

  template <typename T>
  void Values(std::string_view payload, std::uint64_t expected, const char* type, std::vector<T>& out,
              std::size_t count) const {
    if (payload.size() != expected) {
      throw Fail(chunk_, std::string(type) + ": " + std::to_string(payload.size()) + " bytes, not " +
                             std::to_string(expected) + " for the frame's records");
    }
    out.resize(count);
    if (count != 0) std::memcpy(out.data(), payload.data(), payload.size());
  }

  // 64-bit words, or 32-bit words widened.
  void Identities(std::string_view payload, bool full_keys, const char* type, std::vector<std::uint64_t>& out,
                  std::size_t count) const {
    if (full_keys) return Values(payload, std::uint64_t(count) * 8, type, out, count);
    std::vector<std::uint32_t> words;
    Values(payload, std::uint64_t(count) * 4, type, words, count);
    out.assign(words.begin(), words.end());
  }

  CapturedTable Table(std::string_view payload, const Capture& c, const char* type) const {
    const std::uint64_t slots = c.capacity;
    const std::uint64_t sum_bytes = slots * 3 * (c.float32_sums || c.packed_sums ? 4 : 8);
    const std::uint64_t tag_bytes = slots * (c.full_keys ? 8 : 4);
    const std::uint64_t count_bytes = slots * (c.packed_sums ? 4 : 8);
    const std::uint64_t expected = tag_bytes + sum_bytes + count_bytes + (c.last_seen ? slots * 4 : 0);
    if (payload.size() != expected) {
      throw Fail(chunk_, std::string(type) + ": " + std::to_string(payload.size()) + " bytes, not " +
                             std::to_string(expected) + " for " + std::to_string(slots) + " slots");
    }
    CapturedTable t;
    std::size_t at = 0;
    auto take = [&](auto& out, std::uint64_t bytes) {
      out.resize(std::size_t(slots));
      std::memcpy(out.data(), payload.data() + at, std::size_t(bytes));
      at += std::size_t(bytes);
    };
    Identities(payload.substr(0, std::size_t(tag_bytes)), c.full_keys, type, t.tags, std::size_t(slots));
    at += std::size_t(tag_bytes);
    if (c.packed_sums) {  // 32-bit words widened; each count word split into its count and frame counter
      std::vector<std::array<std::uint32_t, 3>> sums;
      std::vector<std::uint32_t> words;
      take(sums, sum_bytes);
      take(words, count_bytes);
      t.fixed_sums.resize(sums.size());
      for (std::size_t s = 0; s < sums.size(); ++s) t.fixed_sums[s] = {sums[s][0], sums[s][1], sums[s][2]};
      t.counts.resize(words.size());
      t.frame_counters.resize(words.size());
      SplitCountWords(words, t.counts, t.frame_counters);
    } else {
      if (c.float32_sums) {
        take(t.float_sums, sum_bytes);
      } else {
        take(t.fixed_sums, sum_bytes);
      }
      take(t.counts, count_bytes);
    }
    if (c.last_seen) take(t.last_seen, slots * 4);
    return t;
  }

  const std::string& bytes_;
  std::string source_;
  std::size_t offset_ = 0, chunk_ = 0;
};

}  // namespace

Capture ReadCaptureBytes(const std::string& bytes, const std::string& source) {
  return CaptureParser(bytes, source).Parse();
}

Capture ReadCapture(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the capture");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw InputError(path + ": reading the capture failed");
  return ReadCaptureBytes(bytes.str(), path);
}

}  // namespace hpsf
