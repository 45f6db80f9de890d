// Transport: what happens to a beam between its light and the camera when
// the scene has objects (objects.h). The beam goes from surface to surface,
// each meeting ("bounce") with its own Philox block (device_shared.h:
// kRngBlockBounce), until the camera counts or absorbs it, it leaves the
// scene, a surface absorbs it, or it meets more than maxBounces surfaces.
//
// Beams carry flux, so scattering is analog and keeps the weight: a
// surface of reflectance rho reflects a beam with probability rho (Russian
// roulette with the exact survival probability, unbiased), a dielectric
// reflects with the Fresnel probability and refracts otherwise. Camera
// connections carry fractional weights (as aimed area lights do, which
// scenes whose objects are all absorbers keep).
#ifndef SPECTRACE_TRANSPORT_H
#define SPECTRACE_TRANSPORT_H

// A material's reflectance at a wavelength: linear between its table's
// nodes, holding the end values outside.
FN float reflectanceAt(Material m, float lambda) {
  PRECISE float x = (lambda - m.reflectanceLambda0) * m.reflectanceNodesPerNm;
  float last = float(m.reflectanceCount - 1u);
  float clamped = min(max(x, 0.0f), last);
  uint node = min(uint(clamped), m.reflectanceCount > 1u ? m.reflectanceCount - 2u : 0u);
  float a = readSceneFloat(m.reflectanceFirst + node);
  float b = m.reflectanceCount > 1u ? readSceneFloat(m.reflectanceFirst + node + 1u) : a;
  PRECISE float t = clamped - float(node);
  PRECISE float value = a + (b - a) * t;
  return value;
}

// The Sellmeier index at a wavelength (nm); the host keeps poles out of the
// spectrum range.
FN float refractiveIndexAt(Material m, float lambda) {
  // A constant index (every C zero) exactly, without the float rounding of
  // B l^2 / l^2: no dispersion, as colour from the bins assumes.
  if (m.sellmeierC.x == 0.0f && m.sellmeierC.y == 0.0f && m.sellmeierC.z == 0.0f) {
    PRECISE float constant = 1.0f + m.sellmeierB.x + m.sellmeierB.y + m.sellmeierB.z;
    return sqrt(constant);
  }
  PRECISE float l = lambda * 0.001f;
  PRECISE float l2 = l * l;
  PRECISE float n2 = 1.0f + m.sellmeierB.x * l2 / (l2 - m.sellmeierC.x) + m.sellmeierB.y * l2 / (l2 - m.sellmeierC.y) +
                     m.sellmeierB.z * l2 / (l2 - m.sellmeierC.z);
  return sqrt(n2);
}

// Unpolarised Fresnel reflectance for eta = n_incident / n_transmitted.
FN float fresnelDielectric(float cosIncident, float cosTransmitted, float eta) {
  PRECISE float rs = (eta * cosIncident - cosTransmitted) / (eta * cosIncident + cosTransmitted);
  PRECISE float rp = (cosIncident - eta * cosTransmitted) / (cosIncident + eta * cosTransmitted);
  PRECISE float f = 0.5f * (rs * rs + rp * rp);
  return f;
}

FN vec3 reflected(vec3 direction, vec3 n) {
  PRECISE vec3 r = direction - n * (2.0f * dot3(direction, n));
  return r;
}

// Light tracing's camera connection (pbrt-v4's lightpath, Mitsuba 3's
// ptracer): from a diffuse vertex at `point`, lit from the side `facing`,
// to a uniform point of the camera model's entrance (camera.h: a pinhole's
// disk, a bare sensor's own area). The beam's flux times the BRDF
// (rho / pi), the geometry term and the entrance's area is what reaches
// that point, and it goes on straight to the sensor. Counted when nothing
// stands in between.
FN void connectToCamera(uint64_t beamIndex, uint bounce, vec3 point, vec3 facing, float weight, float lambda, uint bin,
                        INOUT(BeamTally) tally) {
  if (!(weight > 0.0f) || !(point.z > constants.cameraFrontZ)) return;
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
  if (!hitSensor(point, direction, cell)) return;
  ObjectHit blocker;
  vec3 start = offsetOffSurface(point, facing);
  PRECISE float reach = distance * 0.99999f;
  if (intersectObjects(start, direction, reach, true, blocker)) return;
  PRECISE float ratio = weight * (1.0f / 3.14159265358979f) * cosSurface * cosCamera * area / distanceSq;
  contribute(tally, cell, bin, lambda, ratio, uniformFromWord(words.z));
}

// The beam from its light (origin, direction, weight ratio), with its
// wavelength, through the scene's objects to the camera.
FN void transportBeam(uint64_t beamIndex, vec3 origin, vec3 direction, float ratio, float lambda, float spareUniform,
                      INOUT(BeamTally) tally) {
  uint bin = storedBinOf(lambda);
  bool connect = constants.connect != 0u;
  bool afterDiffuse = false;
  for (uint bounce = 0u; bounce <= constants.maxBounces; ++bounce) {
    ObjectHit hit;
    bool metObject = intersectObjects(origin, direction, 3.0e38f, false, hit);
    bool counted;
    uvec2 cell;
    float toCamera = intersectCamera(origin, direction, counted, cell);
    if (toCamera >= 0.0f && (!metObject || toCamera <= hit.t)) {
      // A beam straight from a diffuse vertex is the connection's (counted
      // there), so analog counts take the others only.
      if (counted && ratio > 0.0f && !(connect && afterDiffuse))
        contribute(tally, cell, bin, lambda, ratio, spareUniform);
      return;
    }
    if (!metObject || bounce == constants.maxBounces) return;
    Primitive surface = readPrimitive(hit.primitive);
    Material material = readMaterial(surface.material);
    if (material.type == kMaterialAbsorber) return;
    PRECISE vec3 found = origin + direction * hit.t;
    vec3 n = primitiveNormal(surface, found);
    vec3 point = pointOnSurface(surface, found, n);
    bool fromOutside = dot3(direction, n) < 0.0f;
    vec3 facing = fromOutside ? n : -n;  // towards the side the beam came from
    uvec4 words = philox4x32(constants.seed, beamIndex, kRngBlockBounce + 2u * bounce);
    float choice = uniformFromWord(words.x);
    if (material.type == kMaterialDiffuse) {
      float rho = reflectanceAt(material, lambda);
      if (connect) connectToCamera(beamIndex, bounce, point, facing, rho * ratio, lambda, bin, tally);
      if (!(choice < rho)) return;
      vec3 tangent;
      vec3 bitangent;
      frameAround(facing, tangent, bitangent);
      direction = toFrame(sampleCosineHemisphere(uniformFromWord(words.y), uniformFromWord(words.z)), tangent,
                          bitangent, facing);
      origin = offsetOffSurface(point, facing);
      afterDiffuse = true;
    } else if (material.type == kMaterialMirror) {
      if (!(choice < reflectanceAt(material, lambda))) return;
      direction = reflected(direction, facing);
      origin = offsetOffSurface(point, facing);
      afterDiffuse = false;
    } else {
      float index = refractiveIndexAt(material, lambda);
      PRECISE float eta = fromOutside ? 1.0f / index : index;
      PRECISE float cosIncident = -dot3(direction, facing);
      PRECISE float sinSqTransmitted = eta * eta * max(1.0f - cosIncident * cosIncident, 0.0f);
      bool total = sinSqTransmitted >= 1.0f;  // total internal reflection
      PRECISE float cosTransmitted = total ? 0.0f : sqrt(1.0f - sinSqTransmitted);
      float fresnel = total ? 1.0f : fresnelDielectric(cosIncident, cosTransmitted, eta);
      if (choice < fresnel) {
        direction = reflected(direction, facing);
        origin = offsetOffSurface(point, facing);
      } else {
        PRECISE vec3 refracted = direction * eta + facing * (eta * cosIncident - cosTransmitted);
        PRECISE vec3 unit = refracted * (1.0f / sqrt(dot3(refracted, refracted)));
        direction = unit;
        origin = offsetOffSurface(point, -facing);
      }
      afterDiffuse = false;
    }
  }
}

#endif  // SPECTRACE_TRANSPORT_H
