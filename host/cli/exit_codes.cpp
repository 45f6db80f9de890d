#include "cli/exit_codes.h"

#include <new>
#include <stdexcept>

#include "cli/cli_numbers.h"
#include "film/film_state.h"
#include "json/json_fields.h"
#include "json/scene_error.h"
#include "session/job_file.h"
#include "session/session.h"
#include "spectrum/spd.h"

namespace spectrace::cli {

Failure failureOf(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const UsageError& e) {
    return {kExitBadInput, e.what()};
  } catch (const SceneError& e) {
    return {kExitBadInput, e.what()};
  } catch (const json_fields::JsonFieldError& e) {
    return {kExitBadInput, e.what()};
  } catch (const SpdError& e) {
    return {kExitBadInput, e.what()};
  } catch (const JobFileError& e) {
    return {kExitBadInput, e.what()};
  } catch (const OutputPathError& e) {
    return {kExitBadInput, e.what()};
  } catch (const FilmStateError& e) {  // a state that cannot be read or does not belong
    return {kExitBadInput, e.what()};
  } catch (const std::invalid_argument& e) {  // parseDeviceChoice
    return {kExitBadInput, e.what()};
  } catch (const std::bad_alloc&) {
    // Films are checked against the memory before tracing; this is what is left.
    return {kExitRuntime, "out of memory (an allocation failed); use fewer pixels, bins, lights or table rows"};
  } catch (const std::exception& e) {
    return {kExitRuntime, e.what()};
  } catch (...) {
    return {kExitRuntime, "unknown error"};
  }
}

}  // namespace spectrace::cli
