// The thin lens: an ideal lens disk at distance s in front of the sensor,
// focused at d (1/f = 1/d + 1/s). A beam that crosses the lens plane inside
// the disk at p, with slope m = direction.xy / -direction.z, leaves towards
// the point where the lens's chief ray of slope m meets the focal plane,
// so it lands on the sensor at
//   p (1 - s/f) + s m  =  -p s/d + s m,
// which is the pinhole's crossing when p = 0, and is p-independent (in
// focus) exactly for the beams from a point at distance d. Every beam
// through the disk reaches the sensor with all its flux; the lens is not
// dispersive. The image is inverted on the sensor, so it is turned
// upright. shaders/cameras/thin_lens.h is its kernel.
#include "camera/thin_lens_camera.h"

#include <cmath>

#include <fmt/format.h>

#include "camera/camera_types.h"
#include "camera/entrance_disk_model.h"
#include "camera/world_limits.h"
#include "device_shared.h"

namespace spectrace {
namespace {

namespace jf = json_fields;

class ThinLensModel final : public EntranceDiskModel {
 public:
  // k = 1 - s/f = -s/d: the lens point's share of where a beam lands.
  explicit ThinLensModel(const ThinLens& lens)
      : EntranceDiskModel(lens.lensDistanceM(), lens.apertureRadiusM, -lens.lensDistanceM() / lens.focusDistanceM,
                          "thin lens"),
        lens_(lens) {}
  const ThinLens& lens() const { return lens_; }

  void validate(const CameraFieldCheck& check) const override {
    check.checkLength("thin_lens/focal_length_m", lens_.focalLengthM);
    check.checkLength("thin_lens/aperture_radius_m", lens_.apertureRadiusM);
    check.checkLength("thin_lens/focus_distance_m", lens_.focusDistanceM);
    if (!(lens_.focusDistanceM > lens_.focalLengthM))
      check.fail("thin_lens/focus_distance_m",
                 fmt::format("must exceed focal_length_m ({} m): an object at or inside the focal length has no real "
                             "image to focus on the sensor (got {})",
                             lens_.focalLengthM, check.got("thin_lens/focus_distance_m", lens_.focusDistanceM)));
    const double s = lens_.lensDistanceM();
    if (!(std::isfinite(s) && s <= kMaxCoordinateM))
      check.fail("thin_lens/focus_distance_m",
                 fmt::format("puts the lens {} m from the sensor, beyond the world's bounds (got {})", s,
                             check.got("thin_lens/focus_distance_m", lens_.focusDistanceM)));
  }
  // cameraParams.x: the aperture's radius squared; .y: the lens point's
  // coefficient in the crossing, 1 - s/f = -s/d (computed in double).
  void pack(device::TraceConstants& c, SceneData&) const override {
    c.cameraType = device::kCameraThinLens;
    c.cameraFrontZ = float(frontZ());
    c.cameraParams = glm::vec4(float(radiusM() * radiusM()), float(k()), 0.0f, 0.0f);
  }
  const char* frontName() const override { return "the thin lens's plane"; }

 private:
  ThinLens lens_;
};

std::shared_ptr<const CameraModel> parse(const jf::Source& c, const jf::Json& v, const std::string& ptr) {
  jf::checkObject(c, v, ptr, {"focal_length_m", "aperture_radius_m", "focus_distance_m"}, "camera.thin_lens");
  ThinLens lens;
  const auto length = [&](const char* key) {
    return jf::getLength(c, jf::require(c, v, ptr, key), jf::child(ptr, key), kMaxCoordinateM);
  };
  lens.focalLengthM = length("focal_length_m");
  lens.apertureRadiusM = length("aperture_radius_m");
  lens.focusDistanceM = length("focus_distance_m");
  return thinLensModel(lens);
}

}  // namespace

std::shared_ptr<const CameraModel> thinLensModel(const ThinLens& lens) {
  return std::make_shared<ThinLensModel>(lens);
}

const ThinLens* thinLensOf(const Camera& camera) {
  const auto* model = dynamic_cast<const ThinLensModel*>(camera.model.get());
  return model ? &model->lens() : nullptr;
}

const CameraTypeUnit& thinLensCameraUnit() {
  static const CameraTypeUnit unit{"thin_lens", parse};
  return unit;
}

}  // namespace spectrace
