// Reading files out of .pk3 archives (zip files, as Quake 3 packs its data) through libzip.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace bounce::quake {

// The largest entry we read: a corrupt directory must not make us allocate gigabytes.
constexpr size_t kMaxEntryBytes = size_t(256) << 20;

// One open archive. Entry names are matched without regard to case, as the game does.
class Pk3Archive {
 public:
  // Opens `path`; throws Error naming it when it is missing or not a readable zip archive.
  explicit Pk3Archive(const std::string& path);
  ~Pk3Archive();
  Pk3Archive(Pk3Archive&&) noexcept;
  Pk3Archive& operator=(Pk3Archive&&) noexcept;

  const std::string& path() const { return path_; }
  // Every entry name (files only), in the archive's order.
  const std::vector<std::string>& names() const { return names_; }
  bool contains(const std::string& name) const;
  // The bytes of an entry; throws Error naming the archive and entry when it is missing,
  // larger than kMaxEntryBytes or cannot be decompressed (a bad checksum included).
  std::vector<uint8_t> read(const std::string& name) const;

 private:
  struct Impl;
  std::string path_;
  std::vector<std::string> names_;
  std::unique_ptr<Impl> impl_;
};

// Archives searched in order: the first that holds a name wins.
class Pk3Set {
 public:
  void add(Pk3Archive archive) { archives_.push_back(std::move(archive)); }
  const std::vector<Pk3Archive>& archives() const { return archives_; }
  // The archive holding `name`, or null.
  const Pk3Archive* find(const std::string& name) const;

 private:
  std::vector<Pk3Archive> archives_;
};

}  // namespace bounce::quake
