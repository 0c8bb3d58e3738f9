// The display transform, written once for the GPU's composite pass (shaders/CloudCompositeFS.glsl,
// spliced in by the mapper) and for the C++ that turns float images into display values (PNG at
// 16 bits, transparent PNG, the CPU reference: filters/CloudDisplayTransform.h): the cloud's
// linear, premultiplied radiance times the exposure 2^EV, then a display curve. It is in the
// common subset of GLSL 1.50 and C++/glm (float literals with f, no swizzles, no const locals).
// docs/export.md, "Exposure and the display curve", gives the equations.
//
// The background is already a display colour (a sky gradient, a solid colour), so the cloud is
// composited over it in display values too: the curve maps the cloud's own colour L / alpha,
// and the "over" blend adds the background behind, display = alpha D(L / alpha) + (1 - alpha) B.
// (Mapping L itself, as a camera would over a black sky, lifts a thin edge's faint light through
// the curve's steep start and draws a white rim around a cloud in front of a bright sky.)

// The curves render.display names (DisplayCurve in filters/CloudDisplayTransform.h).
const int DisplayLinear = 0; // the radiance as it is, clamped to [0, 1] by the 8-bit target
const int DisplayFilmic = 1; // the filmic curve, then sRGB's encoding

// sRGB's encoding (IEC 61966-2-1) of a display-linear value in [0, 1].
float SrgbEncode(float v)
{
  return v <= 0.0031308f ? 12.92f * v : 1.055f * pow(v, 1.0f / 2.4f) - 0.055f;
}

// The filmic tone curve: Narkowicz's rational fit (2015) of the ACES reference rendering and
// output transforms, display-linear in [0, 1]. A toe below about 0.05, a shoulder that reaches
// 0.8 at x = 1 and 0.97 at x = 4, and white (1) from x = 7.24 on.
float FilmicCurve(float x)
{
  return clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

// The premultiplied display value of premultiplied linear radiance `radiance` of opacity `alpha`
// under exposure scale 2^EV.
vec3 DisplayValue(vec3 radiance, float alpha, float exposureScale, int curve)
{
  vec3 x = max(radiance * exposureScale, vec3(0.0f));
  if (curve == DisplayFilmic)
  {
    float a = max(alpha, 1e-6f);
    vec3 c = x / a;
    return a * vec3(SrgbEncode(FilmicCurve(c.x)), SrgbEncode(FilmicCurve(c.y)),
      SrgbEncode(FilmicCurve(c.z)));
  }
  return x;
}
