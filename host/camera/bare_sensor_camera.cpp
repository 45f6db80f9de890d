// The bare sensor: nothing before it. Beams count where they cross the
// sensor plane from in front; shaders/cameras/bare_sensor.h is its kernel.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "camera/camera.h"
#include "device_shared.h"

namespace spectrace {
namespace {

class BareSensorModel final : public CameraModel {
 public:
  void validate(const CameraFieldCheck&) const override {}
  void pack(device::TraceConstants& c, SceneData&) const override {
    c.cameraType = device::kCameraBareSensor;
    c.cameraFrontZ = 0.0f;
  }
  double frontZ() const override { return 0.0; }
  const char* frontName() const override { return "the sensor plane"; }
  std::string beamMissesBecause(const Camera& camera, const glm::dvec2& centre, double reach) const override {
    const glm::dvec2 half(0.5 * camera.sensorWidthM, 0.5 * camera.sensorHeightM);
    const glm::dvec2 outside = glm::max(glm::abs(centre) - half, glm::dvec2(0.0));
    if (!(glm::length(outside) < reach)) return "its beam misses the sensor";
    return "";
  }
  // The sensor's half diagonal about its centre.
  EntranceSphere entranceSphere(const Camera& camera) const override {
    return {{0.0, 0.0, 0.0}, 0.5 * std::hypot(camera.sensorWidthM, camera.sensorHeightM)};
  }
  // Only a collimated beam is bounded: its footprint lies within R / |a.z|
  // of where its axis meets the sensor.
  std::optional<SensorBox> reachOnSensor(const EmitterReach& emitter) const override {
    if (!emitter.collimated || !(emitter.axis.z < 0.0)) return std::nullopt;
    const double t = emitter.centre.z / -emitter.axis.z;
    const glm::dvec2 centre(emitter.centre.x + t * emitter.axis.x, emitter.centre.y + t * emitter.axis.y);
    const double extent = emitter.radius / -emitter.axis.z;
    return SensorBox{centre - extent, centre + extent};
  }
  bool imageFlipped() const override { return false; }
  std::optional<double> cameraPathEntranceAreaM2() const override { return std::nullopt; }
  std::string cameraPathsAbsentBecause() const override {
    return "the bare sensor starts no camera paths (they need a pinhole or a lens)";
  }
  // Beams land on the plane whatever its size (a spot 1e6 m from a 1 mm
  // sensor matches its closed form: geometry_numerics_test).
  double smallestEntranceSine() const override { return 0.0; }
};

}  // namespace

std::shared_ptr<const CameraModel> bareSensorModel() {
  static const std::shared_ptr<const CameraModel> model = std::make_shared<BareSensorModel>();
  return model;
}

}  // namespace spectrace
