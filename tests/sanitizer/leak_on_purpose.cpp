// Sanitizer builds only: a leak of our own, made on purpose after a Vulkan
// instance has come and gone (so the driver has been loaded and "unloaded",
// as in every GPU test). The sanitizer_catches_our_own_leak test passes only
// if LeakSanitizer, under the same LSAN_OPTIONS and suppressions as every
// other test, reports exactly this leak: a suppression or the driver pinning
// (keep_vulkan_driver_loaded.cpp) that hid our own leaks fails it, and so
// does a driver block that is reported again.
#include <vulkan/vulkan.h>

#include <cstdio>

// Out of line, and the pointer dropped through a volatile, so the compiler
// can neither elide the allocation nor leave it reachable.
__attribute__((noinline)) void spectraceLeakOnPurpose() {
  int* volatile leaked = new int[64];  // 256 bytes
  leaked[0] = 42;
  leaked = nullptr;
}

int main() {
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  info.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  if (vkCreateInstance(&info, nullptr, &instance) == VK_SUCCESS) {
    uint32_t devices = 0;
    vkEnumeratePhysicalDevices(instance, &devices, nullptr);
    std::printf("leak_on_purpose: %u Vulkan device(s)\n", devices);
    vkDestroyInstance(instance, nullptr);
  } else {
    std::puts("leak_on_purpose: no Vulkan instance (no driver?); leaking anyway");
  }
  spectraceLeakOnPurpose();
  std::puts("leak_on_purpose: leaked 256 bytes; LeakSanitizer should report them at exit");
  std::fflush(stdout);
  return 0;
}
