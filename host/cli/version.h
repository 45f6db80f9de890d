#pragma once
// `spectrace --version`: "spectrace x.y.z", with " (git <commit>)" when built
// from a git checkout (cmake/Version.cmake).
namespace spectrace::cli {

const char* versionText();

}  // namespace spectrace::cli
