// The per-pixel resolve, written once: a pixel's counters to XYZ, linear
// sRGB, irradiance and its exact sums. resolve.comp runs it in float on the
// device; the host's develop (host/film/develop.cpp) runs the same text in
// double. Each keeps its own precision, so the two agree to float rounding,
// not bit for bit; each is bit-stable on its own.
//
// The includer defines, before including this file:
//   RESOLVE_REAL, RESOLVE_VEC3   the arithmetic (float, vec3 / double, dvec3)
//   RESOLVE_PIXEL                what names one pixel's counters
//   WideCount resolveBinCount(RESOLVE_PIXEL pixel, uint bin)   stored bin `bin`
//   WideCount resolveColourSum(RESOLVE_PIXEL pixel, uint k)    exact colour's X, Y, Z sums
// (a plain film's one-word counters with high words 0).
//   RESOLVE_VEC3 resolveBinWeight(RESOLVE_PIXEL pixel, uint bin)
//                                 683 x the bin-averaged CMFs of stored bin `bin`
#ifndef SPECTRACE_RESOLVE_PIXEL_H
#define SPECTRACE_RESOLVE_PIXEL_H

// What turns one pixel's counts into light, the same for every pixel.
struct ResolveFactors {
  uint bins;                        // stored bins
  bool exactColour;                 // XYZ from the colour sums, not the bins
  RESOLVE_REAL irradiancePerCount;  // W/m^2 carried by one count
  RESOLVE_REAL xyzPerColourUnit;    // XYZ carried by one colour-sum unit
  RESOLVE_VEC3 xyzToRgbRow0;        // linear sRGB = rows . XYZ
  RESOLVE_VEC3 xyzToRgbRow1;
  RESOLVE_VEC3 xyzToRgbRow2;
};

struct PixelResolution {
  RESOLVE_VEC3 xyz;
  RESOLVE_VEC3 rgb;
  RESOLVE_REAL irradiance;  // W/m^2 over all bins
  WideCount total;          // the sum of its bin counters (exact)
  WideCount largest;        // its largest bin counter
};

FN WideCount wideSum(WideCount a, WideCount b) {
  WideCount sum;
  sum.low = a.low + b.low;
  sum.high = a.high + b.high + (sum.low < a.low ? uint64_t(1) : uint64_t(0));
  return sum;
}
FN bool wideLess(WideCount a, WideCount b) { return a.high < b.high || (a.high == b.high && a.low < b.low); }
// (With a high word of 0, as in a plain film, exactly RESOLVE_REAL(low).)
FN RESOLVE_REAL realOfWide(WideCount w) {
  return RESOLVE_REAL(w.high) * RESOLVE_REAL(18446744073709551616.0) + RESOLVE_REAL(w.low);
}

FN void addBinCount(RESOLVE_PIXEL pixel, uint bin, INOUT(WideCount) total, INOUT(WideCount) largest,
                    INOUT(RESOLVE_VEC3) weighted) {
  WideCount count = resolveBinCount(pixel, bin);
  total = wideSum(total, count);
  if (wideLess(largest, count)) largest = count;
  weighted += realOfWide(count) * resolveBinWeight(pixel, bin);
}

FN PixelResolution resolvePixel(RESOLVE_PIXEL pixel, ResolveFactors f) {
  WideCount total;
  total.low = uint64_t(0);
  total.high = uint64_t(0);
  WideCount largest = total;
  RESOLVE_VEC3 weighted = RESOLVE_VEC3(0.0f);
  // llvmpipe (lavapipe) ends a shader loop after 65535 iterations in all
  // (nesting does not reset the count), which silently dropped the bins
  // past 65535. So the loop takes kResolveBinsPerIteration bins at a time
  // (vulkan_tracer.cpp checks that the largest spectrum stays under the
  // limit), written out rather than as an inner loop, which would count
  // towards the limit; the bins are still summed one by one, in order.
  uint b = 0u;
  uint whole = f.bins - f.bins % kResolveBinsPerIteration;
  for (; b < whole; b += kResolveBinsPerIteration) {
    addBinCount(pixel, b, total, largest, weighted);
    addBinCount(pixel, b + 1u, total, largest, weighted);
    addBinCount(pixel, b + 2u, total, largest, weighted);
    addBinCount(pixel, b + 3u, total, largest, weighted);
  }
  for (; b < f.bins; ++b) addBinCount(pixel, b, total, largest, weighted);

  PixelResolution result;
  result.xyz = weighted * f.irradiancePerCount;
  if (f.exactColour)
    result.xyz = RESOLVE_VEC3(realOfWide(resolveColourSum(pixel, 0u)), realOfWide(resolveColourSum(pixel, 1u)),
                              realOfWide(resolveColourSum(pixel, 2u))) *
                 f.xyzPerColourUnit;
  result.rgb = RESOLVE_VEC3(dot(f.xyzToRgbRow0, result.xyz), dot(f.xyzToRgbRow1, result.xyz),
                            dot(f.xyzToRgbRow2, result.xyz));
  result.irradiance = realOfWide(total) * f.irradiancePerCount;
  result.total = total;
  result.largest = largest;
  return result;
}

#endif  // SPECTRACE_RESOLVE_PIXEL_H
