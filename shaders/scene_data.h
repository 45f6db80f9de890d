// Reading the scene data (device_shared.h): 32-bit words by offset, floats
// as their bits. The includer provides readSceneWord (kernel_interface.h).
#ifndef SPECTRACE_SCENE_DATA_H
#define SPECTRACE_SCENE_DATA_H

FN float readSceneFloat(uint word) { return uintBitsToFloat(readSceneWord(word)); }

#endif  // SPECTRACE_SCENE_DATA_H
