#include "core/record_file.h"

#include <bit>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/error.h"

namespace hpsf {
namespace {

static_assert(std::endian::native == std::endian::little, ".hpsfv is little-endian and written as memory");

constexpr char kMagic[8] = {'H', 'P', 'S', 'F', 'V', 'R', 'E', 'C'};

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
};
static_assert(sizeof(Header) == 48);

std::uint64_t Fnv1a(const void* data, std::size_t size, std::uint64_t hash = 0xcbf29ce484222325ull) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull;
  return hash;
}

}  // namespace

void WriteRecordFile(const std::string& path, const RecordBatch& batch) {
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
  const std::size_t record_bytes = batch.records.size() * sizeof(Record);
  const std::uint64_t checksum = Fnv1a(batch.records.data(), record_bytes, Fnv1a(&header, sizeof header));

  const std::string temporary = path + ".partial";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path + ": cannot write the record file");
    out.write(reinterpret_cast<const char*>(&header), sizeof header);
    out.write(reinterpret_cast<const char*>(batch.records.data()), static_cast<std::streamsize>(record_bytes));
    out.write(reinterpret_cast<const char*>(&checksum), sizeof checksum);
    if (!out.flush()) {
      std::filesystem::remove(temporary);
      throw InputError(path + ": writing the record file failed");
    }
  }
  std::filesystem::rename(temporary, path);
}

RecordBatch ReadRecordFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the record file");
  const std::uint64_t file_size = std::filesystem::file_size(path);
  auto fail = [&](std::uint64_t offset, const std::string& problem) -> InputError {
    return InputError(path + ": byte " + std::to_string(offset) + ": " + problem);
  };
  Header header{};
  if (file_size < sizeof header) throw fail(file_size, "truncated: the header needs " + std::to_string(sizeof header) + " bytes");
  in.read(reinterpret_cast<char*>(&header), sizeof header);
  if (std::memcmp(header.magic, kMagic, sizeof kMagic) != 0) throw fail(0, "not an .hpsfv record file (bad magic)");
  if (header.version != kRecordFileVersion) {
    throw fail(8, "format version " + std::to_string(header.version) + ", this hpsf reads version " + std::to_string(kRecordFileVersion));
  }
  if (header.header_size != sizeof header) throw fail(12, "header size " + std::to_string(header.header_size) + ", expected 48");
  if (header.record_size != sizeof(Record)) throw fail(16, "record size " + std::to_string(header.record_size) + ", expected 144");
  if (std::uint64_t(header.width) * header.height * header.samples_per_pixel != header.record_count) {
    throw fail(20, "width x height x samples per pixel does not equal the record count " + std::to_string(header.record_count));
  }
  const std::uint64_t expected = sizeof header + header.record_count * sizeof(Record) + sizeof(std::uint64_t);
  if (header.record_count > (1ull << 31) || file_size != expected) {
    throw fail(std::min(file_size, expected), (file_size < expected ? "truncated: " : "trailing bytes: ") +
                                                  std::to_string(file_size) + " bytes, expected " + std::to_string(expected));
  }
  RecordBatch batch;
  batch.width = header.width;
  batch.height = header.height;
  batch.samples_per_pixel = header.samples_per_pixel;
  batch.fov_y_radians = header.fov_y_radians;
  batch.records.resize(header.record_count);
  in.read(reinterpret_cast<char*>(batch.records.data()), static_cast<std::streamsize>(header.record_count * sizeof(Record)));
  std::uint64_t checksum = 0;
  in.read(reinterpret_cast<char*>(&checksum), sizeof checksum);
  if (!in) throw fail(sizeof header, "read failed");
  if (checksum != Fnv1a(batch.records.data(), batch.records.size() * sizeof(Record), Fnv1a(&header, sizeof header))) {
    throw fail(expected - sizeof checksum, "checksum mismatch: the file is corrupt");
  }
  return batch;
}

}  // namespace hpsf
