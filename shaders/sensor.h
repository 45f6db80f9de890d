// The sensor's side of the kernel: which pixel a beam lands in (the seed's
// Camera.computeBeam(), through the camera's model, camera.h) and what a
// counted beam adds to the film's counters (countBeam), written once for the
// shader and the CPU reference.
#ifndef SPECTRACE_SENSOR_H
#define SPECTRACE_SENSOR_H

// The seed's Camera.computeBeam(): the sensor lies in the plane z = 0 of the
// camera frame and looks along +z, so a beam counts only when it travels
// towards -z from beyond the camera's front plane (the sensor, or a
// model's entrance) and its model lets it through (camera.h) at wavelength
// lambda (nm), with the share `transmission` of its flux. Returns the
// pixel's (column, row), or false for a miss. A beam parallel to the
// sensor (direction.z == 0) never reaches a division; NaN or infinite hit
// points fail the bounds tests.
FN bool hitSensor(vec3 origin, vec3 direction, float lambda, OUT(uvec2) cell, OUT(float) transmission) {
  cell = uvec2(0u, 0u);
  transmission = 0.0f;
  if (!(direction.z < 0.0f) || !(origin.z > constants.cameraFrontZ)) return false;
  vec2 onSensor;
  bool flip;
  if (!cameraCrossing(origin, direction, lambda, onSensor, flip, transmission)) return false;
  vec2 halfSize = constants.sensorHalfSize;
  vec2 pixelsPerMetre = constants.pixelsPerMetre;
  float hx = onSensor.x;
  float hy = onSensor.y;
  if (!(abs(hx) < halfSize.x) || !(abs(hy) < halfSize.y)) return false;
  // Image columns run along +x (camera right) and rows down from +y; an
  // image inverted on the sensor (a pinhole's) is flipped upright.
  PRECISE float fx = flip ? (halfSize.x - hx) * pixelsPerMetre.x : (hx + halfSize.x) * pixelsPerMetre.x;
  PRECISE float fy = flip ? (hy + halfSize.y) * pixelsPerMetre.y : (halfSize.y - hy) * pixelsPerMetre.y;
  uint column = min(uint(max(fx, 0.0f)), constants.pixelsX - 1u);
  uint row = min(uint(max(fy, 0.0f)), constants.pixelsY - 1u);
  cell = uvec2(column, row);
  return true;
}

// The inverse of hitSensor's pixel mapping (camera paths): the point of
// the sensor plane at (column + u, row + v) in pixels of `cell`, for an
// image `flipped` on the sensor or not.
FN vec3 sensorPointInCell(uvec2 cell, float u, float v, bool flipped) {
  vec2 halfSize = constants.sensorHalfSize;
  PRECISE float fx = (float(cell.x) + u) / constants.pixelsPerMetre.x;
  PRECISE float fy = (float(cell.y) + v) / constants.pixelsPerMetre.y;
  PRECISE float hx = flipped ? halfSize.x - fx : fx - halfSize.x;
  PRECISE float hy = flipped ? fy - halfSize.y : halfSize.y - fy;
  return vec3(hx, hy, 0.0f);
}

// A pixel's index, row-major over the whole sensor (beam records).
FN uint pixelOfCell(uvec2 cell, uint pixelsX) { return cell.y * pixelsX + cell.x; }

// The observer's CMF at a wavelength, linear between the table's nodes and
// zero outside.
FN vec3 cmfAtWavelength(float lambda) {
  PRECISE float x = (lambda - constants.cmfLambdaMin) * constants.cmfNodesPerNm;
  vec3 result = vec3(0.0f, 0.0f, 0.0f);
  if (x >= 0.0f && x <= float(constants.cmfCount - 1u)) {
    uint node = min(uint(x), constants.cmfCount - 2u);
    PRECISE float t = x - float(node);
    vec3 a = readCmf(node);
    vec3 b = readCmf(node + 1u);
    PRECISE vec3 c = a + (b - a) * t;
    result = c;
  }
  return result;
}

// `scaled` rounded down or up, up with probability equal to its fraction,
// so the sum is unbiased (to 2^-24 of a unit, the resolution of `u`, a
// uniform in [0, 1)). floor and the subtraction are exact in float.
FN uint64_t roundStochastic(float scaled, float u) {
  // Clamped below 2^63, so the conversion is defined on both sides for any
  // weight (a camera connection's grows as 1 / distance^2).
  PRECISE float whole = floor(min(scaled, 4.0e18f));
  PRECISE float fraction = scaled - whole;
  return uint64_t(whole) + (u < fraction ? 1ul : 0ul);
}

// A CMF value (times the beam's weight ratio) in colour fixed point. The
// scaling by 2^20 is exact.
FN uint64_t colourFixedPoint(float value, float u) {
  PRECISE float scaled = value * kColourFixedPointScale;
  return roundStochastic(scaled, u);
}

// A weighted count (device_shared.h, kWeightUnitsFractional): x * 2^63 in
// two words, for x >= 0. Exact for x >= 2^-39, where the float x * 2^63 is
// an integer: its high word is floor(x * 2^-64 * 2^63), and the rest is
// exact in float (it has no more bits than x). Below, rounded
// stochastically, where roundStochastic's floor and subtraction are exact.
// x is clamped below 2^64 (full-weight beams in one count).
FN WideCount wideFixedPoint(float x, float u) {
  WideCount w;
  PRECISE float scaled = min(x, 1.8e19f) * 9.2233720e18f;  // 2^63: exact
  if (scaled < 16777216.0f) {
    w.low = roundStochastic(scaled, u);
    w.high = 0ul;
    return w;
  }
  PRECISE float high = floor(scaled * 5.4210109e-20f);  // 2^-64: exact
  PRECISE float low = scaled - high * 1.8446744e19f;    // 2^64
  w.low = uint64_t(low);
  w.high = uint64_t(high);
  return w;
}

// Where pixel `cell` (column, row of the sensor) keeps its counters: its
// histogram chunk and its first counter there, in the layout of
// device_shared.h (countersPerPixelOf). False for a pixel outside the
// stored window, which the host proves unreachable (the tests against the
// whole sensor would show a disproof); the guard keeps such a count in
// bounds.
FN bool storedCounters(uvec2 cell, OUT(uint) chunk, OUT(uint) base) {
  uint windowRow = cell.y - constants.windowY0;  // wraps to large when row < windowY0
  uint windowColumn = cell.x - constants.windowX0;
  chunk = 0u;
  base = 0u;
  if (!(windowRow < constants.windowHeight && windowColumn < constants.windowWidth)) return false;
  uint stored = windowRow * constants.windowWidth + windowColumn;
  // One chunk (the usual case, and always on the CPU) needs no division.
  chunk = SPECTRACE_SINGLE_CHUNK ? 0u : stored / constants.pixelsPerChunk;
  base = (stored - chunk * constants.pixelsPerChunk) * constants.countersPerPixel;
  return true;
}

// Adds one count of weight `ratio` at wavelength `lambda` (stored bin
// `bin`) to a pixel's counters: the weight to the bin and its CMF values
// (exact colour), through the includer's addCount and addWideCount. A
// plain film counts hits (every ratio is 1); a weighted one adds wide
// counts (wideFixedPoint).
FN void countInBin(uint chunk, uint base, uint bin, float lambda, float ratio, float spareUniform) {
  bool exactColour = SPECTRACE_EXACT_COLOUR;
  bool weighted = SPECTRACE_WEIGHTED;
  if (weighted) {
    addWideCount(chunk, base + 2u * bin, wideFixedPoint(ratio, spareUniform));
  } else {
    addCount(chunk, base + bin, 1ul);
  }
  if (exactColour) {
    PRECISE vec3 cmf = cmfAtWavelength(lambda) * ratio;
    uint colour = base + colourCounterOffset(constants.bins, weighted);
    if (weighted) {
      addWideCount(chunk, colour, wideFixedPoint(cmf.x, spareUniform));
      addWideCount(chunk, colour + 2u, wideFixedPoint(cmf.y, spareUniform));
      addWideCount(chunk, colour + 4u, wideFixedPoint(cmf.z, spareUniform));
    } else {
      addCount(chunk, colour, colourFixedPoint(cmf.x, spareUniform));
      addCount(chunk, colour + 1u, colourFixedPoint(cmf.y, spareUniform));
      addCount(chunk, colour + 2u, colourFixedPoint(cmf.z, spareUniform));
    }
  }
}

// A weighted film's squared weight of one event (a beam or path reaching
// the pixel once, with all the wavelengths it carries): the square of
// their summed weight, so the film's error estimate sees the wavelengths
// of one event as the one sample they are.
FN void countSquaredWeight(uint chunk, uint base, float square, float spareUniform) {
  if (SPECTRACE_WEIGHTED)
    addWideCount(chunk, base + squaredWeightCounterOffset(constants.bins, SPECTRACE_EXACT_COLOUR),
                 wideFixedPoint(square, spareUniform));
}

// Adds a beam that hit pixel `cell` in stored bin `bin` to the film, with
// its squared weight; false outside the stored window (storedCounters).
FN bool countBeam(uvec2 cell, uint bin, float lambda, float ratio, float spareUniform) {
  uint chunk;
  uint base;
  if (!storedCounters(cell, chunk, base)) return false;
  countInBin(chunk, base, bin, lambda, ratio, spareUniform);
  countSquaredWeight(chunk, base, ratio * ratio, spareUniform);
  return true;
}

// The bin among the stored bins of a wavelength: its bin of the full
// spectrum, then its place among the stored ones (the host stores every bin
// a light can reach, so the clamp never acts).
FN uint storedBinOf(float lambda) {
  uint fullBin = binOfWavelength(lambda, constants.lambdaMin, constants.binsPerNm, constants.totalBins);
  return min(max(fullBin, constants.binOffset) - constants.binOffset, constants.bins - 1u);
}

// What one beam put on the film: how many counts (a beam makes one at the
// camera, and with camera connections one more per diffuse vertex), and its
// last one's pixel, bin and weight ratio (record mode).
struct BeamTally {
  uvec2 cell;
  uint bin;
  uint contributions;
  float ratio;
};

FN BeamTally emptyTally() {
  BeamTally tally;
  tally.cell = uvec2(0u, 0u);
  tally.bin = 0u;
  tally.contributions = 0u;
  tally.ratio = 0.0f;
  return tally;
}

// One count of a beam: added to the film, or, in record mode, only noted.
FN void contribute(INOUT(BeamTally) tally, uvec2 cell, uint bin, float lambda, float ratio, float spareUniform) {
  // (The squared-weight counter gets each count's own square: with camera
  // connections one beam may count twice in one pixel, whose cross term it
  // lacks, so the film's error estimate is then a lower bound.)
  bool counted = true;
  if (SPECTRACE_RECORDING) tally.ratio = ratio;
  else counted = countBeam(cell, bin, lambda, ratio, spareUniform);
  if (counted) {
    tally.cell = cell;
    tally.bin = bin;
    tally.contributions += 1u;
  }
}

#endif  // SPECTRACE_SENSOR_H
