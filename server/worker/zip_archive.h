#pragma once
// A zip of already-compressed files (PNG frames), built in memory with libzip. Entries are stored,
// not deflated, and carry a fixed timestamp so the same frames always give the same bytes.
#include <string>
#include <utility>
#include <vector>

#include "core/expected.h"

namespace shadelab::worker {

Expected<std::string> zip_stored(const std::vector<std::pair<std::string, std::vector<std::uint8_t>>>& files);

}  // namespace shadelab::worker
