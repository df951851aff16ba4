#include "core/record_file.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "core/fnv1a.h"

namespace hpsf {
namespace {

static_assert(std::endian::native == std::endian::little, ".hpsfv is little-endian and written as memory");

constexpr char kMagic[8] = {'H', 'P', 'S', 'F', 'V', 'R', 'E', 'C'};

// Version 1's header is the first 48 bytes of version 2's.
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
  std::uint32_t frame;        // version 2
  std::uint32_t frame_count;  // version 2: the same in every block
};
static_assert(sizeof(Header) == 56);
constexpr std::uint32_t kVersion1HeaderSize = 48;

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
  Header header{};
  std::memcpy(header.magic, kMagic, sizeof kMagic);
  header.version = kRecordFileVersion;
  header.header_size = sizeof(Header);
  header.record_size = sizeof(Record);
  header.width = batch.width;
  header.height = batch.height;
  header.samples_per_pixel = batch.samples_per_pixel;
  header.fov_y_radians = batch.fov_y_radians;
  header.record_count = batch.records.size();
  header.frame = batch.frame;
  header.frame_count = frames_;
  const std::size_t record_bytes = batch.records.size() * sizeof(Record);
  const std::uint64_t checksum = Fnv1a(batch.records.data(), record_bytes, Fnv1a(&header, sizeof header));
  out_.write(reinterpret_cast<const char*>(&header), sizeof header);
  out_.write(reinterpret_cast<const char*>(batch.records.data()), static_cast<std::streamsize>(record_bytes));
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
    if (header.version != 2 && !(header.version == 1 && at == 0)) {
      throw fail(at + 8, "format version " + std::to_string(header.version) + ", this hpsf reads versions 1 and 2" +
                             (at > 0 ? " (version 1 holds one frame)" : ""));
    }
    const std::uint32_t header_size = header.version == 1 ? kVersion1HeaderSize : std::uint32_t(sizeof(Header));
    if (header.header_size != header_size) {
      throw fail(at + 12,
                 "header size " + std::to_string(header.header_size) + ", expected " + std::to_string(header_size));
    }
    if (header.version == 2) {
      if (file_size - at < sizeof header) throw fail(file_size, "truncated: the header needs 56 bytes");
      in.read(reinterpret_cast<char*>(&header.frame), sizeof header - kVersion1HeaderSize);
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
    const std::uint64_t block_end = at + header_size + header.record_count * sizeof(Record) + sizeof(std::uint64_t);
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
    in.read(reinterpret_cast<char*>(batch.records.data()),
            static_cast<std::streamsize>(header.record_count * sizeof(Record)));
    std::uint64_t checksum = 0;
    in.read(reinterpret_cast<char*>(&checksum), sizeof checksum);
    if (!in) throw fail(at + header_size, "read failed");
    if (checksum != Fnv1a(batch.records.data(), batch.records.size() * sizeof(Record), Fnv1a(&header, header_size))) {
      throw fail(block_end - sizeof checksum, "checksum mismatch: the file is corrupt");
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
