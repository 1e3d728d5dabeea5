#include "worker/zip_archive.h"

#include <zip.h>

namespace shadelab::worker {

Expected<std::string> zip_stored(const std::vector<std::pair<std::string, std::vector<std::uint8_t>>>& files) {
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* buffer = zip_source_buffer_create(nullptr, 0, 0, &error);
  zip_t* archive = buffer ? zip_open_from_source(buffer, ZIP_TRUNCATE, &error) : nullptr;
  if (!archive) {
    if (buffer) zip_source_free(buffer);
    return make_error(ErrorCode::io_error, std::string("cannot create a zip: ") + zip_error_strerror(&error));
  }
  zip_source_keep(buffer);  // survive zip_close, which is when the archive is written into it
  constexpr time_t kFixedTime = 1'700'000'000;  // any constant: the output must not depend on the clock
  for (const auto& [name, bytes] : files) {
    zip_source_t* entry = zip_source_buffer(archive, bytes.data(), bytes.size(), 0);
    const zip_int64_t index = entry ? zip_file_add(archive, name.c_str(), entry, ZIP_FL_ENC_UTF_8) : -1;
    if (index < 0) {
      if (entry) zip_source_free(entry);
      zip_discard(archive);
      zip_source_free(buffer);
      return make_error(ErrorCode::io_error, "cannot add " + name + " to the zip");
    }
    zip_set_file_compression(archive, static_cast<zip_uint64_t>(index), ZIP_CM_STORE, 0);
    zip_file_set_mtime(archive, static_cast<zip_uint64_t>(index), kFixedTime, 0);
  }
  if (zip_close(archive) < 0) {
    zip_source_free(buffer);
    return make_error(ErrorCode::io_error, "cannot write the zip");
  }
  std::string out;
  zip_stat_t stat;
  if (zip_source_stat(buffer, &stat) == 0 && zip_source_open(buffer) == 0) {
    out.resize(stat.size);
    zip_source_read(buffer, out.data(), stat.size);
    zip_source_close(buffer);
  }
  zip_source_free(buffer);
  return out;
}

}  // namespace shadelab::worker
