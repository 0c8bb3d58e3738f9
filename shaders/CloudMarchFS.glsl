//VTK::System::Dec

// The march pass of vtkCloudVolumeMapper: one fragment per pixel of the march target.
// A ray from the near to the far plane is clipped to the volume box and to the opaque depth,
// then samples the density at s = (k + jitter) * Step past the point where it enters the box,
// k = 0, 1, 2, ... Bricks the occupancy map marks empty are leapt over, landing on the same
// lattice of k; a sample costs no division (docs/performance.md, "The march's per-sample
// cost"). Lighting models plug in by defining SourceTerm() at the lighting tag below, so all
// share this march; what it computes with is shared with the CPU (shaders/transport/).
// Quantities: everything is computed in the local frame of filters/CloudMarchUniforms.h (world
// translated to the volume's centre and scaled by a power of two near the voxel size), never in
// world coordinates, so precision does not depend on where the volume is or how large it is.
// t and s are local distances along the ray; p is a point in voxel index space (voxel centres
// at integers); sigma_t the extinction per local unit; T the transmittance to the eye.

in vec2 texCoord;

// Constants the C++ defines once (MAX_LIGHTS, Pi, PhaseToRadiance, DirectionalLightDistance,
// LightBoxMargin, the path tracer's, NoDepth, DepthTransmittance), substituted by the mapper
// (app/rendering/CloudMarchShader.cxx).
//CLOUD::Constants::Dec

uniform mat4 DCLocalMatrix;  // normalized device -> local frame
uniform sampler2D DepthTexture; // opaque depth of the viewport, full resolution
uniform sampler2D JitterTexture; // blue noise, tiled
uniform float JitterTextureSize;
uniform float JitterOffset;      // golden-ratio sequence over accumulated frames
uniform int JitterEnabled;
uniform float Step; // local units
uniform float TerminationTransmittance;
uniform int MaximumIterations;

//VTK::Output::Dec

// The light transport shared with the CPU (shaders/transport/, docs/transport.md),
// spliced here with its prelude and the GPU's accessors (shaders/transport/Accessors.glsl): the
// field's uniforms and textures (Dimensions, IndexToLocal, LocalToIndex, DensityTexture,
// TransferTexture, TableRange, EmptyDistanceTexture, BrickSize...), IntersectBox, Optical,
// LocalOfIndex, IndexOfLocal, EmptyBricksAround, the lights and every lighting model's terms.
//CLOUD::Transport::Dec

vec3 LocalPoint(vec2 ndc, float ndcDepth)
{
  vec4 p = DCLocalMatrix * vec4(ndc, ndcDepth, 1.0);
  return p.xyz / p.w;
}

// The lighting model: SourceTerm(p, density, albedo, d), which calls the model's terms of the
// shared source, or (the path tracer, which defines CLOUD_OWN_MAIN) a main() of its own that uses
// the helpers above. The light-volume pass defines CLOUD_OWN_MAIN too, after the march's lighting,
// and appends its own main().
//CLOUD::Lighting::Dec

#ifndef CLOUD_OWN_MAIN
// The march's state along one ray: premultiplied radiance, transmittance T, and the count
// target's tallies (FirstSignificant: the local distance from the near plane where T first falls
// below DepthTransmittance, NoDepth where it never does; DepthSum: the distances weighted by the
// opacity each step adds, which divided by the opacity is the cloud's mean depth, followed by
// temporal reprojection).
struct MarchState
{
  vec3 Radiance;
  float T;
  float SamplesTaken;
  float UsefulSamples;
  float FirstSignificant;
  float DepthSum;
};

// What a sample needs that is the same all along the ray, computed once per ray by main() so that
// a sample only multiplies and adds (issue 12, the per-sample cost; docs/performance.md): the
// density texture's coordinate of sample s is EntryTexture + s * DirectionTexture ((p + 0.5) /
// Dimensions, as DensityAt has it); the transfer table's coordinate is one multiply-add of the
// density texel (TableCoordinate(texel * DensityScale + DensityBias), its clamp to [0, 1] moved to
// the first and last entries' centres); a step's transmittance is exp2 of the table's extinction
// times StepLog2Transmittance (-ExtinctionUnit * Step / ln 2).
struct RayConstants
{
  vec3 EntryTexture;
  vec3 DirectionTexture;
  float TexelToTable;
  float TableOffset;
  vec2 TableEnds;
  float StepLog2Transmittance;
  float Enter; // tEnter: the local distance from the near plane to s = 0
  vec3 View;   // d, the unit view direction
};

// The sample at distance s past the entry (index point p): its in-scattering and transmittance
// added to m. False when T has fallen below TerminationTransmittance: the ray is done.
bool MarchSample(inout MarchState m, RayConstants ray, float s, vec3 p)
{
  float texel = texture(DensityTexture, ray.EntryTexture + s * ray.DirectionTexture).r;
  vec4 optical = texture(TransferTexture,
    clamp(texel * ray.TexelToTable + ray.TableOffset, ray.TableEnds.x, ray.TableEnds.y));
  m.SamplesTaken += 1.0;
  if (optical.a > 0.0)
  {
    m.UsefulSamples += 1.0;
    float stepT = exp2(optical.a * ray.StepLog2Transmittance);
    float density = texel * DensityScale + DensityBias; // DensityAt(p)
    // In-scattering integrated over the step: S * (1 - exp(-sigma_t dt)), exact for S
    // constant over the step, so the sum does not depend on the step size.
    m.Radiance += m.T * SourceTerm(p, density, optical.rgb, ray.View) * (1.0 - stepT);
    m.DepthSum += (ray.Enter + s) * m.T * (1.0 - stepT);
    m.T *= stepT;
    // T only falls, so the first sample below DepthTransmittance keeps the smallest distance.
    m.FirstSignificant = min(m.FirstSignificant, m.T < DepthTransmittance ? ray.Enter + s : NoDepth);
  }
  return m.T >= TerminationTransmittance;
}

void main()
{
  vec2 ndc = texCoord * 2.0 - 1.0;
  vec3 nearPoint = LocalPoint(ndc, -1.0);
  vec3 toFar = LocalPoint(ndc, 1.0) - nearPoint;
  float rayLength = length(toFar);
  vec3 d = toFar / rayLength; // view direction, unit
  vec3 origin = IndexOfLocal(nearPoint); // index point at t = 0
  vec3 direction = LocalToIndex * d;              // index units per local unit

  float opaqueDepth = texture(DepthTexture, texCoord).r;
  float tOpaque = length(LocalPoint(ndc, opaqueDepth * 2.0 - 1.0) - nearPoint);
  vec2 tBox = IntersectBox(origin, direction, vec3(0.0), Dimensions - 1.0);
  float tEnter = max(tBox.x, 0.0);
  float tExit = min(min(tBox.y, tOpaque), rayLength);

  MarchState m = MarchState(vec3(0.0), 1.0, 0.0, 0.0, NoDepth, 0.0);
  if (tEnter < tExit)
  {
    // Samples are placed from the entry point, so their spacing keeps its precision however far
    // the camera is from the volume.
    vec3 entry = origin + tEnter * direction;
    float span = tExit - tEnter;
    float jitter = 0.0;
    if (JitterEnabled != 0)
    {
      jitter = fract(texture(JitterTexture, gl_FragCoord.xy / JitterTextureSize).r + JitterOffset);
    }

    // (A table over a single density holds one value: its first entry serves every density.)
    float tableWidth = TableRange.y - TableRange.x;
    float tableScale = tableWidth > 0.0 ? (TableSize - 1.0) / (TableSize * tableWidth) : 0.0;
    RayConstants ray = RayConstants((entry + 0.5) / Dimensions,
      direction / Dimensions,
      DensityScale * tableScale,
      (DensityBias - TableRange.x) * tableScale + 0.5 / TableSize,
      vec2(0.5, TableSize - 0.5) / TableSize,
      -ExtinctionUnit * Step / log(2.0),
      tEnter,
      d);
    // A leap leaves the cube of empty bricks through its far face on each axis: exitSide picks
    // it (the positive face for an axis the ray does not move along, as IntersectBox's 1e-30
    // does) and inverseDirection is IntersectBox's, so sLeave is IntersectBox(entry, direction,
    // lo, hi).y to the bit.
    float brickScale = 1.0 / BrickSize;
    vec3 inverseDirection = 1.0 / mix(direction, vec3(1e-30), equal(direction, vec3(0.0)));
    vec3 exitSide = mix(vec3(0.5), vec3(-0.5), lessThan(direction, vec3(0.0)));

    float k = 0.0;
    for (int i = 0; i < MaximumIterations; ++i)
    {
      float s = (k + jitter) * Step;
      if (s >= span)
      {
        break;
      }
      vec3 p = entry + s * direction;
      if (SkipEmptySpace != 0)
      {
        // BrickOf(p); the multiplication by 1 / BrickSize may put a p within an ulp of a brick
        // face in the neighbouring brick, where the occupancy's footprint still covers it.
        vec3 brick = clamp(floor(p * brickScale), vec3(0.0), BrickCount - 1.0);
        float emptyBricks = EmptyBricksAround(brick);
        if (emptyBricks > 0.0)
        {
          // Every brick within Chebyshev distance emptyBricks - 1 is empty: leave that cube
          // and resume at the first lattice sample beyond it.
          vec3 exitFace = (brick + 0.5 + exitSide * (2.0 * emptyBricks - 1.0)) * BrickSize;
          vec3 tFar = (exitFace - entry) * inverseDirection;
          float sLeave = min(min(tFar.x, tFar.y), tFar.z);
          k = max(k + 1.0, ceil(sLeave / Step - jitter));
          continue;
        }
      }
      // Dense fields: more samples before the map is read again (SAMPLES_PER_MAP_READ, the
      // program's variant). One may lie in another brick, and if that one is empty it adds
      // nothing (its extinction is 0 there), so the image is the same; the next iteration
      // reads the map again and leaps from there.
      bool marching = MarchSample(m, ray, s, p);
      for (int j = 1; marching && j < SAMPLES_PER_MAP_READ; ++j)
      {
        k += 1.0;
        s = (k + jitter) * Step;
        marching = s < span && MarchSample(m, ray, s, entry + s * direction);
      }
      if (!marching)
      {
        break;
      }
      k += 1.0;
    }
  }
  gl_FragData[0] = vec4(m.Radiance, 1.0 - m.T); // premultiplied: alpha is the opacity
  gl_FragData[1] = vec4(m.SamplesTaken, m.UsefulSamples, m.FirstSignificant, m.DepthSum);
}
#endif
