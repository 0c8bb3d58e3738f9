//VTK::System::Dec

// The composite pass of vtkCloudVolumeMapper: draws the march target (premultiplied RGBA,
// possibly at a lower resolution) over the viewport. The target holds the sum of the accumulated
// frames; FrameWeight (1 / their number) makes it their mean. Below full resolution it upsamples
// with a Catmull-Rom filter (16 texels); the blend state composites it over the opaque scene.

in vec2 texCoord;

uniform sampler2D MarchTexture;
uniform sampler2D CountTexture;
uniform vec2 MarchSize;
uniform int Upsample;
uniform int ShowSampleCount;
uniform float SampleCountScale;
uniform float FrameWeight;

//VTK::Output::Dec

// Catmull-Rom weights of the four texels around a fraction f.
vec4 CatmullRomWeights(float f)
{
  float f2 = f * f, f3 = f2 * f;
  return vec4(-0.5 * f3 + f2 - 0.5 * f,
              1.5 * f3 - 2.5 * f2 + 1.0,
              -1.5 * f3 + 2.0 * f2 + 0.5 * f,
              0.5 * f3 - 0.5 * f2);
}

vec4 Bicubic(sampler2D image, vec2 uv)
{
  vec2 position = uv * MarchSize - 0.5;
  vec2 base = floor(position);
  vec2 f = position - base;
  vec4 wx = CatmullRomWeights(f.x);
  vec4 wy = CatmullRomWeights(f.y);
  ivec2 last = ivec2(MarchSize) - 1;
  vec4 sum = vec4(0.0);
  for (int j = 0; j < 4; ++j)
  {
    vec4 row = vec4(0.0);
    for (int i = 0; i < 4; ++i)
    {
      ivec2 texel = clamp(ivec2(base) + ivec2(i - 1, j - 1), ivec2(0), last);
      row += wx[i] * (texelFetch(image, texel, 0) * FrameWeight);
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

void main()
{
  if (ShowSampleCount != 0)
  {
    float samples = texelFetch(CountTexture, ivec2(texCoord * MarchSize), 0).r * FrameWeight;
    gl_FragData[0] = vec4(FalseColor(samples * SampleCountScale), 1.0);
    return;
  }
  if (Upsample != 0)
  {
    gl_FragData[0] = Bicubic(MarchTexture, texCoord);
  }
  else
  {
    gl_FragData[0] = texelFetch(MarchTexture, ivec2(texCoord * MarchSize), 0) * FrameWeight;
  }
}
