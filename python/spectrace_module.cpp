// The Python module's native half (`spectrace._spectrace`): a thin binding
// over the C++ Session, render states and devices. The Python half
// (python/spectrace/__init__.py) only shapes arguments and errors; every
// number comes from the same code the CLI runs.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/function.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/shared_ptr.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "backend/device.h"
#include "film/film_state.h"
#include "io/image.h"
#include "json/scene_error.h"
#include "scene/scene.h"
#include "scene/scene_override.h"
#include "session/session.h"

namespace nb = nanobind;
namespace fs = std::filesystem;

namespace spectrace::python {
namespace {

// A finished render or developed state: the image as the CLI would write
// it, what its EXR header needs, and its exact state.
struct Result {
  RenderImage image;
  Scene scene;  // for the EXR header (write_exr)
  std::string deviceLabel;
  bool aim = true;
  uint64_t seed = 0, firstBeam = 0, beams = 0;
  double seconds = 0.0;
  std::shared_ptr<const FilmState> state;
};

// A float array of the image's, (H, W) or (H, W, n), owned by the Result's
// Python object so that it lives as long as any array made from it.
nb::ndarray<nb::numpy, const float> imageArray(const std::vector<float>& values, const Result& r, size_t perPixel,
                                               nb::handle owner) {
  if (values.empty()) return {};
  const size_t h = size_t(r.image.height), w = size_t(r.image.width);
  if (perPixel == 1) return nb::ndarray<nb::numpy, const float>(values.data(), {h, w}, owner);
  return nb::ndarray<nb::numpy, const float>(values.data(), {h, w, perPixel}, owner);
}

// The scene of a render call: a file (loaded as the CLI loads it) or JSON
// text named `file` (a dict or string from Python; relative paths resolve
// against its folder), with JSON-pointer overrides applied as --set does.
Scene sceneOf(const std::string& source, bool isFile, const std::string& file,
              const std::vector<std::pair<std::string, std::string>>& overrides) {
  if (isFile && overrides.empty()) return loadScene(source);
  const fs::path path = isFile ? fs::path(source) : fs::path(file);
  if (overrides.empty()) return parseScene(source, path);
  nlohmann::json json = isFile ? readSceneJson(source) : nlohmann::json::parse(source, nullptr, true, true);
  std::vector<SceneOverride> applied;
  for (const auto& [pointer, value] : overrides) {
    applied.push_back({pointer, nlohmann::json::parse(value)});
    try {
      applySceneOverride(json, applied.back(), path);
    } catch (const SceneOverrideError& e) {
      throw SceneError(fmt::format("{}: {}: {}", path.string(), pointer, e.what()));
    }
  }
  Scene scene = parseSceneJson(json, path);
  scene.overrides = overridesText(applied);
  return scene;
}

// Calls Python between batches: the caller's progress callback, and the
// check for Ctrl-C, which cancels the render and is raised after it.
class Interrupts {
 public:
  explicit Interrupts(std::function<void(uint64_t, uint64_t)> progress) : progress_(std::move(progress)) {}

  void between(uint64_t done, uint64_t total) {
    nb::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) return stop();
    if (!progress_) return;
    try {
      progress_(done, total);
    } catch (nb::python_error& e) {
      e.restore();
      stop();
    }
  }
  const std::atomic<bool>* cancel() const { return &cancel_; }
  // Raises what stopped the render, if anything did.
  void raiseIfStopped() {
    if (!error_) return;
    PyErr_Restore(error_->type, error_->value, error_->traceback);
    error_.reset();
    throw nb::python_error();
  }

 private:
  struct Error {
    PyObject *type, *value, *traceback;
  };
  void stop() {
    Error e{};
    PyErr_Fetch(&e.type, &e.value, &e.traceback);
    error_ = e;
    cancel_ = true;
  }
  std::function<void(uint64_t, uint64_t)> progress_;
  std::atomic<bool> cancel_{false};
  std::optional<Error> error_;
};

class PySession {
 public:
  explicit PySession(const std::string& device) : session_(std::make_unique<Session>(parseDeviceChoice(device))) {}

  std::string deviceName() const { return open().device().capabilities().name; }
  void close() { session_.reset(); }

  Result render(const std::string& source, bool isFile, const std::string& file,
                const std::vector<std::pair<std::string, std::string>>& overrides, std::optional<uint64_t> beams,
                std::optional<uint64_t> seed, uint64_t firstBeam, bool spectral,
                std::function<void(uint64_t, uint64_t)> progress) {
    RenderJob job;
    job.scene = sceneOf(source, isFile, file, overrides);
    job.beams = beams;
    job.seed = seed;
    job.firstBeam = firstBeam;
    job.outputs.spectral = spectral;
    Interrupts interrupts(std::move(progress));
    job.loop.cancel = interrupts.cancel();
    job.loop.onProgress = [&](uint64_t done, uint64_t total) { interrupts.between(done, total); };
    Session::InMemoryRender done;
    {
      nb::gil_scoped_release released;
      done = open().renderInMemory(job);
    }
    interrupts.raiseIfStopped();
    Result r;
    r.image = std::move(done.result.image);
    r.deviceLabel = done.result.deviceLabel();
    r.aim = job.plan.aim;
    r.seed = job.seedValue();
    r.firstBeam = firstBeam;
    r.beams = done.result.beamsTraced;
    r.seconds = done.result.wallSeconds;
    r.state = std::make_shared<const FilmState>(std::move(done.state));
    r.scene = std::move(job.scene);
    return r;
  }

  Result develop(const std::shared_ptr<const FilmState>& state, bool spectral) {
    Result r;
    RenderResult developed;
    {
      nb::gil_scoped_release released;
      developed = open().developInMemory(*state, spectral, &r.scene);
    }
    r.image = std::move(developed.image);
    r.deviceLabel = developed.deviceLabel();
    r.aim = state->fingerprint.compileOptions.count("aim") ? state->fingerprint.compileOptions.at("aim") : true;
    r.seed = state->fingerprint.seed;
    r.firstBeam = state->ranges.empty() ? 0 : state->ranges.front().first;
    r.beams = state->beams();
    r.state = state;
    return r;
  }

 private:
  const Session& open() const {
    if (!session_) throw std::runtime_error("this Session is closed");
    return *session_;
  }
  std::unique_ptr<Session> session_;
};

void writeResultExr(const Result& r, const std::string& path, bool png) {
  RenderJob job;
  job.scene = r.scene;
  job.output = path;
  job.png = png;
  job.outputs.spectral = !r.image.spectralIrradiance.empty();
  checkOutputPath(job);  // never over the scene or a file it names
  writeRenderImage(job.output, r.image,
                   renderMetadata(r.scene, r.deviceLabel, r.aim, r.seed, r.firstBeam, r.beams, r.seconds), png);
}

// The film's bin counters, (H, W, bins) uint64, or (H, W, bins, 2) with the
// low word first where weighted films count in 128 bits.
nb::ndarray<nb::numpy, const uint64_t> countsOf(const std::shared_ptr<const FilmState>& state, nb::handle owner) {
  const SpectralHistogram& h = state->histogram;
  const std::vector<uint64_t>& counts = h.counts();
  const size_t cells = size_t(h.pixelsX) * h.pixelsY * h.bins;
  const size_t words = cells ? counts.size() / cells : 1;
  if (words == 1)
    return nb::ndarray<nb::numpy, const uint64_t>(counts.data(), {h.pixelsY, h.pixelsX, h.bins}, owner);
  return nb::ndarray<nb::numpy, const uint64_t>(counts.data(), {h.pixelsY, h.pixelsX, h.bins, words}, owner);
}

std::shared_ptr<const FilmState> mergeAll(const std::vector<std::shared_ptr<const FilmState>>& states) {
  if (states.empty()) throw std::invalid_argument("merge needs at least one state");
  FilmState merged = *states.front();
  for (size_t i = 1; i < states.size(); ++i) {
    try {
      merged = mergeStates(merged, *states[i]);
    } catch (const FilmStateError& e) {
      std::string before = "states[0]";
      for (size_t k = 1; k < i; ++k) before += fmt::format(", states[{}]", k);
      throw FilmStateError(fmt::format("cannot merge states[{}] with {}: {}", i, before, e.what()));
    }
  }
  return std::make_shared<const FilmState>(std::move(merged));
}

// SceneError as the Python class of that name (its .file, .pointer and
// .message from the message "<file>: <pointer>: <what>").
void registerErrors() {
  nb::register_exception_translator([](const std::exception_ptr& p, void*) {
    try {
      std::rethrow_exception(p);
    } catch (const SceneError& e) {
      nb::object cls = nb::module_::import_("spectrace").attr("SceneError");
      nb::object error = cls.attr("_from_message")(std::string(e.what()));
      PyErr_SetObject(cls.ptr(), error.ptr());
    } catch (const FilmStateError& e) {
      nb::object cls = nb::module_::import_("spectrace").attr("StateError");
      PyErr_SetString(cls.ptr(), e.what());
    } catch (const OutputError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const ImageIoError& e) {
      PyErr_SetString(PyExc_OSError, e.what());
    } catch (const std::invalid_argument& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const nlohmann::json::exception& e) {
      nb::object cls = nb::module_::import_("spectrace").attr("SceneError");
      nb::object error = cls.attr("_from_message")(std::string("<scene>: /: ") + e.what());
      PyErr_SetObject(cls.ptr(), error.ptr());
    } catch (const std::runtime_error& e) {
      nb::object cls = nb::module_::import_("spectrace").attr("DeviceError");
      PyErr_SetString(cls.ptr(), e.what());
    }
  });
}

}  // namespace
}  // namespace spectrace::python

NB_MODULE(_spectrace, m) {
  using namespace spectrace;
  using namespace spectrace::python;
  m.attr("__version__") = SPECTRACE_VERSION;
  registerErrors();

  nb::class_<FilmState>(m, "_FilmState");

  nb::class_<Result>(m, "_Result")
      .def_prop_ro("xyz", [](nb::handle self) { const Result& r = nb::cast<const Result&>(self); return imageArray(r.image.xyz, r, 3, self); })
      .def_prop_ro("rgb", [](nb::handle self) { const Result& r = nb::cast<const Result&>(self); return imageArray(r.image.rgb, r, 3, self); })
      .def_prop_ro("irradiance", [](nb::handle self) { const Result& r = nb::cast<const Result&>(self); return imageArray(r.image.irradiance, r, 1, self); })
      .def_prop_ro("error", [](nb::handle self) { const Result& r = nb::cast<const Result&>(self); return imageArray(r.image.irradianceError, r, 1, self); })
      .def_prop_ro("spectral", [](nb::handle self) -> nb::object {
        const Result& r = nb::cast<const Result&>(self);
        if (r.image.spectralIrradiance.empty()) return nb::none();
        return nb::cast(imageArray(r.image.spectralIrradiance, r, r.image.spectralBinCentresNm.size(), self));
      })
      .def_prop_ro("wavelengths_nm", [](nb::handle self) -> nb::object {
        const Result& r = nb::cast<const Result&>(self);
        if (r.image.spectralBinCentresNm.empty()) return nb::none();
        return nb::cast(nb::ndarray<nb::numpy, const double>(r.image.spectralBinCentresNm.data(),
                                                             {r.image.spectralBinCentresNm.size()}, self));
      })
      .def_ro("beams", &Result::beams)
      .def_ro("seed", &Result::seed)
      .def_ro("first_beam", &Result::firstBeam)
      .def_ro("seconds", &Result::seconds)
      .def_ro("device", &Result::deviceLabel)
      .def_prop_ro("_state", [](const Result& r) { return r.state; })
      .def("_write_exr", &writeResultExr, nb::arg("path"), nb::arg("png"));

  nb::class_<PySession>(m, "_Session")
      .def(nb::init<const std::string&>(), nb::arg("device"))
      .def_prop_ro("device", &PySession::deviceName)
      .def("close", &PySession::close)
      .def("render", &PySession::render, nb::arg("source"), nb::arg("is_file"), nb::arg("file"), nb::arg("overrides"),
           nb::arg("beams").none(), nb::arg("seed").none(), nb::arg("first_beam"), nb::arg("spectral"),
           nb::arg("progress").none())
      .def("develop", &PySession::develop, nb::arg("state"), nb::arg("spectral"));

  m.def("_load_state", [](const std::string& path) { return std::make_shared<const FilmState>(readFilmState(path)); });
  m.def("_save_state", [](const std::shared_ptr<const FilmState>& s, const std::string& path) {
    writeFilmState(path, *s);
  });
  m.def("_state_beams", [](const std::shared_ptr<const FilmState>& s) { return s->beams(); });
  m.def("_state_ranges", [](const std::shared_ptr<const FilmState>& s) {
    std::vector<std::pair<uint64_t, uint64_t>> ranges;
    for (const BeamRange& r : s->ranges) ranges.emplace_back(r.first, r.count);
    return ranges;
  });
  m.def("_state_counts", [](nb::handle owner, const std::shared_ptr<const FilmState>& s) { return countsOf(s, owner); });
  m.def("_merge", &mergeAll);
  m.def("_devices_json", &describeDevicesJson);
  // An EXR's channels as a result's arrays (for tests that compare with the CLI).
  m.def("_read_exr", [](const std::string& path) {
    Result r;
    r.image = readExr(path).image;
    return r;
  });
}
