#include "rng/philox.h"

#include <Random123/philox.h>

namespace spectrace {

std::array<uint32_t, 4> philoxWords(uint64_t seed, uint64_t beamIndex, uint32_t block) {
  r123::Philox4x32_R<10> philox;
  const r123::Philox4x32_R<10>::ctr_type counter = {
      {uint32_t(beamIndex), uint32_t(beamIndex >> 32), block, 0u}};
  const r123::Philox4x32_R<10>::key_type key = {{uint32_t(seed), uint32_t(seed >> 32)}};
  const auto out = philox(counter, key);
  return {out[0], out[1], out[2], out[3]};
}

}  // namespace spectrace
