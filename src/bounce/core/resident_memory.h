// The process's resident memory, sampled over a long run (bench --memory-every, the soak) to show
// that memory stays flat: a leak or a buffer that grows each frame shows as a rising series.
#pragma once

#include <cstdint>
#include <vector>

namespace bounce {

// Resident set size of this process in bytes (/proc/self/statm, resident pages x page size);
// 0 where /proc is not available.
uint64_t resident_memory_bytes();

// Resident memory sampled at frame numbers (counted from the first frame rendered).
struct MemorySamples {
  std::vector<int> frames;
  std::vector<uint64_t> bytes;

  void add(int frame, uint64_t resident) {
    frames.push_back(frame);
    bytes.push_back(resident);
  }
  // Growth after warm-up: (largest sample at or after `from_frame`) / (first sample at or after
  // it) - 1, so 0.01 is 1 %. 0 when fewer than two samples lie there.
  double growth_after(int from_frame) const;
};

}  // namespace bounce
