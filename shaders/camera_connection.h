// The camera connection a material's unit may make at its vertex
// (materials/diffuse.h), before the beam goes on: transport.h's loop counts
// the beams that reach the camera themselves.
#ifndef SPECTRACE_CAMERA_CONNECTION_H
#define SPECTRACE_CAMERA_CONNECTION_H

// Light tracing's camera connection (pbrt-v4's lightpath, Mitsuba 3's
// ptracer): from a diffuse vertex at `point`, lit from the side `facing`,
// to a uniform point of the camera model's entrance (camera.h: a pinhole's
// disk, a bare sensor's own area). The beam's flux (`ratio` times each
// wavelength's share) times the BRDF (rho / pi), the geometry term and the
// entrance's area is what reaches that point, and it goes on straight to
// the sensor (through a lens system, deterministically: the share its
// surfaces transmit, `transmission`, weights the count, so the estimator
// stays unbiased with no roulette). Counted when nothing stands in between.
FN void connectToCamera(uint64_t beamIndex, uint bounce, vec3 point, vec3 facing, float ratio, WavelengthFactors rho,
                        PathWavelengths w, INOUT(BeamTally) tally) {
  keepWavelengthsThroughCamera(w);
  WavelengthFactors weight;
  bool any = false;
  for (uint j = 0u; j < kMaxWavelengthsPerPath; ++j) {
    PRECISE float carried = rho.value[j] * ratio * w.share[j];
    weight.value[j] = carried;
    any = any || carried > 0.0f;
  }
  if (!any || !(point.z > constants.cameraFrontZ)) return;
  uvec4 words = philox4x32(constants.seed, beamIndex, kRngBlockBounce + 2u * bounce + 1u);
  float area;
  vec3 target = cameraConnectionPoint(uniformFromWord(words.x), uniformFromWord(words.y), area);
  PRECISE vec3 toTarget = target - point;
  PRECISE float distanceSq = dot3(toTarget, toTarget);
  PRECISE float distance = sqrt(distanceSq);
  PRECISE vec3 direction = toTarget * (1.0f / distance);
  float cosSurface = dot3(direction, facing);
  float cosCamera = -direction.z;
  if (!(cosSurface > 0.0f) || !(cosCamera > 0.0f)) return;
  uvec2 cell;
  float transmission;
  if (!hitSensor(point, direction, w.lambda[0], cell, transmission)) return;
  ObjectHit blocker;
  vec3 start = offsetOffSurface(point, facing);
  PRECISE float reach = distance * 0.99999f;
  if (intersectObjects(start, direction, reach, true, blocker)) return;
  WavelengthFactors count;
  for (uint j = 0u; j < kMaxWavelengthsPerPath; ++j) {
    PRECISE float c =
        weight.value[j] * (1.0f / 3.14159265358979f) * cosSurface * cosCamera * area / distanceSq * transmission;
    count.value[j] = c;
  }
  contributeCounts(tally, cell, w, count, uniformFromWord(words.z));
}

#endif  // SPECTRACE_CAMERA_CONNECTION_H
