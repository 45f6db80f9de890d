// Linked into every gtest binary (spectrace_add_test): before main(), points
// Mesa's shader cache, the runtime directory and $XDG_CACHE_HOME
// (spectrace's pipeline cache) into the build tree, unless
// the caller set them, so tests leave nothing under $HOME. Done here rather
// than through CTest's ENVIRONMENT property because gtest_discover_tests
// splits a list-valued property, and so the binaries behave the same when
// run by hand.
#include <cstdlib>

namespace {

__attribute__((constructor)) void spectraceTestEnvironment() {
  setenv("MESA_SHADER_CACHE_DIR", SPECTRACE_TEST_BUILD_DIR "/mesa_shader_cache", 0);
  setenv("XDG_RUNTIME_DIR", SPECTRACE_TEST_BUILD_DIR, 0);
  setenv("XDG_CACHE_HOME", SPECTRACE_TEST_BUILD_DIR "/xdg_cache", 0);
}

}  // namespace
