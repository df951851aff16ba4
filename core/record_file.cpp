#include "core/record_file.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "core/fnv1a.h"
#include "core/transport.h"

namespace hpsf {
namespace {

static_assert(std::endian::native == std::endian::little, ".hpsfv is little-endian and written as memory");

constexpr char kMagic[8] = {'H', 'P', 'S', 'F', 'V', 'R', 'E', 'C'};

// Version 1's header is the first 48 bytes of version 2's, and version 2's the first 56 of version 3's.
struct Header {
  char magic[8];
  std::uint32_t version;
  std::uint32_t header_size;
  std::uint32_t record_size;
  std::uint32_t width;
  std::uint32_t height;
  std::uint32_t samples_per_pixel;
  double fov_y_radians;
  std::uint64_t record_count;
  std::uint32_t frame;            // version 2
  std::uint32_t frame_count;      // version 2: the same in every block
  std::uint64_t deeper_count;     // version 3
  std::uint64_t scattered_count;  // version 3: none, or one per record and deeper record
  std::uint64_t own_light_count;  // version 4: none, or one per record
};
static_assert(sizeof(Header) == 80);
constexpr std::uint32_t kVersion1HeaderSize = 48;
constexpr std::uint32_t kVersion2HeaderSize = 56;
constexpr std::uint32_t kVersion3HeaderSize = 72;

std::uint32_t HeaderSize(std::uint32_t version) {
  return version == 1   ? kVersion1HeaderSize
         : version == 2 ? kVersion2HeaderSize
         : version == 3 ? kVersion3HeaderSize
                        : std::uint32_t(sizeof(Header));
}

// The bytes of a block's own lights (version 4): one vec4 per record.
std::size_t OwnLightBytes(std::uint64_t count) { return std::size_t(count) * sizeof(glm::vec4); }

}  // namespace

RecordFileWriter::RecordFileWriter(const std::string& path, std::uint32_t frames)
    : path_(path), temporary_(path + ".partial"), frames_(frames) {
  if (frames == 0 || frames > kMaxRecordFileFrames) {
    throw InputError(path + ": a record file holds 1 to 2^20 frames, not " + std::to_string(frames));
  }
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) throw InputError(path + ": cannot write the record file");
}

RecordFileWriter::~RecordFileWriter() {
  if (finished_) return;
  out_.close();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void RecordFileWriter::Append(const RecordBatch& batch) {
  if (written_ == frames_) throw InputError(path_ + ": more frames than the " + std::to_string(frames_) + " announced");
  if (written_ > 0 && batch.frame <= last_frame_) {
    throw InputError(path_ + ": frame " + std::to_string(batch.frame) + " after frame " + std::to_string(last_frame_) +
                     "; frame numbers must increase");
  }
  CheckScatteredShape(batch);
  if (!batch.own_light.empty() && batch.own_light.size() != batch.records.size()) {
    throw InputError(path_ + ": " + std::to_string(batch.own_light.size()) + " own lights for " +
                     std::to_string(batch.records.size()) + " records (none, or one per record)");
  }
  // Each version only where the one before cannot hold the batch: a file of single-vertex records stays what it was.
  const bool several_bounces = !batch.deeper.empty() || !batch.scattered.empty();
  Header header{};
  std::memcpy(header.magic, kMagic, sizeof kMagic);
  header.version = !batch.own_light.empty() ? kRecordFileVersion : several_bounces ? 3 : 2;
  header.header_size = HeaderSize(header.version);
  header.record_size = sizeof(Record);
  header.width = batch.width;
  header.height = batch.height;
  header.samples_per_pixel = batch.samples_per_pixel;
  header.fov_y_radians = batch.fov_y_radians;
  header.record_count = batch.records.size();
  header.frame = batch.frame;
  header.frame_count = frames_;
  header.deeper_count = batch.deeper.size();
  header.scattered_count = batch.scattered.size();
  header.own_light_count = batch.own_light.size();
  std::uint64_t checksum = Fnv1a(&header, header.header_size);
  out_.write(reinterpret_cast<const char*>(&header), header.header_size);
  for (const std::vector<Record>* records : {&batch.records, &batch.deeper, &batch.scattered}) {
    const std::size_t bytes = records->size() * sizeof(Record);
    checksum = Fnv1a(records->data(), bytes, checksum);
    out_.write(reinterpret_cast<const char*>(records->data()), static_cast<std::streamsize>(bytes));
  }
  const std::size_t own_bytes = OwnLightBytes(batch.own_light.size());
  checksum = Fnv1a(batch.own_light.data(), own_bytes, checksum);
  out_.write(reinterpret_cast<const char*>(batch.own_light.data()), static_cast<std::streamsize>(own_bytes));
  out_.write(reinterpret_cast<const char*>(&checksum), sizeof checksum);
  if (!out_) throw InputError(path_ + ": writing the record file failed");
  ++written_;
  last_frame_ = batch.frame;
}

void RecordFileWriter::Finish() {
  if (written_ != frames_) {
    throw InputError(path_ + ": " + std::to_string(written_) + " frames written of the " + std::to_string(frames_) +
                     " announced");
  }
  if (!out_.flush()) throw InputError(path_ + ": writing the record file failed");
  out_.close();
  std::filesystem::rename(temporary_, path_);
  finished_ = true;
}

void WriteRecordFile(const std::string& path, std::span<const RecordBatch> frames) {
  RecordFileWriter writer(path, std::uint32_t(frames.size()));
  for (const RecordBatch& batch : frames) writer.Append(batch);
  writer.Finish();
}

void WriteRecordFile(const std::string& path, const RecordBatch& batch) {
  WriteRecordFile(path, std::span<const RecordBatch>(&batch, 1));
}

std::vector<RecordBatch> ReadRecordFrames(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the record file");
  const std::uint64_t file_size = std::filesystem::file_size(path);
  auto fail = [&](std::uint64_t offset, const std::string& problem) -> InputError {
    return InputError(path + ": byte " + std::to_string(offset) + ": " + problem);
  };
  std::vector<RecordBatch> frames;
  std::uint64_t at = 0;  // where this block starts
  std::uint32_t frame_count = 1;
  do {
    Header header{};
    if (file_size - at < kVersion1HeaderSize) {
      throw fail(file_size, "truncated: the header needs " + std::to_string(kVersion1HeaderSize) + " bytes");
    }
    in.read(reinterpret_cast<char*>(&header), kVersion1HeaderSize);
    if (std::memcmp(header.magic, kMagic, sizeof kMagic) != 0) throw fail(at, "not an .hpsfv record file (bad magic)");
    if (header.version != 2 && header.version != 3 && header.version != 4 && !(header.version == 1 && at == 0)) {
      throw fail(at + 8, "format version " + std::to_string(header.version) + ", this hpsf reads versions 1 to 4" +
                             (at > 0 ? " (version 1 holds one frame)" : ""));
    }
    const std::uint32_t header_size = HeaderSize(header.version);
    if (header.header_size != header_size) {
      throw fail(at + 12,
                 "header size " + std::to_string(header.header_size) + ", expected " + std::to_string(header_size));
    }
    if (header.version >= 2) {
      if (file_size - at < header_size) {
        throw fail(file_size, "truncated: the header needs " + std::to_string(header_size) + " bytes");
      }
      in.read(reinterpret_cast<char*>(&header.frame), header_size - kVersion1HeaderSize);
      if (at == 0) {
        if (header.frame_count == 0 || header.frame_count > kMaxRecordFileFrames) {
          throw fail(at + 52, "frame count " + std::to_string(header.frame_count) + ", expected 1 to 2^20");
        }
        frame_count = header.frame_count;
      } else if (header.frame_count != frame_count) {
        throw fail(at + 52, "frame count " + std::to_string(header.frame_count) + ", the first frame's says " +
                                std::to_string(frame_count));
      }
      if (!frames.empty() && header.frame <= frames.back().frame) {
        throw fail(at + 48, "frame " + std::to_string(header.frame) + " after frame " +
                                std::to_string(frames.back().frame) + "; frame numbers must increase");
      }
    }
    if (header.record_size != sizeof(Record)) {
      throw fail(at + 16, "record size " + std::to_string(header.record_size) + ", expected 144");
    }
    if (std::uint64_t(header.width) * header.height * header.samples_per_pixel != header.record_count) {
      throw fail(at + 20, "width x height x samples per pixel does not equal the record count " +
                              std::to_string(header.record_count));
    }
    if (header.record_count > (1ull << 31)) {
      throw fail(at + 40, "record count " + std::to_string(header.record_count) + ", at most 2^31 a frame");
    }
    // Versions 3 and 4 hold the deeper and scattered counts: bounded before any size is computed from them.
    if (header.version >= 3) {
      if (header.deeper_count > (1ull << 31) - header.record_count) {
        throw fail(at + 56, "deeper record count " + std::to_string(header.deeper_count) +
                                ", at most 2^31 records a frame with the others");
      }
      if (header.scattered_count != 0 && header.scattered_count != header.record_count + header.deeper_count) {
        throw fail(at + 64, "scattered vertex count " + std::to_string(header.scattered_count) +
                                ", expected none or one per record and deeper record (" +
                                std::to_string(header.record_count + header.deeper_count) + ")");
      }
      if (header.version == 3 && header.deeper_count == 0 && header.scattered_count == 0) {
        throw fail(at + 56, "a version 3 block without deeper records or scattered vertices (version 2 holds it)");
      }
    }
    if (header.version == 4 && (header.own_light_count != header.record_count || header.record_count == 0)) {
      throw fail(at + 72, "own light count " + std::to_string(header.own_light_count) + ", expected one per record (" +
                              std::to_string(header.record_count) +
                              "), at least one: versions 2 and 3 hold a block without");
    }
    const std::uint64_t stored = header.record_count + header.deeper_count + header.scattered_count;
    const std::uint64_t block_end =
        at + header_size + stored * sizeof(Record) + OwnLightBytes(header.own_light_count) + sizeof(std::uint64_t);
    if (block_end > file_size) {
      throw fail(file_size, "truncated: " + std::to_string(file_size) + " bytes, frame " +
                                std::to_string(frames.size()) + " ends at byte " + std::to_string(block_end));
    }
    if (frames.size() + 1 == frame_count && block_end != file_size) {
      throw fail(block_end, "trailing bytes: " + std::to_string(file_size) + " bytes, the last frame ends at byte " +
                                std::to_string(block_end));
    }
    RecordBatch batch;
    batch.width = header.width;
    batch.height = header.height;
    batch.samples_per_pixel = header.samples_per_pixel;
    batch.fov_y_radians = header.fov_y_radians;
    batch.frame = header.version == 1 ? 0 : header.frame;
    batch.records.resize(header.record_count);
    batch.deeper.resize(header.deeper_count);
    batch.scattered.resize(header.scattered_count);
    std::uint64_t expected = Fnv1a(&header, header_size);
    for (std::vector<Record>* records : {&batch.records, &batch.deeper, &batch.scattered}) {
      in.read(reinterpret_cast<char*>(records->data()), static_cast<std::streamsize>(records->size() * sizeof(Record)));
      expected = Fnv1a(records->data(), records->size() * sizeof(Record), expected);
    }
    batch.own_light.resize(header.own_light_count);
    const std::size_t own_bytes = OwnLightBytes(header.own_light_count);
    in.read(reinterpret_cast<char*>(batch.own_light.data()), static_cast<std::streamsize>(own_bytes));
    expected = Fnv1a(batch.own_light.data(), own_bytes, expected);
    std::uint64_t checksum = 0;
    in.read(reinterpret_cast<char*>(&checksum), sizeof checksum);
    if (!in) throw fail(at + header_size, "read failed");
    if (checksum != expected) {
      throw fail(block_end - sizeof checksum, "checksum mismatch: the file is corrupt");
    }
    // An own light is a pixel's light, blended into the image: finite, its alpha 0, as the tracer writes it.
    const std::uint64_t own_start = block_end - sizeof checksum - own_bytes;
    for (std::size_t i = 0; i < batch.own_light.size(); ++i) {
      const glm::vec4& own = batch.own_light[i];
      if (!(std::isfinite(own.x) && std::isfinite(own.y) && std::isfinite(own.z)) || own.w != 0.0f) {
        throw fail(own_start + i * sizeof(glm::vec4),
                   "own light " + std::to_string(i) + " is not a finite light with alpha 0");
      }
    }
    frames.push_back(std::move(batch));
    at = block_end;
  } while (frames.size() < frame_count);
  return frames;
}

RecordBatch ReadRecordFile(const std::string& path) {
  std::vector<RecordBatch> frames = ReadRecordFrames(path);
  if (frames.size() != 1) {
    throw InputError(path + ": holds " + std::to_string(frames.size()) +
                     " frames; this command filters one (replay and crosscheck take several)");
  }
  return std::move(frames[0]);
}

}  // namespace hpsf
