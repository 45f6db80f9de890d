// Its own file: only this one recompiles when the commit changes.
#include "cli/version.h"

#include "spectrace_version.h"

namespace spectrace::cli {

const char* versionText() { return SPECTRACE_VERSION_TEXT; }

}  // namespace spectrace::cli
