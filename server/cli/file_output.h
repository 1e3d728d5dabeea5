#pragma once
// Every file the CLI writes, written the same way: beside the target and renamed over it once the
// bytes are on disk, so a full disk or a kill never leaves half a file under the real name, and
// an error that says why (ENOSPC: "No space left on device") instead of a silent short file.
// Devices and pipes (/dev/stdout, /dev/full) are written in place.
#include <filesystem>
#include <string_view>

#include "core/expected.h"

namespace shadelab::cli {

Status write_file(const std::filesystem::path& path, std::string_view bytes);

}  // namespace shadelab::cli
