#pragma once
// The scene data on the host (device_shared.h, "The scene data"): the
// 32-bit words a unit (a light, camera or material type) appends its
// parameters and tables to, keeping the offsets in its own record; the
// tracers upload the words as one buffer.
#include <bit>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

namespace spectrace {

class SceneData {
 public:
  // Appends `values` (floats as their bits); returns the offset of the first.
  uint32_t append(std::span<const float> values) {
    const uint32_t first = reserve(values.size());
    for (float v : values) words_.push_back(std::bit_cast<uint32_t>(v));
    return first;
  }
  uint32_t append(std::span<const uint32_t> values) {
    const uint32_t first = reserve(values.size());
    words_.insert(words_.end(), values.begin(), values.end());
    return first;
  }
  // Never empty: the buffer is bound even when no unit uses it.
  const std::vector<uint32_t>& words() const { return words_; }

 private:
  uint32_t reserve(size_t count) const {
    if (words_.size() + count > UINT32_MAX) throw std::length_error("the scene data passes 2^32 words");
    return uint32_t(words_.size());
  }
  std::vector<uint32_t> words_{0u};
};

}  // namespace spectrace
