//VTK::System::Dec

// The composite pass of vtkCloudVolumeMapper: draws the march target (premultiplied RGBA,
// possibly at a lower resolution) over the viewport. The target holds the sum of the accumulated
// frames; FrameWeight (1 / their number) makes it their mean. Below full resolution it upsamples
// with a Catmull-Rom filter (16 texels); the blend state composites it over the opaque scene.
//
// With temporal reprojection the same program first resolves the frame into the history target
// at full resolution (ResolveHistory: output 0 the image, output 1 its depth and age), then
// draws that target over the scene as a full-resolution march target. On an interactive frame
// the resolve reprojects the last image (Reproject): each pixel's point on the cloud (at the
// cloud's opacity-weighted mean depth, from the march's count target) is projected into the last
// camera; the last image's value there is kept when it lands on the screen, its depth agrees
// with that point's, and then only within the colour bounds of the current neighbourhood (so a
// cloud edge that moved cannot leave a ghost), blended with the current upsampled sample by
// HistoryWeight, less as the views it holds turn away from this one. Everywhere else the current
// sample stands alone.
//
// Drawn over the viewport, the cloud's radiance goes through the display transform (exposure and
// curve, shaders/display/DisplayTransform.glsl, which the mapper splices in below); the history
// target keeps linear radiance.

in vec2 texCoord;

uniform sampler2D MarchTexture;
uniform sampler2D CountTexture;
uniform vec2 MarchSize;
uniform int Upsample;
uniform int ShowSampleCount;
uniform float SampleCountScale;
uniform float FrameWeight;

uniform int ResolveHistory;            // write the history target (image; depth and age)
uniform int Reproject;                 // blend the last image, reprojected
uniform sampler2D HistoryColorTexture; // the last image, premultiplied RGBA, viewport size
uniform sampler2D HistoryDepthTexture; // its depth (MarchDepth; negative: no cloud) and age
uniform vec2 HistorySize;
uniform mat4 DCLocalMatrix;            // this frame: normalized device -> local frame
uniform mat4 LastDCLocalMatrix;        // the last image's camera, both ways
uniform mat4 LastLocalDCMatrix;
uniform float HistoryWeight;           // share of the reprojected history in the blend
uniform float DepthTolerance;          // local units a reprojected depth may differ by
uniform float FadeAngle;               // radians of turn that leave no history
uniform float ExposureScale;           // 2^EV
uniform int DisplayCurve;              // DisplayLinear or DisplayFilmic
uniform int ColorWithinAlpha;          // clamp the display colour to its alpha (for compositors)

//VTK::Output::Dec

//CLOUDVIS::DisplayTransform

// Below this opacity (one 8-bit level) the cloud is too faint for its depth to mean anything.
const float MinimumDepthOpacity = 1.0 / 255.0;

// Catmull-Rom weights of the four texels around a fraction f.
vec4 CatmullRomWeights(float f)
{
  float f2 = f * f, f3 = f2 * f;
  return vec4(-0.5 * f3 + f2 - 0.5 * f,
              1.5 * f3 - 2.5 * f2 + 1.0,
              -1.5 * f3 + 2.0 * f2 + 0.5 * f,
              0.5 * f3 - 0.5 * f2);
}

// The image of `size` texels (times `weight`) at uv, Catmull-Rom filtered.
vec4 Bicubic(sampler2D image, vec2 uv, vec2 size, float weight)
{
  vec2 position = uv * size - 0.5;
  vec2 base = floor(position);
  vec2 f = position - base;
  vec4 wx = CatmullRomWeights(f.x);
  vec4 wy = CatmullRomWeights(f.y);
  ivec2 last = ivec2(size) - 1;
  vec4 sum = vec4(0.0);
  for (int j = 0; j < 4; ++j)
  {
    vec4 row = vec4(0.0);
    for (int i = 0; i < 4; ++i)
    {
      ivec2 texel = clamp(ivec2(base) + ivec2(i - 1, j - 1), ivec2(0), last);
      row += wx[i] * (texelFetch(image, texel, 0) * weight);
    }
    sum += wy[j] * row;
  }
  // Catmull-Rom overshoots at edges: keep a valid premultiplied color.
  sum.a = clamp(sum.a, 0.0, 1.0);
  sum.rgb = max(sum.rgb, vec3(0.0));
  return sum;
}

// Blue (cheap) through green to red (expensive).
vec3 FalseColor(float x)
{
  x = clamp(x, 0.0, 1.0);
  return clamp(vec3(2.0 * x - 0.5, 1.5 - abs(2.0 * x - 1.0) * 1.5, 1.0 - 2.0 * x), 0.0, 1.0);
}

// The cloud's opacity-weighted mean depth (local units from the near plane) in the march target
// at uv: the depth sums (the count target's fourth channel) and the opacities interpolated apart
// over the 2 x 2 texels around uv, so the mean weighs each by its opacity. Negative where the
// cloud is too faint.
float MarchDepth(vec2 uv)
{
  vec2 position = uv * MarchSize - 0.5;
  vec2 base = floor(position);
  vec2 f = position - base;
  ivec2 last = ivec2(MarchSize) - 1;
  float depthSum = 0.0;
  float alphaSum = 0.0;
  for (int j = 0; j < 2; ++j)
  {
    for (int i = 0; i < 2; ++i)
    {
      ivec2 texel = clamp(ivec2(base) + ivec2(i, j), ivec2(0), last);
      float w = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
      depthSum += w * texelFetch(CountTexture, texel, 0).a;
      alphaSum += w * texelFetch(MarchTexture, texel, 0).a;
    }
  }
  return alphaSum * FrameWeight > MinimumDepthOpacity ? depthSum / alphaSum : -1.0;
}

vec3 LocalPoint(mat4 deviceToLocal, vec2 ndc, float ndcDepth)
{
  vec4 p = deviceToLocal * vec4(ndc, ndcDepth, 1.0);
  return p.xyz / p.w;
}

// The current sample blended with the last image reprojected to this pixel, or the current
// sample alone where the history does not hold this pixel's cloud. `age` receives the blend's:
// the angle (radians) the history's views lie from this one, weighted as the blend weighs them.
vec4 BlendHistory(vec4 current, out float age)
{
  age = 0.0;
  float depth = MarchDepth(texCoord);
  if (depth < 0.0)
  {
    return current; // no cloud here to follow
  }
  vec2 ndc = texCoord * 2.0 - 1.0;
  vec3 nearPoint = LocalPoint(DCLocalMatrix, ndc, -1.0);
  vec3 point = nearPoint + depth * normalize(LocalPoint(DCLocalMatrix, ndc, 1.0) - nearPoint);
  vec4 clip = LastLocalDCMatrix * vec4(point, 1.0);
  if (clip.w <= 0.0)
  {
    return current;
  }
  vec2 lastNdc = clip.xy / clip.w;
  vec2 lastUV = lastNdc * 0.5 + 0.5;
  if (any(lessThan(lastUV, vec2(0.0))) || any(greaterThan(lastUV, vec2(1.0))))
  {
    return current; // it was off the screen
  }
  // The colour bounds and the depth range of the 3 x 3 march texels around the pixel.
  ivec2 centre = ivec2(texCoord * MarchSize);
  ivec2 last = ivec2(MarchSize) - 1;
  vec4 lo = vec4(1e30);
  vec4 hi = vec4(-1e30);
  vec2 depthRange = vec2(depth, depth);
  for (int j = -1; j <= 1; ++j)
  {
    for (int i = -1; i <= 1; ++i)
    {
      ivec2 texel = clamp(centre + ivec2(i, j), ivec2(0), last);
      vec4 c = texelFetch(MarchTexture, texel, 0) * FrameWeight;
      lo = min(lo, c);
      hi = max(hi, c);
      if (c.a > MinimumDepthOpacity)
      {
        float d = texelFetch(CountTexture, texel, 0).a * FrameWeight / c.a;
        depthRange = vec2(min(depthRange.x, d), max(depthRange.y, d));
      }
    }
  }
  // The last image's depth there must be this point's, give or take the depths the low
  // resolution blurs together here.
  ivec2 lastTexel = min(ivec2(lastUV * HistorySize), ivec2(HistorySize) - 1);
  vec2 lastDepthAndAge = texelFetch(HistoryDepthTexture, lastTexel, 0).rg;
  float lastDepth = lastDepthAndAge.x;
  vec3 lastNearPoint = LocalPoint(LastDCLocalMatrix, lastNdc, -1.0);
  float expected = length(point - lastNearPoint);
  float tolerance = DepthTolerance + (depthRange.y - depthRange.x);
  if (lastDepth < 0.0 || abs(lastDepth - expected) > tolerance)
  {
    return current; // another part of the cloud (or none) was there: disoccluded, or it moved
  }
  vec4 history = clamp(Bicubic(HistoryColorTexture, lastUV, HistorySize, 1.0), lo, hi);
  // A cloud is seen through: the more the ray through this point turned since the views the
  // history holds, the more what lies behind it changed, so the history's share fades out with
  // that angle (its age plus this frame's turn; the age keeps the lag of a steady orbit bounded).
  vec3 ray = normalize(point - nearPoint);
  vec3 lastRay = normalize(point - lastNearPoint);
  float turn = lastDepthAndAge.y + acos(clamp(dot(ray, lastRay), -1.0, 1.0));
  float weight = HistoryWeight * clamp(1.0 - turn / FadeAngle, 0.0, 1.0);
  age = weight * turn;
  return mix(current, history, weight);
}

void main()
{
  if (ShowSampleCount != 0)
  {
    float samples = texelFetch(CountTexture, ivec2(texCoord * MarchSize), 0).r * FrameWeight;
    gl_FragData[0] = vec4(FalseColor(samples * SampleCountScale), 1.0);
    return;
  }
  vec4 current;
  if (Upsample != 0)
  {
    current = Bicubic(MarchTexture, texCoord, MarchSize, FrameWeight);
  }
  else
  {
    current = texelFetch(MarchTexture, ivec2(texCoord * MarchSize), 0) * FrameWeight;
  }
  if (ResolveHistory == 0)
  {
    vec3 shown = DisplayValue(current.rgb, current.a, ExposureScale, DisplayCurve);
    gl_FragData[0] = vec4(ColorWithinAlpha != 0 ? min(shown, vec3(current.a)) : shown, current.a);
    return;
  }
  float age = 0.0;
  gl_FragData[0] = Reproject != 0 ? BlendHistory(current, age) : current;
  gl_FragData[1] = vec4(MarchDepth(texCoord), age, 0.0, 1.0);
}
