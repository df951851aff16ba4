// Captures through the writer a team's engine calls (core/capture_writer.h) and back through the reader: every
// array round-trips bit for bit, and every way a file can be broken (truncated at any byte, any byte flipped, chunks
// missing, out of order or inconsistent) is an InputError naming the file and the place, never a crash.

#include "core/capture_file.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/capture_writer.h"
#include "core/error.h"
#include "core/fnv1a.h"

namespace hpsf {
namespace {

// The arrays of a small capture: 5 records of 2-word keys, a table of 8 slots before and after, and optionally
// hpsf's records and last-seen frames. Each word is distinct, so a swapped or shifted array shows.
struct Arrays {
  std::vector<float> contributions = {0.5f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f,
                                      8.0f, 9.0f, 10.f, 11.f, 12.f, 13.f, 14.f};
  std::vector<std::uint32_t> keys = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  std::vector<std::uint32_t> home = {0, 1, 2, 3, 4};
  std::vector<std::uint32_t> identities = {11, 12, 13, 14, 15};
  std::vector<std::uint32_t> statuses = {0, 0, 1, 0, 2};
  std::vector<std::uint32_t> placements = {0, 1, capture::kNotPlaced, capture::kProbeFailure, capture::kNotPlaced};
  std::vector<std::byte> records = std::vector<std::byte>(5 * capture::kRecordBytes);
  std::vector<std::uint32_t> tags = {11, 12, 0, 0, 0, 0, 0, 7};
  std::vector<std::uint64_t> sums = std::vector<std::uint64_t>(24);
  std::vector<std::uint64_t> counts = {1, 1, 0, 0, 0, 0, 0, 3};
  std::vector<std::uint32_t> last_seen = {4, 4, 0, 0, 0, 0, 0, 2};
  std::vector<std::uint32_t> tags_before = std::vector<std::uint32_t>(8);
  std::vector<std::uint32_t> occupied = {7, 0, 1};
  // With full keys: 64-bit identities and tags whose high words are set.
  std::vector<std::uint64_t> full_identities = {0x1'0000'0011ull, 0x2'0000'0012ull, 13, 0xFFFF'FFFF'0000'0014ull, 15};
  std::vector<std::uint64_t> full_tags = {0x1'0000'0011ull, 0x2'0000'0012ull, 0, 0, 0, 0, 0, 7};
  std::vector<std::uint64_t> full_tags_before = std::vector<std::uint64_t>(8);
  std::span<const std::uint32_t> occupied_view = occupied;
  Arrays() {
    std::iota(sums.begin(), sums.end(), std::uint64_t(1) << 40);
    for (std::size_t i = 0; i < records.size(); ++i) records[i] = std::byte(i * 7);
  }
};

const char* const kDeclaration = R"({"hpsf_table": 1, "capacity": 8, "probing": "bucket:4"})";

capture::FrameCapture Written(const Arrays& a, const capture::RecordView* records, const capture::TableBuffers* before,
                              bool last_seen) {
  capture::FrameCapture c;
  c.declaration = kDeclaration;
  c.frame = 4;
  c.capacity = 8;
  c.fixed_point_bits = -3;
  c.key_words = 2;
  c.contributions = a.contributions;
  c.keys = a.keys;
  c.home_slots = a.home;
  c.identities = a.identities;
  c.statuses = a.statuses;
  c.placements = a.placements;
  c.hpsf_records = records;
  c.before = before;
  c.after = {a.tags,
             a.sums,
             {},
             a.counts,
             last_seen ? std::span<const std::uint32_t>(a.last_seen) : std::span<const std::uint32_t>(),
             {},
             {},
             {}};
  return c;
}

std::string TempPath(const std::string& name) { return ::testing::TempDir() + "/" + name; }

std::string Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The capture every test below breaks: all chunks present.
std::string FullCaptureBytes() {
  const Arrays a;
  const capture::RecordView records{32, 16, 2, 0.75, a.records};
  const capture::TableBuffers before{a.tags_before, a.sums, {}, a.counts, a.last_seen, {}, {}, {}};
  const std::string path = TempPath("full.hpsfc");
  capture::FrameCapture c = Written(a, &records, &before, true);
  c.occupied = &a.occupied_view;
  EXPECT_EQ(capture::WriteCapture(path, c), "");
  return Bytes(path);
}

void ExpectInputError(const std::string& bytes, const std::string& expected) {
  try {
    ReadCaptureBytes(bytes, "broken.hpsfc");
    ADD_FAILURE() << "read without error; expected: " << expected;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("broken.hpsfc: ", 0), 0u) << what;
    EXPECT_NE(what.find(expected), std::string::npos) << what;
  }
}

TEST(CaptureFile, EveryArrayRoundTripsBitForBit) {
  const Arrays a;
  const capture::RecordView records{32, 16, 2, 0.75, a.records};
  const capture::TableBuffers before{a.tags_before, a.sums, {}, a.counts, a.last_seen, {}, {}, {}};
  const std::string path = TempPath("round_trip.hpsfc");
  capture::FrameCapture written = Written(a, &records, &before, true);
  written.occupied = &a.occupied_view;
  ASSERT_EQ(capture::WriteCapture(path, written), "");
  const Capture c = ReadCapture(path);
  EXPECT_EQ(c.frame, 4u);
  EXPECT_EQ(c.capacity, 8u);
  EXPECT_EQ(c.fixed_point_bits, -3);
  EXPECT_FALSE(c.float32_sums);
  EXPECT_TRUE(c.last_seen);
  EXPECT_EQ(c.declaration, kDeclaration);
  ASSERT_EQ(c.record_count(), 5u);
  for (std::size_t i = 0; i < 5; ++i) {
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_EQ(c.contributions[i][std::size_t(ch)], a.contributions[3 * i + std::size_t(ch)]);
  }
  EXPECT_EQ(c.keys, a.keys);
  EXPECT_EQ(c.home_slots, a.home);
  EXPECT_EQ(c.identities, std::vector<std::uint64_t>(a.identities.begin(), a.identities.end()));
  EXPECT_FALSE(c.full_keys);
  EXPECT_EQ(c.statuses, a.statuses);
  EXPECT_EQ(c.placements, a.placements);
  ASSERT_TRUE(c.hpsf_records);
  EXPECT_EQ(c.hpsf_records->width, 32u);
  EXPECT_EQ(c.hpsf_records->height, 16u);
  EXPECT_EQ(c.hpsf_records->samples_per_pixel, 2u);
  EXPECT_EQ(c.hpsf_records->fov_y_radians, 0.75);
  ASSERT_EQ(c.hpsf_records->records.size(), 5u);
  EXPECT_EQ(std::memcmp(c.hpsf_records->records.data(), a.records.data(), a.records.size()), 0);
  ASSERT_TRUE(c.before);
  EXPECT_EQ(c.before->tags, std::vector<std::uint64_t>(a.tags_before.begin(), a.tags_before.end()));
  EXPECT_EQ(c.after.tags, std::vector<std::uint64_t>(a.tags.begin(), a.tags.end()));
  EXPECT_EQ(c.after.counts, a.counts);
  EXPECT_EQ(c.after.last_seen, a.last_seen);
  ASSERT_EQ(c.after.fixed_sums.size(), 8u);
  for (std::size_t s = 0; s < 8; ++s) {
    for (std::size_t ch = 0; ch < 3; ++ch) EXPECT_EQ(c.after.fixed_sums[s][ch], a.sums[3 * s + ch]);
  }
  EXPECT_EQ(c.occupied, a.occupied);
}

// The occupied list's chunk (OCCL) is optional, after the table; one longer than the table is named, and the writer
// refuses to write one.
TEST(CaptureFile, AnOccupiedListLongerThanTheTableIsNamed) {
  Arrays a;
  EXPECT_FALSE(ReadCaptureBytes(Bytes([&] {
                                  const std::string path = TempPath("no_list.hpsfc");
                                  EXPECT_EQ(capture::WriteCapture(path, Written(a, nullptr, nullptr, true)), "");
                                  return path;
                                }()),
                                "no_list.hpsfc")
                   .occupied);
  std::vector<std::uint32_t> long_list(9, 1);
  const std::span<const std::uint32_t> view = long_list;
  capture::FrameCapture c = Written(a, nullptr, nullptr, true);
  c.occupied = &view;
  EXPECT_EQ(capture::WriteCapture(TempPath("long_list.hpsfc"), c),
            TempPath("long_list.hpsfc") + ": occupied: more entries than the capacity");
  // Written with a list of 3, then its size word and payload made 9 entries long: the reader names the chunk.
  std::string bytes = FullCaptureBytes();
  const std::size_t list = bytes.size() - (8 + 12 + 16);
  ASSERT_EQ(bytes.substr(list, 4), "OCCL");
  std::string longer = bytes.substr(0, list + 8);
  const std::uint64_t size = 36;
  longer.append(reinterpret_cast<const char*>(&size), 8);
  std::string payload(36, '\1');
  longer += payload;
  const std::uint64_t checksum = Fnv1a(payload.data(), payload.size());
  longer.append(reinterpret_cast<const char*>(&checksum), 8);
  ExpectInputError(longer, "OCCL: 36 bytes, not a list of at most 8 slots");
}

// The list before the frame (OCCB) follows OCCL and round-trips; the writer refuses one without a table before the
// frame and a list after it, or longer than the table.
TEST(CaptureFile, TheListBeforeTheFrameRoundTripsBesideTheTableBefore) {
  const Arrays a;
  const capture::TableBuffers before{a.tags_before, a.sums, {}, a.counts, a.last_seen, {}, {}, {}};
  const std::vector<std::uint32_t> listed_before = {3, 5};
  const std::span<const std::uint32_t> before_view = listed_before;
  capture::FrameCapture c = Written(a, nullptr, &before, true);
  c.occupied = &a.occupied_view;
  c.occupied_before = &before_view;
  const std::string path = TempPath("list_before.hpsfc");
  ASSERT_EQ(capture::WriteCapture(path, c), "");
  const Capture read = ReadCapture(path);
  EXPECT_EQ(read.occupied, a.occupied);
  EXPECT_EQ(read.occupied_before, listed_before);
  capture::FrameCapture no_table = Written(a, nullptr, nullptr, true);
  no_table.occupied = &a.occupied_view;
  no_table.occupied_before = &before_view;
  EXPECT_EQ(capture::WriteCapture(TempPath("no_table.hpsfc"), no_table),
            TempPath("no_table.hpsfc") + ": occupied_before: without a table before the frame and a list after it");
  const std::vector<std::uint32_t> long_list(9, 1);
  const std::span<const std::uint32_t> long_view = long_list;
  c.occupied_before = &long_view;
  EXPECT_EQ(capture::WriteCapture(TempPath("long_before.hpsfc"), c),
            TempPath("long_before.hpsfc") + ": occupied_before: more entries than the capacity");
}

TEST(CaptureFile, Float32SumsWithoutTheOptionalChunksRoundTrip) {
  Arrays a;
  std::vector<float> float_sums(24);
  std::iota(float_sums.begin(), float_sums.end(), 0.25f);
  capture::FrameCapture c = Written(a, nullptr, nullptr, false);
  c.float32_sums = true;
  c.after.fixed_sums = {};
  c.after.float_sums = float_sums;
  const std::string path = TempPath("float32.hpsfc");
  ASSERT_EQ(capture::WriteCapture(path, c), "");
  const Capture read = ReadCapture(path);
  EXPECT_TRUE(read.float32_sums);
  EXPECT_FALSE(read.last_seen);
  EXPECT_FALSE(read.hpsf_records);
  EXPECT_FALSE(read.before);
  ASSERT_EQ(read.after.float_sums.size(), 8u);
  EXPECT_EQ(read.after.float_sums[7][2], float_sums[23]);
  EXPECT_TRUE(read.after.fixed_sums.empty());
}

// A table of full keys (flag bit 2): identities and tags as 64-bit words, their high words kept; the writer refuses
// the 32-bit arrays in their place, and a table of the other width.
TEST(CaptureFile, FullKeysRoundTripAs64BitWords) {
  const Arrays a;
  const capture::TableBuffers before{{}, a.sums, {}, a.counts, {}, a.full_tags_before, {}, {}};
  capture::FrameCapture c = Written(a, nullptr, &before, false);
  c.full_keys = true;
  c.identities = {};
  c.full_identities = a.full_identities;
  c.after.tags = {};
  c.after.full_tags = a.full_tags;
  const std::string path = TempPath("full_keys.hpsfc");
  ASSERT_EQ(capture::WriteCapture(path, c), "");
  const Capture read = ReadCapture(path);
  EXPECT_TRUE(read.full_keys);
  EXPECT_EQ(read.identities, a.full_identities);
  EXPECT_EQ(read.after.tags, a.full_tags);
  ASSERT_TRUE(read.before);
  EXPECT_EQ(read.before->tags, a.full_tags_before);
  EXPECT_EQ(read.after.counts, a.counts);
  capture::FrameCapture narrow = c;
  narrow.identities = a.identities;  // both widths
  EXPECT_NE(capture::WriteCapture(TempPath("both.hpsfc"), narrow).find("not one per record"), std::string::npos);
  capture::FrameCapture narrow_table = c;
  narrow_table.after.tags = a.tags;
  EXPECT_NE(capture::WriteCapture(TempPath("both.hpsfc"), narrow_table).find("after.full_tags: not one per slot"),
            std::string::npos);
  // The flag cleared (and FRAM's checksum made right): the 64-bit chunks are of the wrong length for 32-bit words,
  // named, not misread.
  std::string bytes = Bytes(path);
  const std::size_t frame = 16 + 16;  // the file's header, FRAM's chunk header
  bytes[frame + 20] = char(bytes[frame + 20] & ~capture::kFlagFullKeys);
  const std::uint64_t checksum = Fnv1a(bytes.data() + frame, 32);
  std::memcpy(bytes.data() + frame + 32, &checksum, 8);
  ExpectInputError(bytes, "IDEN: 40 bytes, not 20 for the frame's records");
}

// packed-decimal sums (flag bit 3): 32-bit sums and count words, read back as the dump holds them (the sums widened,
// each count word split into its 24-bit count and its frame counter); the writer refuses them beside 64-bit counts,
// and beside float32 sums.
TEST(CaptureFile, PackedSumsRoundTripAsCountsAndFrameCounters) {
  const Arrays a;
  std::vector<std::uint32_t> packed_sums(24), count_words = {0x01000001u, 0x02000005u, 0, 0, 0, 0, 0, 0xFF123456u};
  std::iota(packed_sums.begin(), packed_sums.end(), 0xFFFFFFF0u);  // wraps: each word distinct
  capture::FrameCapture c = Written(a, nullptr, nullptr, false);
  c.packed_sums = true;
  c.after.fixed_sums = {};
  c.after.counts = {};
  c.after.packed_sums = packed_sums;
  c.after.count_words = count_words;
  const std::string path = TempPath("packed.hpsfc");
  ASSERT_EQ(capture::WriteCapture(path, c), "");
  const Capture read = ReadCapture(path);
  EXPECT_TRUE(read.packed_sums);
  ASSERT_EQ(read.after.fixed_sums.size(), 8u);
  for (std::size_t s = 0; s < 8; ++s) {
    for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(read.after.fixed_sums[s][ch], packed_sums[3 * s + std::size_t(ch)]);
  }
  EXPECT_EQ(read.after.counts, (std::vector<std::uint64_t>{1, 5, 0, 0, 0, 0, 0, 0x123456}));
  EXPECT_EQ(read.after.frame_counters, (std::vector<std::uint32_t>{1, 2, 0, 0, 0, 0, 0, 255}));
  capture::FrameCapture with_counts = c;
  with_counts.after.counts = a.counts;
  EXPECT_NE(capture::WriteCapture(TempPath("both.hpsfc"), with_counts).find("after.count_words"), std::string::npos);
  capture::FrameCapture both = c;
  both.float32_sums = true;
  EXPECT_NE(capture::WriteCapture(TempPath("both.hpsfc"), both).find("one encoding of sums only"), std::string::npos);
}

TEST(CaptureFile, TheWriterRefusesArraysOfTheWrongLengthAndLeavesNoFile) {
  Arrays a;
  a.identities.pop_back();
  const std::string path = TempPath("refused.hpsfc");
  std::filesystem::remove(path);
  const std::string error = capture::WriteCapture(path, Written(a, nullptr, nullptr, false));
  EXPECT_NE(error.find("statuses and placements: not one per record"), std::string::npos) << error;
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
}

TEST(CaptureFile, EveryTruncationIsNamed) {
  const std::string bytes = FullCaptureBytes();
  ASSERT_GT(bytes.size(), 1000u);
  for (std::size_t size = 0; size < bytes.size(); ++size) {
    try {
      ReadCaptureBytes(bytes.substr(0, size), "broken.hpsfc");
      ADD_FAILURE() << "a capture cut to " << size << " bytes was read";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("broken.hpsfc: byte ", 0), 0u) << e.what();
    }
  }
}

TEST(CaptureFile, EveryFlippedByteIsNamed) {
  const std::string bytes = FullCaptureBytes();
  for (std::size_t at = 0; at < bytes.size(); ++at) {
    std::string broken = bytes;
    broken[at] = char(broken[at] ^ 0x10);
    try {
      ReadCaptureBytes(broken, "broken.hpsfc");
      ADD_FAILURE() << "a capture with byte " << at << " flipped was read";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("broken.hpsfc: byte ", 0), 0u) << e.what();
    }
  }
}

TEST(CaptureFile, BrokenStructureIsNamed) {
  const std::string bytes = FullCaptureBytes();
  ExpectInputError("", "not an hpsf capture");
  ExpectInputError("HPSFCAPX" + bytes.substr(8), "not an hpsf capture");
  std::string version = bytes;
  version[8] = 2;
  ExpectInputError(version, "capture version 2; this hpsf reads version 1");
  std::string fewer = bytes;
  fewer[12] = char(fewer[12] - 1);  // the header then leaves out the optional list: bytes follow the table
  ExpectInputError(fewer, "bytes after the last chunk");
  fewer[12] = char(fewer[12] - 1);  // and the table after the frame
  ExpectInputError(fewer, "the header's 10 chunks end before the TAFT chunk");
  std::string more = bytes;
  more[12] = char(more[12] + 1);
  ExpectInputError(more, "are known");
  ExpectInputError(bytes + "x", "bytes after the last chunk");
}

TEST(CaptureFile, InconsistentFramesAreNamedBeforeAnythingIsAllocated) {
  Arrays a;
  auto written = [&](capture::FrameCapture c, const char* name) {
    const std::string path = TempPath(name);
    EXPECT_EQ(capture::WriteCapture(path, c), "");
    return Bytes(path);
  };
  // The header's words rewritten with their checksum, as a broken writer would leave them.
  auto with_frame_word = [](std::string bytes, int word, std::uint32_t value) {
    const std::size_t payload = 16 + 16;  // the file header, then FRAM's chunk header
    std::memcpy(bytes.data() + payload + 4 * word, &value, 4);
    const std::uint64_t checksum = [&] {
      std::uint64_t h = 0xcbf29ce484222325ull;
      for (std::size_t i = 0; i < 32; ++i) h = (h ^ std::uint8_t(bytes[payload + i])) * 0x100000001b3ull;
      return h;
    }();
    std::memcpy(bytes.data() + payload + 32, &checksum, 8);
    return bytes;
  };
  const std::string bytes = written(Written(a, nullptr, nullptr, false), "plain.hpsfc");
  EXPECT_NO_THROW(ReadCaptureBytes(bytes, "broken.hpsfc"));
  ExpectInputError(with_frame_word(bytes, 1, 0x7FFFFFFFu), "more than 2^28");
  ExpectInputError(with_frame_word(bytes, 1, 6), "CONT: 60 bytes, not 72 for the frame's records");
  ExpectInputError(with_frame_word(bytes, 2, 12), "capacity 12 is not a power of two");
  ExpectInputError(with_frame_word(bytes, 2, 1u << 30), "TAFT: ");
  ExpectInputError(with_frame_word(bytes, 3, 7), "7 key words, not 1 to 6");
  ExpectInputError(with_frame_word(bytes, 5, 16), "unknown flags");
  ExpectInputError(with_frame_word(bytes, 5, capture::kFlagFloat32Sums | capture::kFlagPackedSums),
                   "float32 and packed-decimal sums both flagged");
  ExpectInputError(with_frame_word(bytes, 5, capture::kFlagFullKeys), "IDEN: 20 bytes, not 40 for the frame's records");
  ExpectInputError(with_frame_word(bytes, 5, capture::kFlagLastSeen), "TAFT: ");
}

TEST(CaptureFile, AMissingOrMisplacedChunkIsNamed) {
  const std::string bytes = FullCaptureBytes();
  // Dropping DECL: its chunk begins after the header (16) and FRAM (16 + 32 + 8).
  const std::size_t decl = 16 + 56;
  std::uint64_t decl_size;
  std::memcpy(&decl_size, bytes.data() + decl + 8, 8);
  std::string without = bytes.substr(0, decl) + bytes.substr(decl + 16 + decl_size + 8);
  without[12] = char(without[12] - 1);
  ExpectInputError(without, "a DECL chunk expected, found CONT");
}

TEST(CaptureFile, AFileThatCannotBeOpenedIsNamed) {
  try {
    ReadCapture(TempPath("no-such.hpsfc"));
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no-such.hpsfc: cannot open the capture"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hpsf
