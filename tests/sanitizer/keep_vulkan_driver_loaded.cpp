// Sanitizer builds only (SPECTRACE_SANITIZE=ON): compiled into every
// executable that links spectrace_core, never into a normal build.
//
// The Vulkan loader dlopen()s the driver when an instance is created and
// dlclose()s it again at vkDestroyInstance. Mesa's lavapipe
// (libvulkan_lvp.so, which links libLLVM) keeps a few heap blocks (128 bytes,
// grown with realloc) reachable only from its own static data. Once it is
// unloaded, LeakSanitizer no longer scans that data at exit, so those blocks
// look leaked, and their allocation frames point into unmapped memory
// ("<unknown module>"), which no suppression can name.
//
// Opening the driver once more with RTLD_NODELETE before main() pins it (and
// the libraries it needs, libLLVM among them) for the life of the process:
// the loader's later dlopen() by full path finds this same object, its
// dlclose() no longer unmaps it, and at exit LeakSanitizer still scans the
// driver's data and names its module in any stack it prints. Leaks of our own
// are unaffected (tests/sanitizer/leak_on_purpose.cpp checks that).
//
// Where lavapipe is not installed there is nothing to pin: the failure is
// ignored and the loader behaves as usual.
#include <dlfcn.h>

namespace {

__attribute__((constructor)) void spectraceKeepVulkanDriverLoaded() {
  // The handle is deliberately never closed.
  (void)dlopen("libvulkan_lvp.so", RTLD_LAZY | RTLD_LOCAL | RTLD_NODELETE);
  // The same for the Khronos validation layer, which the loader also unloads
  // at vkDestroyInstance (validation_test turns it on).
  (void)dlopen("libVkLayer_khronos_validation.so", RTLD_LAZY | RTLD_LOCAL | RTLD_NODELETE);
}

}  // namespace
