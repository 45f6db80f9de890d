#pragma once
// The test binaries' shared precompiled header (CMakeLists.txt,
// SPECTRACE_TEST_PCH): the library headers whose parsing took most of a
// test file's compile time. Only headers from outside the project, so a
// change to ours never rebuilds it.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <vulkan/vulkan_raii.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>
