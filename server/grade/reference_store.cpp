#include "grade/reference_store.h"

#include <elf.h>
#include <link.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>

#include "core/hash.h"
#include "grade/reference_entry.h"

namespace shadelab::grade {

namespace fs = std::filesystem;

namespace {

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::string out;
  in.seekg(0, std::ios::end);
  const auto size = in.tellg();
  if (size <= 0) return out;
  out.resize(static_cast<size_t>(size));
  in.seekg(0);
  in.read(out.data(), size);
  out.resize(static_cast<size_t>(in.gcount()));
  return out;
}

// The GNU build ID the linker wrote into the running executable (a hash of the whole output),
// read from its loaded notes; empty when it has none.
std::string gnu_build_id() {
  std::string id;
  dl_iterate_phdr([](dl_phdr_info* info, size_t, void* out) -> int {
    for (int i = 0; i < info->dlpi_phnum; ++i) {
      const ElfW(Phdr)& ph = info->dlpi_phdr[i];
      if (ph.p_type != PT_NOTE) continue;
      const auto* at = reinterpret_cast<const unsigned char*>(info->dlpi_addr + ph.p_vaddr);
      for (size_t offset = 0; offset + sizeof(ElfW(Nhdr)) <= ph.p_memsz;) {
        ElfW(Nhdr) note;
        std::memcpy(&note, at + offset, sizeof note);
        const size_t name_at = offset + sizeof note, desc_at = name_at + ((note.n_namesz + 3) & ~3u);
        if (desc_at + note.n_descsz > ph.p_memsz) break;
        if (note.n_type == NT_GNU_BUILD_ID && note.n_namesz == 4 && std::memcmp(at + name_at, "GNU", 4) == 0) {
          static_cast<std::string*>(out)->assign(reinterpret_cast<const char*>(at + desc_at), note.n_descsz);
          return 1;
        }
        offset = desc_at + ((note.n_descsz + 3) & ~3u);
      }
    }
    return 1;  // the first object is the executable: no further
  }, &id);
  return id;
}

// The redis key of a store's entry: beside uploads and responses (store/shared_store.h).
std::string shared_key(const std::string& key) { return "shadelab:1:reference:" + key; }

}  // namespace

// Reading and hashing the whole executable took ~0.4 s a process for a 150 MB build with debug
// information: every worker and every Gradescope run paid it. The build ID is the linker's hash of
// the same bytes, read from memory.
const std::string& build_fingerprint() {
  static const std::string fingerprint = [] {
    const std::string id = gnu_build_id();
    return id.empty() ? sha256_hex(read_file("/proc/self/exe")) : "gnu-build-id:" + sha256_hex(id);
  }();
  return fingerprint;
}

std::string default_reference_folder() {
  if (const char* dir = std::getenv("SHADELAB_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/shadelab/references";
  if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/shadelab/references";
  return {};
}

ReferenceStore::ReferenceStore(fs::path folder, store::SharedStore* shared, std::string renderer)
    : folder_(std::move(folder)), shared_(shared), renderer_(std::move(renderer)) {}

std::string ReferenceStore::key(const render::RenderRequest& request, const std::string& mesh) const {
  return sha256_hex(std::string(kReferenceEntryFormat) + build_fingerprint() + '\0' + renderer_ + '\0' + mesh + '\0' + render::pixel_identity(request));
}

std::optional<SharedFrames> ReferenceStore::load(const std::string& key, const render::RenderRequest& request) const {
  if (!folder_.empty())
    if (auto frames = decode_reference_entry(read_file(folder_ / key), request)) return frames;
  if (!shared_) return std::nullopt;
  auto entry = shared_->get(shared_key(key));  // an outage is a miss: the grader renders
  if (!entry || !*entry) return std::nullopt;
  auto frames = decode_reference_entry(**entry, request);
  if (frames) write_to_folder(key, **entry);  // the next grade on this node reads its disk
  return frames;
}

void ReferenceStore::save(const std::string& key, const SharedFrames& frames) const {
  if (frames.empty()) return;
  const std::string entry = encode_reference_entry(frames);
  if (entry.empty()) return;
  write_to_folder(key, entry);
  if (shared_) (void)shared_->put(shared_key(key), entry);
}

void ReferenceStore::write_to_folder(const std::string& key, const std::string& entry) const {
  if (folder_.empty()) return;
  std::error_code ec;
  fs::create_directories(folder_, ec);
  const fs::path temporary = folder_ / (key + ".tmp" + std::to_string(::getpid()));
  {
    std::ofstream file(temporary, std::ios::binary);
    if (!file.write(entry.data(), static_cast<std::streamsize>(entry.size()))) {
      fs::remove(temporary, ec);
      return;
    }
  }
  fs::rename(temporary, folder_ / key, ec);
  if (ec) fs::remove(temporary, ec);
}

}  // namespace shadelab::grade
