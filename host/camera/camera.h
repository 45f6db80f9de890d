#pragma once
// The camera as a scene describes it: a sensor, and what stands in front of
// it (its model: nothing, a pinhole, ...). Lengths in metres, world
// coordinates in double.
//
// Each kind of camera model is one unit: host/camera/<kind>_camera.cpp (its
// JSON keys, checks, the kernel's constants, its aim target, where on the
// sensor beams from a light can land, why a beam cannot enter it) beside the
// kernel's shaders/cameras/<kind>.h (where a beam crosses the sensor, a
// camera connection's point); camera_types.cpp is the only table of them.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "device_data/scene_data.h"
#include "device_shared.h"

namespace spectrace {

// The sphere every counted beam passes through: the camera model's entrance
// (a pinhole's disk, or the bare sensor). Aiming (lights/light_shared.h)
// sends beams only towards it.
struct EntranceSphere {
  glm::dvec3 centre;
  double radius;
};

// Where an emitter can send beams from, conservatively, in the camera frame:
// the corners of a convex region holding its emission points, and for a
// collimated emitter (a laser) its beam.
struct EmitterReach {
  std::vector<glm::dvec3> corners;
  bool collimated = false;
  glm::dvec3 centre{0.0}, axis{0.0};
  double radius = 0.0;
};

// A rectangle of the sensor plane (camera frame, metres).
struct SensorBox {
  glm::dvec2 lo, hi;
};

// How a model's `validate` reports a problem: throws SceneError naming the
// field (`key` relative to the camera, e.g. "pinhole/radius_m").
class CameraFieldCheck {
 public:
  virtual ~CameraFieldCheck() = default;
  [[noreturn]] virtual void fail(const std::string& key, const std::string& what) const = 0;
  // For "(got ...)": the value as the scene file wrote it, else `fallback`.
  virtual std::string got(const std::string& key, double fallback) const = 0;
  // Fails unless `value` is a length in metres within the world bounds.
  virtual void checkLength(const std::string& key, double value) const = 0;
  // The scene's spectrum range (nm), over which a glass must have an index.
  virtual double spectrumMinNm() const = 0;
  virtual double spectrumMaxNm() const = 0;
};

struct Camera;

// What stands in front of the sensor. Immutable; shared between copies of a
// scene.
class CameraModel {
 public:
  virtual ~CameraModel() = default;
  // Its value checks; the scene's are validateScene's.
  virtual void validate(const CameraFieldCheck& check) const = 0;
  // The kernel's camera constants: cameraType, cameraFrontZ, cameraParams,
  // and any tables appended to the scene data (cameraDataFirst).
  virtual void pack(device::TraceConstants& constants, SceneData& data) const = 0;
  // The plane a counted beam comes from beyond (camera frame z: the aperture
  // plane; 0: the sensor), and its name in messages.
  virtual double frontZ() const = 0;
  virtual const char* frontName() const = 0;
  // Why a collimated beam crossing the front plane within `reach` of
  // `centre` can never enter the camera, or "".
  virtual std::string beamMissesBecause(const Camera& camera, const glm::dvec2& centre, double reach) const = 0;
  virtual EntranceSphere entranceSphere(const Camera& camera) const = 0;
  // Where on the sensor plane beams from `emitter` can land (nullopt: no
  // bound), and whether the image is turned upright (a pinhole's is
  // inverted on the sensor).
  virtual std::optional<SensorBox> reachOnSensor(const EmitterReach& emitter) const = 0;
  virtual bool imageFlipped() const = 0;
  // Camera paths (shaders/camera_path.h) start at a uniform point of a
  // pixel and of the model's entrance, a disk parallel to the sensor at
  // frontZ (cameraConnectionPoint): the entrance's area, or nullopt for a
  // model that starts none (the bare sensor, where light paths measure the
  // irradiance they are best at).
  virtual std::optional<double> cameraPathEntranceAreaM2() const = 0;
  // Why a model without that entrance starts none (the estimator note).
  virtual std::string cameraPathsAbsentBecause() const { return ""; }
  // The files the model was read from (a lens file), which a render's
  // state records with the scene's other files.
  virtual std::vector<std::filesystem::path> files() const { return {}; }
  // The smallest angle (its sine) under which a light may see the entrance
  // (entranceSphere) for the model to tell beams that pass from beams that
  // miss; 0: any.
  virtual double smallestEntranceSine() const = 0;
};

// The model of a camera with nothing before its sensor (camera/bare_sensor_camera.cpp).
std::shared_ptr<const CameraModel> bareSensorModel();

struct Camera {
  glm::dvec3 position{0.0};
  glm::dvec3 lookAt{0.0, 0.0, 1.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double sensorWidthM = 0.036;
  double sensorHeightM = 0.024;
  int pixelsX = 360;
  int pixelsY = 240;
  std::shared_ptr<const CameraModel> model = bareSensorModel();
  double exposureS = 1.0;
};

}  // namespace spectrace
