#include "core/record_file.h"

#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"

namespace hpsf {
namespace {

RecordBatch SmallBatch() {
  RecordBatch b;
  b.width = 2;
  b.height = 1;
  b.samples_per_pixel = 2;
  b.fov_y_radians = 0.5;
  VertexSample v;
  v.position = glm::vec3(1.0f, -0.0f, 3.0f);
  v.contribution = glm::vec3(0.5f);
  b.records = {MakeVertexRecord(v), MakeRecordWithoutVertex(0, 1, glm::vec3(2.0f)), MakeVertexRecord(v),
               MakeRecordWithoutVertex(1, 1, glm::vec3(0.0f))};
  return b;
}

std::string TempPath(const std::string& name) { return (std::filesystem::temp_directory_path() / name).string(); }

std::string ErrorOf(const std::string& path) {
  try {
    ReadRecordFile(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(RecordFile, RoundTripsBitForBit) {
  const RecordBatch batch = SmallBatch();
  const std::string path = TempPath("hpsf_round_trip.hpsfv");
  WriteRecordFile(path, batch);
  const RecordBatch read = ReadRecordFile(path);
  EXPECT_EQ(read.width, 2u);
  EXPECT_EQ(read.samples_per_pixel, 2u);
  EXPECT_EQ(read.fov_y_radians, 0.5);
  ASSERT_EQ(read.records.size(), batch.records.size());
  EXPECT_EQ(std::memcmp(read.records.data(), batch.records.data(), batch.records.size() * sizeof(Record)), 0);
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
}

TEST(RecordFile, TruncatedAndCorruptFilesAreNamedWithTheirByte) {
  const std::string path = TempPath("hpsf_damaged.hpsfv");
  WriteRecordFile(path, SmallBatch());
  const auto size = std::filesystem::file_size(path);

  std::filesystem::resize_file(path, size - 100);
  EXPECT_NE(ErrorOf(path).find(path + ": byte "), std::string::npos);
  EXPECT_NE(ErrorOf(path).find("truncated"), std::string::npos) << ErrorOf(path);

  std::filesystem::resize_file(path, 20);
  EXPECT_NE(ErrorOf(path).find("truncated: the header needs 48 bytes"), std::string::npos) << ErrorOf(path);

  WriteRecordFile(path, SmallBatch());
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    f.put('\x7f');
  }
  EXPECT_NE(ErrorOf(path).find("checksum mismatch"), std::string::npos) << ErrorOf(path);

  std::ofstream(path) << "not a record file at all, but long enough to hold a header.......";
  EXPECT_NE(ErrorOf(path).find("bad magic"), std::string::npos) << ErrorOf(path);
  EXPECT_NE(ErrorOf(TempPath("hpsf_missing.hpsfv")).find("cannot open"), std::string::npos);
}

}  // namespace
}  // namespace hpsf
