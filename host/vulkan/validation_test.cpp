// SPECTRACE_VALIDATION=1 makes a validation message fail the process: the
// next sync point throws VulkanError with the message. This test turns
// validation on for itself, so it needs the Khronos layer installed
// (vulkan-validationlayers, from scripts/setup.sh) and fails without it.
#include <cstdlib>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "vulkan/context.h"

namespace spectrace::vk_util {
namespace {

using ::testing::HasSubstr;

std::unique_ptr<Context> validatingContext() {
  setenv("SPECTRACE_VALIDATION", "1", 1);
  auto ctx = Context::create();
  EXPECT_TRUE(ctx->validationEnabled()) << "the Khronos validation layer is not installed (vulkan-validationlayers)";
  return ctx;
}

TEST(Validation, MisuseFailsTheNextSyncPoint) {
  auto ctx = validatingContext();
  ASSERT_TRUE(ctx->validationEnabled());
  std::string message;
  try {
    // A barrier with no source or destination stage is invalid without the
    // synchronization2 feature (VUID-vkCmdPipelineBarrier-srcStageMask-03937);
    // drivers ignore it, so only the layer can notice.
    ctx->submitAndWait([](const vk::raii::CommandBuffer& cmd) { cmd.pipelineBarrier({}, {}, {}, {}, {}, {}); });
  } catch (const VulkanError& e) {
    message = e.what();
  }
  EXPECT_THAT(message, HasSubstr("Vulkan validation (SPECTRACE_VALIDATION=1) reported"));
  EXPECT_THAT(message, HasSubstr("srcStageMask"));
  // Each message is reported once: a correct submission afterwards passes.
  EXPECT_NO_THROW(ctx->submitAndWait([](const vk::raii::CommandBuffer& cmd) { computeBarrier(cmd); }));
}

TEST(Validation, CorrectUseIsQuiet) {
  auto ctx = validatingContext();
  ASSERT_TRUE(ctx->validationEnabled());
  EXPECT_NO_THROW(ctx->submitAndWait([](const vk::raii::CommandBuffer& cmd) { computeBarrier(cmd); }));
  EXPECT_NO_THROW(ctx->throwOnValidationMessages());
}

}  // namespace
}  // namespace spectrace::vk_util
