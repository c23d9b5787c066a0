#include "bounce/core/qmc.h"

#include <array>

namespace bounce {

float halton(uint32_t dim, uint32_t i) {
  static constexpr std::array<uint32_t, 16> kPrimes = {2,  3,  5,  7,  11, 13, 17, 19,
                                                       23, 29, 31, 37, 41, 43, 47, 53};
  return radical_inverse(kPrimes[dim % kPrimes.size()], i);
}

}  // namespace bounce
