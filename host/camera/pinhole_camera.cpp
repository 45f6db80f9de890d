// The pinhole: an aperture disk in front of the sensor. A beam counts when
// it crosses the aperture plane inside the disk and then the sensor; its
// image is inverted on the sensor, so it is turned upright.
// shaders/cameras/pinhole.h is its kernel.
#include "camera/pinhole_camera.h"

#include "camera/camera_types.h"
#include "camera/entrance_disk_model.h"
#include "camera/world_limits.h"
#include "device_shared.h"

namespace spectrace {
namespace {

namespace jf = json_fields;

class PinholeModel final : public EntranceDiskModel {
 public:
  explicit PinholeModel(const Pinhole& p) : EntranceDiskModel(p.distanceM, p.radiusM, 1.0, "pinhole"), pinhole_(p) {}
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
  const char* frontName() const override { return "the pinhole's aperture plane"; }

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
