// The pinhole: an aperture disk in front of the sensor. A beam counts when
// it crosses the aperture plane inside the disk and then the sensor; its
// image is inverted on the sensor, so it is turned upright.
// shaders/cameras/pinhole.h is its kernel.
#include "camera/pinhole_camera.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "camera/camera_types.h"
#include "camera/world_limits.h"
#include "device_shared.h"

namespace spectrace {
namespace {

namespace jf = json_fields;

class PinholeModel final : public CameraModel {
 public:
  explicit PinholeModel(const Pinhole& p) : pinhole_(p) {}
  const Pinhole& pinhole() const { return pinhole_; }

  void validate(const CameraFieldCheck& check) const override {
    check.checkLength("pinhole/distance_m", pinhole_.distanceM);
    check.checkLength("pinhole/radius_m", pinhole_.radiusM);
  }
  // cameraParams.x: the aperture's radius squared.
  void pack(device::TraceConstants& c, SceneData&) const override {
    c.cameraType = device::kCameraPinhole;
    c.cameraFrontZ = float(pinhole_.distanceM);
    c.cameraParams = glm::vec4(float(pinhole_.radiusM * pinhole_.radiusM), 0.0f, 0.0f, 0.0f);
  }
  double frontZ() const override { return pinhole_.distanceM; }
  const char* frontName() const override { return "the pinhole's aperture plane"; }
  std::string beamMissesBecause(const Camera&, const glm::dvec2& centre, double reach) const override {
    if (!(glm::length(centre) < reach + pinhole_.radiusM)) return "its beam misses the pinhole";
    return "";
  }
  EntranceSphere entranceSphere(const Camera&) const override {
    return {{0.0, 0.0, pinhole_.distanceM}, pinhole_.radiusM};
  }
  // A beam from P (height h = P.z - D > 0) through the aperture point A
  // hits H = A (1 + D/h) - P_xy D/h, inside the disk about -P_xy D/h of
  // radius r (1 + D/h). Over a convex emitter with h > 0 throughout,
  // -P_xy D/h stays in the hull of its corners' images (a perspective map
  // keeps segments straight), and 1 + D/h <= 1 + D/h_min.
  std::optional<SensorBox> reachOnSensor(const EmitterReach& emitter) const override {
    const double d = pinhole_.distanceM, r = pinhole_.radiusM;
    glm::dvec2 lo(INFINITY), hi(-INFINITY);
    double hMin = INFINITY;
    for (const glm::dvec3& p : emitter.corners) {
      const double h = p.z - d;
      if (!(h > 0.0)) return std::nullopt;  // part of the emitter at or behind the aperture plane
      hMin = std::min(hMin, h);
      const glm::dvec2 centre = -glm::dvec2(p.x, p.y) * (d / h);
      lo = glm::min(lo, centre);
      hi = glm::max(hi, centre);
    }
    const double blur = r * (1.0 + d / hMin);
    return SensorBox{lo - blur, hi + blur};
  }
  bool imageFlipped() const override { return true; }
  std::optional<double> cameraPathEntranceAreaM2() const override {
    return M_PI * pinhole_.radiusM * pinhole_.radiusM;
  }
  // Ten times the slack (4e-7, shaders/beam_math.h: SPECTRACE_AIM_SLACK)
  // by which float rounding widens aimed cones. Below it, whether a beam
  // passes the disk is decided by the rounding of float positions and
  // directions (about 6e-8 of the distance) rather than by the disk: a
  // 1e-9 m pinhole at 1.1 m gave 85 times its irradiance, 1e-7 m 1.16.
  double smallestEntranceSine() const override { return 4.0e-6; }

 private:
  Pinhole pinhole_;
};

std::shared_ptr<const CameraModel> parse(const jf::Source& c, const jf::Json& v, const std::string& ptr) {
  jf::checkObject(c, v, ptr, {"distance_m", "radius_m"}, "camera.pinhole");
  Pinhole p;
  p.distanceM = jf::getLength(c, jf::require(c, v, ptr, "distance_m"), jf::child(ptr, "distance_m"), kMaxCoordinateM);
  p.radiusM = jf::getLength(c, jf::require(c, v, ptr, "radius_m"), jf::child(ptr, "radius_m"), kMaxCoordinateM);
  return pinholeModel(p);
}

}  // namespace

std::shared_ptr<const CameraModel> pinholeModel(const Pinhole& pinhole) {
  return std::make_shared<PinholeModel>(pinhole);
}

const Pinhole* pinholeOf(const Camera& camera) {
  const auto* model = dynamic_cast<const PinholeModel*>(camera.model.get());
  return model ? &model->pinhole() : nullptr;
}

const CameraTypeUnit& pinholeCameraUnit() {
  static const CameraTypeUnit unit{"pinhole", parse};
  return unit;
}

}  // namespace spectrace
