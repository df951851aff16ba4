// .hpsfv files: one record batch, so any renderer's vertices can be replayed. Little-endian: a versioned
// header (magic, version, header size, record size, image size, samples per pixel, field of view, count),
// the records in the 144-byte layout of core/shared/record_layout.h, and an FNV-1a checksum of everything
// before it. Reading checks each of these; a truncated or corrupt file is an InputError naming the file and the
// byte offset.
#ifndef HPSF_CORE_RECORD_FILE_H
#define HPSF_CORE_RECORD_FILE_H

#include <string>

#include "core/record.h"

namespace hpsf {

inline constexpr std::uint32_t kRecordFileVersion = 1;

// Writes to a temporary name beside `path` and renames it, so a failure leaves no partial file.
void WriteRecordFile(const std::string& path, const RecordBatch& batch);
RecordBatch ReadRecordFile(const std::string& path);

}  // namespace hpsf

#endif  // HPSF_CORE_RECORD_FILE_H
