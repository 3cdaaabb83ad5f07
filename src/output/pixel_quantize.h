// 8-bit pixels for PNG (and the other 8-bit formats): straight alpha.
//
// The renderers produce premultiplied RGBA (colour already weighted by its
// coverage, out = I + (1 - α)·b). PNG's alpha is unassociated by its
// specification and every viewer reads it so: a premultiplied PNG shows
// translucent pixels too dark. So 8-bit outputs store colour / α; EXR and
// TIFF keep the floats premultiplied, as OpenEXR defines. No gamma; round
// half up. write_image and ImageTileWriter both quantize here, so the two
// paths stay byte-equal.
#pragma once

#include <algorithm>
#include <cstdint>

namespace zs {

inline uint8_t quantize_unit(float v) { return uint8_t(std::clamp(v, 0.f, 1.f) * 255.f + 0.5f); }

// One premultiplied RGBA pixel to straight 8-bit RGBA. Where α is 0 the
// colour is undefined and stored as 0; where α is 1 it is the colour as is
// (opaque pixels are what they were before straight alpha).
inline void quantize_straight(const float* rgba, uint8_t* out) {
  const float a = std::clamp(rgba[3], 0.f, 1.f);
  out[3] = quantize_unit(a);
  if (a >= 1.f) {
    for (int c = 0; c < 3; ++c) out[c] = quantize_unit(rgba[c]);
  } else if (a > 0.f) {
    for (int c = 0; c < 3; ++c) out[c] = quantize_unit(rgba[c] / a);
  } else {
    out[0] = out[1] = out[2] = 0;
  }
}

// The inverse on reading: straight 8-bit levels (as floats k/255) back to
// premultiplied, so images compare against the float formats.
inline void premultiply(float* rgba) {
  for (int c = 0; c < 3; ++c) rgba[c] *= rgba[3];
}

}  // namespace zs
