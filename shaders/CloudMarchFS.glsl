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

// The light transport shared with the CPU (shaders/transport/Transport.glsl, docs/transport.md),
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

  vec3 radiance = vec3(0.0);
  float T = 1.0;
  float samplesTaken = 0.0;
  float usefulSamples = 0.0;
  float firstSignificant = NoDepth; // local distance from the near plane where T first falls
                                    // below DepthTransmittance (NoDepth: it never does)
  float depthSum = 0.0; // the distances weighted by the opacity each step adds: / alpha, the
                        // cloud's mean depth (temporal reprojection follows it)
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

    // What every sample would otherwise divide or recompute, once per ray (issue 12, the
    // per-sample cost; docs/performance.md): the loop body below only multiplies and adds, with
    // one division left, in a leap. The density texture's coordinate of sample s is entryTexture +
    // s * directionTexture, (p + 0.5) / Dimensions as DensityAt has it. The transfer table's
    // coordinate is one multiply-add of the density texel, TableCoordinate(texel * DensityScale
    // + DensityBias) with its clamp to [0, 1] moved to the first and last entries' centres. A
    // step's transmittance is exp2 of the table's extinction times -ExtinctionUnit * Step /
    // ln 2. A leap leaves the cube of empty bricks through its far face on each axis:
    // exitSide picks it (the positive face for an axis the ray does not move along, as
    // IntersectBox's 1e-30 does), inverseDirection is IntersectBox's, so sLeave is IntersectBox
    // (entry, direction, lo, hi).y to the bit.
    vec3 entryTexture = (entry + 0.5) / Dimensions;
    vec3 directionTexture = direction / Dimensions;
    float brickScale = 1.0 / BrickSize;
    vec3 inverseDirection = 1.0 / mix(direction, vec3(1e-30), equal(direction, vec3(0.0)));
    vec3 exitSide = mix(vec3(0.5), vec3(-0.5), lessThan(direction, vec3(0.0)));
    // (A table over a single density holds one value: its first entry serves every density.)
    float tableWidth = TableRange.y - TableRange.x;
    float tableScale = tableWidth > 0.0 ? (TableSize - 1.0) / (TableSize * tableWidth) : 0.0;
    float texelToTable = DensityScale * tableScale;
    float tableOffset = (DensityBias - TableRange.x) * tableScale + 0.5 / TableSize;
    vec2 tableEnds = vec2(0.5, TableSize - 0.5) / TableSize;
    float stepLog2Transmittance = -ExtinctionUnit * Step / log(2.0);

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
      float texel = texture(DensityTexture, entryTexture + s * directionTexture).r;
      vec4 optical =
        texture(TransferTexture, clamp(texel * texelToTable + tableOffset, tableEnds.x, tableEnds.y));
      samplesTaken += 1.0;
      if (optical.a > 0.0)
      {
        usefulSamples += 1.0;
        float stepT = exp2(optical.a * stepLog2Transmittance);
        float density = texel * DensityScale + DensityBias; // DensityAt(p)
        // In-scattering integrated over the step: S * (1 - exp(-sigma_t dt)), exact for S
        // constant over the step, so the sum does not depend on the step size.
        radiance += T * SourceTerm(p, density, optical.rgb, d) * (1.0 - stepT);
        depthSum += (tEnter + s) * T * (1.0 - stepT);
        T *= stepT;
        // T only falls, so the first sample below DepthTransmittance keeps the smallest s.
        firstSignificant = min(firstSignificant, T < DepthTransmittance ? tEnter + s : NoDepth);
        if (T < TerminationTransmittance)
        {
          break;
        }
      }
      k += 1.0;
    }
  }
  gl_FragData[0] = vec4(radiance, 1.0 - T); // premultiplied: alpha is the opacity
  gl_FragData[1] = vec4(samplesTaken, usefulSamples, firstSignificant, depthSum);
}
#endif
