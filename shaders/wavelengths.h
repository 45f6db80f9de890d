// The wavelengths a path carries (hero wavelength sampling; Wilkie et al.,
// EGSR 2014, and pbrt-v4's SampledWavelengths): k of them from the light's
// own table, each counted with 1/k of the path's weight.
//
// k = 1 draws through the alias columns (emit.h: drawWavelength). k = 2 or
// 4 takes the 64-bit uniform u and its rotations u + j 2^64/k through the
// table's integer CDF (intervalOfUniform): each rotation is a
// uniform, so each wavelength is drawn from the light's table exactly as a
// lone one is (the same interval probabilities, the same position inside),
// and the estimate (1/k) sum_j f(lambda_j) / p(lambda_j) is unbiased; the
// rotations are equal steps of the CDF, so the k wavelengths are stratified
// over the light's spectrum (for Y under D65 over 360-830 nm this takes the
// variance per path from 1.7 to 0.002 of the mean squared at k = 4).
#ifndef SPECTRACE_WAVELENGTHS_H
#define SPECTRACE_WAVELENGTHS_H

struct PathWavelengths {
  float lambda[kMaxWavelengthsPerPath];
  uint bin[kMaxWavelengthsPerPath];  // stored bins
  // What each wavelength carries of the path's weight: 1/k at the start,
  // times what surfaces keep of it (surviveReflectance); after a
  // wavelength-dependent event ended the others, k times that for the hero
  // (index 0) and 0 for them. 0: not carried.
  float share[kMaxWavelengthsPerPath];
};

// A factor per wavelength (a reflectance at each).
struct WavelengthFactors {
  float value[kMaxWavelengthsPerPath];
};

// The interval of `light`'s table that the 64-bit uniform u falls in by
// the table's integer CDF: the last whose cdfLow <= u (the first's is 0).
// An interval of probability 0 shares its cdfLow with the next one, so it
// is never the last: never drawn.
FN uint intervalOfUniform(LightRecord light, uint64_t u) {
  uint low = 0u;
  uint count = light.spectralCount;
  while (count > 1u) {
    uint halfCount = count / 2u;
    if (readInterval(light.spectralFirst + low + halfCount).cdfLow <= u) {
      low += halfCount;
      count -= halfCount;
    } else {
      count = halfCount;
    }
  }
  return light.spectralFirst + low;
}

// k wavelengths of `light` from a 64-bit uniform and a position uniform.
FN PathWavelengths drawPathWavelengths(LightRecord light, uint64_t intervalUniform, float positionUniform, uint k) {
  PathWavelengths w;
  for (uint j = 0u; j < kMaxWavelengthsPerPath; ++j) {
    w.lambda[j] = 0.0f;
    w.bin[j] = 0u;
    w.share[j] = 0.0f;
  }
  if (k <= 1u) {
    w.lambda[0] = drawWavelength(light, intervalUniform, positionUniform);
    w.bin[0] = storedBinOf(w.lambda[0]);
    w.share[0] = 1.0f;
    return w;
  }
  uint64_t step = 0xFFFFFFFFFFFFFFFFul / uint64_t(k) + 1ul;  // 2^64 / k, k a power of two
  float share = 1.0f / float(k);                            // exact: k is a power of two
  for (uint j = 0u; j < k; ++j) {
    SpectralInterval interval = readInterval(intervalOfUniform(light, intervalUniform + uint64_t(j) * step));
    w.lambda[j] = wavelengthInInterval(interval.lambda0, interval.width, interval.slope, positionUniform);
    w.bin[j] = storedBinOf(w.lambda[j]);
    w.share[j] = share;
  }
  return w;
}

// A wavelength-dependent event (a dispersive surface) keeps the hero only:
// with the others ended, the hero alone is a draw from the light's table,
// so its share is k times its 1/k (exact: k is a power of two). Once only:
// the ended wavelengths are marked by lambda 0 (no light emits there), so
// a later dispersive surface (a prism's second face) leaves the share be.
FN void keepHeroOnly(INOUT(PathWavelengths) w, uint k) {
  if (w.lambda[1] == 0.0f) return;
  PRECISE float hero = w.share[0] * float(k);
  for (uint j = 1u; j < kMaxWavelengthsPerPath; ++j) {
    w.share[j] = 0.0f;
    w.lambda[j] = 0.0f;
  }
  w.share[0] = hero;
}

// A camera whose crossing depends on the wavelength (camera.h:
// cameraDisperses, a lens system's glass) keeps the hero only, as a
// dispersive surface does: the others would land on other pixels.
FN void keepWavelengthsThroughCamera(INOUT(PathWavelengths) w) {
  if (cameraDisperses() && constants.wavelengthsPerPath > 1u) keepHeroOnly(w, constants.wavelengthsPerPath);
}

// Russian roulette at a surface that keeps each wavelength's share times
// its reflectance rho_j: on with probability p = the largest rho_j of the
// carried wavelengths (the hero's when it is the only one), each share
// then times rho_j / p. Unbiased for every wavelength; false: ended.
FN bool surviveReflectance(WavelengthFactors rho, float choice, INOUT(PathWavelengths) w) {
  float p = 0.0f;
  for (uint j = 0u; j < kMaxWavelengthsPerPath; ++j)
    if (w.share[j] > 0.0f) p = max(p, rho.value[j]);
  if (!(choice < p)) return false;
  for (uint j = 0u; j < kMaxWavelengthsPerPath; ++j) {
    PRECISE float kept = w.share[j] * (rho.value[j] / p);
    w.share[j] = kept;
  }
  return true;
}

// One event's counts at pixel `cell` (a beam reaching the camera, a camera
// connection, a light sample or an emitter seen): count[j] for each
// carried wavelength j into its bin, and into a weighted film's squared
// weights the square of their sum, once (the event is one sample).
// (The loop runs to k, known at run time only, so the shader compiler keeps
// one copy of the count instead of unrolling four.)
FN void contributeCounts(INOUT(BeamTally) tally, uvec2 cell, PathWavelengths w, WavelengthFactors count,
                         float spareUniform) {
  uint chunk = 0u;  // set by storedCounters; unread when recording
  uint base = 0u;
  bool counted = SPECTRACE_RECORDING || storedCounters(cell, chunk, base);
  if (!counted) return;
  PRECISE float sum = 0.0f;
  for (uint j = 0u; j < constants.wavelengthsPerPath; ++j) {
    if (!(w.share[j] > 0.0f)) continue;
    if (SPECTRACE_RECORDING) tally.ratio = count.value[j];
    else countInBin(chunk, base, w.bin[j], w.lambda[j], count.value[j], spareUniform);
    sum += count.value[j];
    tally.cell = cell;
    tally.bin = w.bin[j];
    tally.contributions += 1u;
  }
  if (!SPECTRACE_RECORDING) countSquaredWeight(chunk, base, sum * sum, spareUniform);
}

// `ratio` times each carried wavelength's share: what an event counts when
// nothing on its way depends on the wavelength.
FN WavelengthFactors sharesTimes(PathWavelengths w, float ratio) {
  WavelengthFactors count;
  for (uint j = 0u; j < kMaxWavelengthsPerPath; ++j) {
    PRECISE float c = ratio * w.share[j];
    count.value[j] = c;
  }
  return count;
}

#endif  // SPECTRACE_WAVELENGTHS_H
