#include "bounce/scene/quake/pk3.h"

#include <zip.h>

#include <algorithm>
#include <unordered_map>

#include "bounce/core/error.h"
#include "bounce/core/input_file.h"

namespace bounce::quake {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = (c >= 'A' && c <= 'Z') ? char(c - 'A' + 'a') : c;
  return s;
}

std::string zip_error_text(int code) {
  zip_error_t error;
  zip_error_init_with_code(&error, code);
  std::string text = zip_error_strerror(&error);
  zip_error_fini(&error);
  return text;
}

}  // namespace

struct Pk3Archive::Impl {
  zip_t* zip = nullptr;
  std::unordered_map<std::string, zip_uint64_t> index_of;  // lower-case name -> entry

  ~Impl() {
    if (zip) zip_discard(zip);
  }
};

Pk3Archive::Pk3Archive(const std::string& path) : path_(path), impl_(std::make_unique<Impl>()) {
  check_regular_file(path, "pk3 archive");
  int code = 0;
  // ZIP_CHECKCONS: reject archives whose central directory and local headers disagree.
  impl_->zip = zip_open(path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &code);
  if (!impl_->zip) {
    if (code == ZIP_ER_NOENT || code == ZIP_ER_OPEN)
      fail("{}: cannot open the archive ({})", path, zip_error_text(code));
    fail("{}: not a readable .pk3 (zip) archive: {}", path, zip_error_text(code));
  }
  const zip_int64_t count = zip_get_num_entries(impl_->zip, 0);
  if (count < 0) fail("{}: cannot read the archive's directory", path);
  for (zip_int64_t i = 0; i < count; ++i) {
    const char* name = zip_get_name(impl_->zip, zip_uint64_t(i), 0);
    if (!name) fail("{}: entry {} has no readable name", path, i);
    const std::string entry = name;
    if (entry.empty() || entry.back() == '/') continue;  // folders
    names_.push_back(entry);
    impl_->index_of.emplace(lower(entry), zip_uint64_t(i));
  }
}

Pk3Archive::~Pk3Archive() = default;
Pk3Archive::Pk3Archive(Pk3Archive&&) noexcept = default;
Pk3Archive& Pk3Archive::operator=(Pk3Archive&&) noexcept = default;

bool Pk3Archive::contains(const std::string& name) const {
  return impl_->index_of.count(lower(name)) > 0;
}

std::vector<uint8_t> Pk3Archive::read(const std::string& name) const {
  const auto it = impl_->index_of.find(lower(name));
  if (it == impl_->index_of.end()) fail("{}: no entry '{}' in the archive", path_, name);
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat_index(impl_->zip, it->second, 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
    fail("{}: entry '{}': cannot read its size", path_, name);
  if (st.size > kMaxEntryBytes)
    fail("{}: entry '{}' is {} bytes, more than the {} we read", path_, name, st.size,
         kMaxEntryBytes);
  zip_file_t* file = zip_fopen_index(impl_->zip, it->second, 0);
  if (!file) fail("{}: entry '{}' cannot be opened: {}", path_, name, zip_strerror(impl_->zip));
  std::vector<uint8_t> bytes(size_t(st.size));
  size_t done = 0;
  bool failed = false;
  while (done < bytes.size()) {
    const zip_int64_t n = zip_fread(file, bytes.data() + done, bytes.size() - done);
    if (n <= 0) {
      failed = n < 0;
      break;
    }
    done += size_t(n);
  }
  // Reading past the end makes libzip check the CRC of a stored or deflated entry.
  uint8_t extra = 0;
  const zip_int64_t tail = failed ? -1 : zip_fread(file, &extra, 1);
  std::string reason = tail < 0 ? zip_file_strerror(file) : std::string();
  zip_fclose(file);
  if (tail < 0) fail("{}: entry '{}' is corrupt: {}", path_, name, reason);
  if (done != bytes.size() || tail != 0)
    fail("{}: entry '{}' holds {} bytes, not the {} its header says", path_, name,
         done + size_t(tail > 0 ? tail : 0), bytes.size());
  return bytes;
}

const Pk3Archive* Pk3Set::find(const std::string& name) const {
  for (const auto& a : archives_)
    if (a.contains(name)) return &a;
  return nullptr;
}

}  // namespace bounce::quake
