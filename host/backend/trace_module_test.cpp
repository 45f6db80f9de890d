// The trace shader's modules as SPIR-V: a render's module calls the kernel
// from one place and holds none of the bench's profile. Mesa's Vulkan
// drivers inline every call before specialisation constants prune the
// branches, so each further call site of the kernel is one more copy of it to
// compile in every process (vulkan_tracer.cpp: traceModule).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "embedded_shaders.h"

namespace spectrace {
namespace {

constexpr uint32_t kSpirvMagic = 0x07230203;
constexpr uint32_t kOpName = 5;
constexpr uint32_t kOpFunctionCall = 57;

// The static call sites in a module, by the called function's name up to
// its parameter list (glslang names "traceBeam(u641;...").
std::map<std::string, int> callSitesByName(std::span<const unsigned char> module) {
  std::vector<uint32_t> words(module.size() / 4);
  std::memcpy(words.data(), module.data(), words.size() * 4);
  EXPECT_GE(words.size(), 5u);
  EXPECT_EQ(words.empty() ? 0u : words[0], kSpirvMagic);
  std::map<uint32_t, std::string> names;
  std::map<uint32_t, int> calls;
  for (size_t i = 5; i < words.size();) {
    const uint32_t count = words[i] >> 16, opcode = words[i] & 0xffffu;
    if (count == 0 || i + count > words.size()) {
      ADD_FAILURE() << "a malformed instruction at word " << i;
      break;
    }
    if (opcode == kOpName && count >= 3) {
      const char* text = reinterpret_cast<const char*>(&words[i + 2]);
      const std::string name(text, strnlen(text, (count - 2) * 4));
      names[words[i + 1]] = name.substr(0, name.find('('));
    } else if (opcode == kOpFunctionCall && count >= 4) {
      ++calls[words[i + 3]];
    }
    i += count;
  }
  std::map<std::string, int> byName;
  for (const auto& [id, n] : calls) byName[names.count(id) ? names[id] : "<unnamed>"] += n;
  return byName;
}

int callSites(const std::map<std::string, int>& calls, const std::string& name) {
  const auto it = calls.find(name);
  return it == calls.end() ? 0 : it->second;
}

TEST(TraceModule, RenderModulesCallTheKernelOnceAndHoldNoProfile) {
  for (const auto& [what, module] : {std::pair{"trace_beams", embedded::spv_trace_beams()},
                                     std::pair{"trace_camera_paths", embedded::spv_trace_camera_paths()}}) {
    SCOPED_TRACE(what);
    const auto calls = callSitesByName(module);
    EXPECT_EQ(callSites(calls, "traceBeam"), 1);
    EXPECT_EQ(callSites(calls, "traceLightPath"), 1);
    EXPECT_EQ(callSites(calls, "profileBeam"), 0);
    EXPECT_EQ(callSites(calls, "profileFirstHit"), 0);
  }
}

TEST(TraceModule, ProfileModulesCallTheProfileOnce) {
  for (const auto& [what, module] : {std::pair{"trace_beams_profile", embedded::spv_trace_beams_profile()},
                                     std::pair{"trace_camera_paths_profile",
                                               embedded::spv_trace_camera_paths_profile()}}) {
    SCOPED_TRACE(what);
    const auto calls = callSitesByName(module);
    EXPECT_EQ(callSites(calls, "profileBeam"), 1);
    EXPECT_EQ(callSites(calls, "traceBeam"), 1);  // the profile's whole-kernel stages
  }
}

}  // namespace
}  // namespace spectrace
