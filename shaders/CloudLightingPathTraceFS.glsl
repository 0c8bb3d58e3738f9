// Lighting model "pathtrace": not a source term of the march but a main() of its own, one fragment
// per pixel of the march target, which traces SamplesPerFrame paths through the pixel centre with
// the shared path tracer (TracePath in shaders/transport/PathTrace.glsl, the very code the CPU's
// vtkCloudPathTracer runs; docs/lighting.md, "The path tracer") and writes their mean
// (premultiplied radiance and opacity 1 - T) to the color target and the mean of their squares to
// the moment target; the mapper's additive accumulation sums frames, so the readers get the mean
// and the second moment over every sample, hence the per-pixel variance.
//
// Random numbers are a pure function of (pixel, sample, dimension, seed): sample k of frame f is
// sample SampleBase + k. Majorants and minorants per occupancy brick come from
// ExtinctionBoundsTexture, the empty distances from EmptyDistanceTexture (Accessors.glsl).
//
// The count target's fourth channel is 1 when the fragment's loops all ran to their ends, else 0,
// so its mean over the accumulated frames is 1 only where every frame's paths ran whole. A software
// rasterizer may end a shader's loops early without an error: llvmpipe gives all the loops of a
// fragment 65535 turns in all (LP_MAX_TGSI_LOOP_ITERATIONS) and then breaks out of every one, which
// the deep walks of a thick cloud exceed. The budget only runs down, so a loop of two turns after
// the paths runs both only when it was never spent. The mapper counts the pixels with a cut frame
// (vtkCloudVolumeMapper::CountCutPathTracePixels), and cloudvis refuses to show such an image as
// the truth.
#define CLOUD_OWN_MAIN

uniform int PathTraceSeed;
uniform int SampleBase;
uniform int SamplesPerFrame;
uniform int MarchWidth;

void main()
{
  // The pixel centre's ray, as vtkCloudReferenceRenderer::PixelRay, ending at the opaque scene.
  vec2 ndc = texCoord * 2.0 - 1.0;
  vec3 nearPoint = LocalPoint(ndc, -1.0);
  float opaqueDepth = texture(DepthTexture, texCoord).r;
  vec3 farPoint = LocalPoint(ndc, opaqueDepth * 2.0 - 1.0);
  uint pixel = uint(gl_FragCoord.y) * uint(MarchWidth) + uint(gl_FragCoord.x);
  vec4 sum = vec4(0.0);
  vec4 squares = vec4(0.0);
  for (int k = 0; k < SamplesPerFrame; ++k)
  {
    RandomStream rng;
    rng.Pixel = pixel;
    rng.Sample = uint(SampleBase + k);
    rng.Seed = uint(PathTraceSeed);
    rng.Dimension = 0u;
    vec4 x = TracePath(nearPoint, farPoint, rng);
    sum += x;
    squares += x * x;
  }
  int probeTurns = 0;
  for (int turn = 0; turn < min(SamplesPerFrame, 1) + 1; ++turn) // not a constant: not unrolled
  {
    ++probeTurns;
  }
  float n = float(SamplesPerFrame);
  gl_FragData[0] = sum / n;
  gl_FragData[1] =
    vec4(DensityReads / n, UsefulDensityReads / n, NoDepth, probeTurns == 2 ? 1.0 : 0.0);
  gl_FragData[2] = squares / n;
}
