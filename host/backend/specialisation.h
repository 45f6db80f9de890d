#pragma once
// Which scene features the trace pipeline is specialised to (compiled for
// the scene's value through a specialisation constant, device_shared.h
// kSpec*); the others are decided at run time, as in the general pipeline.
#include <cstdint>

namespace spectrace {

enum SpecialisedFeature : uint32_t {
  kSpecialiseNone = 0,
  kSpecialiseLightTypes = 1u << 0,   // code for absent light types compiled out
  kSpecialiseLightChoice = 1u << 1,  // no light choice with one light
  kSpecialiseCameraType = 1u << 2,   // the camera model's branch fixed
  kSpecialiseExactColour = 1u << 3,  // per-beam colour path fixed on or off
  kSpecialiseAim = 1u << 4,          // aiming code compiled out when no light is aimed
  // The light, interval, CMF and alias tables read from uniform buffers
  // when they fit (host/backend/uniform_tables.h); not a scene feature, but
  // like one it is fixed at compile time, and the general pipeline keeps
  // the storage-buffer path it is checked against.
  kSpecialiseUniformTables = 1u << 5,
  // Code for absent primitive and material types compiled out (a shader's
  // branches all run on lavapipe, taken or not).
  kSpecialiseObjectTypes = 1u << 6,
  kSpecialiseAll = (1u << 7) - 1,
};

}  // namespace spectrace
