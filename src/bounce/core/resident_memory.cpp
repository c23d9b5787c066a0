#include "bounce/core/resident_memory.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace bounce {

uint64_t resident_memory_bytes() {
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  unsigned long long size_pages = 0, resident_pages = 0;
  const int read = std::fscanf(f, "%llu %llu", &size_pages, &resident_pages);
  std::fclose(f);
  if (read != 2) return 0;
  const long page = ::sysconf(_SC_PAGESIZE);
  return uint64_t(resident_pages) * uint64_t(page > 0 ? page : 4096);
}

double MemorySamples::growth_after(int from_frame) const {
  const auto first = std::lower_bound(frames.begin(), frames.end(), from_frame);
  if (first == frames.end() || frames.end() - first < 2) return 0.0;
  const size_t i0 = size_t(first - frames.begin());
  const uint64_t base = bytes[i0];
  const uint64_t peak = *std::max_element(bytes.begin() + long(i0), bytes.end());
  return base > 0 ? double(peak) / double(base) - 1.0 : 0.0;
}

}  // namespace bounce
