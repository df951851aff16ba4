// .hpsfv files: the record batches of one or more frames, so any renderer's vertices can be replayed, frame after
// frame through one table. Little-endian. Version 2 (written): one block per frame, each a header (magic, version,
// header size, record size, image size, samples per pixel, field of view, record count, frame number, frames in
// the file), the records in the 144-byte layout of core/shared/record_layout.h, and an FNV-1a checksum of the
// block before it; frame numbers increase from block to block. Version 3 (written for a batch with several filtered
// bounces, core/transport.h, and only then): version 2's header with the counts of deeper records and of scattered
// vertices (none, or one per record and deeper record) after it, and those arrays after the records. Version 4
// (written for a batch with own lights, RecordBatch::own_light, and only then): version 3's header with the count of
// own lights (one per record) after it, and after the scattered vertices one vec4 per record (finite rgb, alpha 0). A
// file may mix blocks of versions 2 to 4. Version 1 (read): one block without the frame fields, frame 0. Reading
// checks each of these; a truncated or corrupt file is an InputError naming the file and the byte offset.
#ifndef HPSF_CORE_RECORD_FILE_H
#define HPSF_CORE_RECORD_FILE_H

#include <cstdint>
#include <fstream>
#include <span>
#include <string>
#include <vector>

#include "core/record.h"

namespace hpsf {

inline constexpr std::uint32_t kRecordFileVersion = 4;           // the newest written
inline constexpr std::uint32_t kMaxRecordFileFrames = 1u << 20;  // kMaxFrames, the longest sequence a table takes

// Writes the frames as they come, to a temporary name beside `path` that Finish renames: a failure, or a writer
// destroyed unfinished, leaves no file.
class RecordFileWriter {
 public:
  RecordFileWriter(const std::string& path, std::uint32_t frames);
  ~RecordFileWriter();
  RecordFileWriter(const RecordFileWriter&) = delete;
  RecordFileWriter& operator=(const RecordFileWriter&) = delete;
  // The next frame; its frame number above the last one's.
  void Append(const RecordBatch& batch);
  // After exactly `frames` Appends.
  void Finish();

 private:
  std::string path_, temporary_;
  std::uint32_t frames_ = 0, written_ = 0;
  std::uint32_t last_frame_ = 0;
  std::ofstream out_;
  bool finished_ = false;
};

void WriteRecordFile(const std::string& path, std::span<const RecordBatch> frames);
void WriteRecordFile(const std::string& path, const RecordBatch& batch);

// Every frame of the file, in order.
std::vector<RecordBatch> ReadRecordFrames(const std::string& path);
// The one frame of a file that holds one; a file of several is an InputError saying so.
RecordBatch ReadRecordFile(const std::string& path);

}  // namespace hpsf

#endif  // HPSF_CORE_RECORD_FILE_H
