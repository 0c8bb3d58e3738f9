// The multiple-scattering volume's solver (issue 21), written once for both renderers like the
// rest of shaders/transport/, after whose five files it is spliced (GPU) or included (CPU, inside
// cloudvis::glsl::Transport): the texel functions of each pass over a grid's cells, whose order
// filters/CloudScatteringVolume.h states (ComputeScatteringVolume) and the GPU follows
// (app/rendering/CloudScatteringVolumeTexture.cxx). LightMarch.glsl's section "The
// multiple-scattering volume" gives the equations, the march's use of the result and the phase's
// moments these functions read. A cell c is an integer texel of a corner-aligned grid of
// ScatteringVolumeSize texels; t the same as a vec3.

UNIFORM vec3 ScatteringCoarseSize; // texels per axis of the next coarser grid
UNIFORM vec3 ScatteringCellSize;   // local length of a cell per axis, on the grid computed

// The grid being computed, read per cell (c within the grid), and the next coarser grid's
// fluence, linearly interpolated at texel coordinate t.
vec4 ScatteringMediumAt(ivec3 c);
vec4 ScatteringSourceAt(ivec3 c);
vec4 ScatteringDirectionAt(ivec3 c);
vec4 ScatteringFluenceAt(ivec3 c);
vec4 CoarseFluenceFetch(vec3 t);

// The index point of texel t of a corner-aligned grid of `size` texels.
vec3 IndexOfGridTexel(vec3 t, vec3 size)
{
  return t * ((Dimensions - 1.0f) / max(size - 1.0f, vec3(1.0f)));
}

// The medium of cell t: albedo (weighted by extinction) in rgb, mean sigma_t per local unit in a,
// over eight points a quarter cell from its centre.
// The same of the cell centred at index point p whose quarter cell is `quarter` index units (a
// piece of a distributed field computes its cells of the whole field's grid so).
vec4 ScatteringMediumAround(vec3 p, vec3 quarter)
{
  vec3 albedo = vec3(0.0f);
  float sigma = 0.0f;
  for (int k = 0; k < 8; ++k)
  {
    vec3 corner = vec3(float(k % 2), float((k / 2) % 2), float(k / 4)) * 2.0f - 1.0f;
    vec4 optical = Optical(DensityAt(clamp(p + corner * quarter, vec3(0.0f), Dimensions - 1.0f)));
    albedo += optical.w * vec3(optical.x, optical.y, optical.z);
    sigma += optical.w;
  }
  return vec4(sigma > 0.0f ? albedo / sigma : vec3(0.0f), 0.125f * sigma);
}

vec4 ScatteringMediumTexel(vec3 t)
{
  vec3 quarter = 0.25f * ((Dimensions - 1.0f) / max(ScatteringVolumeSize - 1.0f, vec3(1.0f)));
  return ScatteringMediumAround(IndexOfGridTexel(t, ScatteringVolumeSize), quarter);
}

// Light i's beam at index point p of albedo `albedo`, per channel: E exp(-tau (1 - albedo f)), its
// fluence; l the direction toward the light.
vec3 BeamFluence(int i, vec3 p, vec3 albedo, OUT(vec3) l)
{
  float lightDistance, falloff;
  SampleLight(i, LocalOfIndex(p), l, lightDistance, falloff);
  float tau = OpticalDepthToLight(i, p, ExtinctionAt(p), l, lightDistance);
  return LightRadiance[i] * (falloff * PhaseToRadiance) *
    exp(-tau * (vec3(1.0f) - albedo * PhaseForwardFraction()));
}

// The beams' fluence at cell t (centred at index point p) of medium m, summed over the lights: the coarsest grid's first
// guess where there is medium (the limiter has no direction to stream in where phi is 0).
vec4 ScatteringStartAt(vec3 p, vec4 m)
{
  vec3 fluence = vec3(0.0f);
  for (int i = 0; i < LightCount; ++i)
  {
    vec3 l;
    fluence += BeamFluence(i, p, vec3(m.x, m.y, m.z), l);
  }
  return vec4(m.w > 0.0f ? fluence : vec3(0.0f), 0.0f);
}

vec4 ScatteringStartTexel(vec3 t, vec4 m)
{
  return ScatteringStartAt(IndexOfGridTexel(t, ScatteringVolumeSize), m);
}

// The diffuse source of cell t (centred at index point p) with medium m: Q0 per channel in rgb, and the beams' mean
// direction of travel (weighted by their luminance) in the other vec4's xyz. A beam leaves in the
// cell what it loses across it, E (T*(in) - T*(out)) over the cell's mean chord s along the beam
// (T* = exp(-tau (1 - albedo f)), read where the beam enters and leaves), of which the fraction
// albedo (1 - f) / (1 - albedo f) scatters out of the beam: energy is conserved however thick a
// cell is (sigma_t T* at its centre would deposit up to sigma_t s times the light that enters
// a cell whose centre lies just outside a dense edge).
void ScatteringSourceAt(vec3 p, vec4 m, OUT(vec4) source, OUT(vec4) direction)
{
  vec3 albedo = vec3(m.x, m.y, m.z);
  float f = PhaseForwardFraction();
  vec3 deposit = vec3(0.0f);
  vec3 travel = vec3(0.0f);
  for (int i = 0; i < LightCount; ++i)
  {
    vec3 l;
    float lightDistance, falloff;
    SampleLight(i, LocalOfIndex(p), l, lightDistance, falloff);
    float chord = 1.0f / max(dot(abs(l), 1.0f / ScatteringCellSize), 1e-30f);
    vec3 halfChord = (0.5f * chord) * (LocalToIndex * l);
    vec3 enter = clamp(p + halfChord, vec3(0.0f), Dimensions - 1.0f);
    vec3 leave = clamp(p - halfChord, vec3(0.0f), Dimensions - 1.0f);
    float tauIn = OpticalDepthToLight(i, enter, ExtinctionAt(enter), l, lightDistance);
    float tauOut = OpticalDepthToLight(i, leave, ExtinctionAt(leave), l, lightDistance);
    vec3 beamLoss = exp(-tauIn * (vec3(1.0f) - albedo * f)) - exp(-tauOut * (vec3(1.0f) - albedo * f));
    vec3 lost = LightRadiance[i] * (falloff * PhaseToRadiance / chord) * max(beamLoss, vec3(0.0f));
    deposit += lost;
    travel -= (lost.x + lost.y + lost.z) * l;
  }
  float total = deposit.x + deposit.y + deposit.z;
  vec3 scattered = albedo * (1.0f - f) / max(vec3(1.0f) - albedo * f, vec3(1e-6f));
  source = vec4(m.w > 0.0f ? scattered * deposit : vec3(0.0f), 0.0f);
  direction = vec4(total > 0.0f ? travel / total : vec3(0.0f), 0.0f);
}

void ScatteringSourceTexel(vec3 t, vec4 m, OUT(vec4) source, OUT(vec4) direction)
{
  ScatteringSourceAt(IndexOfGridTexel(t, ScatteringVolumeSize), m, source, direction);
}

// The first moment Q1 along axis a, per channel, of a cell's source and its beams' direction.
vec3 MomentAlong(vec4 source, vec4 direction, int a)
{
  float f = PhaseForwardFraction();
  float reduced = (PhaseMeanCosine() - f) / (1.0f - f);
  float along = a == 0 ? direction.x : (a == 1 ? direction.y : direction.z);
  return vec3(source.x, source.y, source.z) * (reduced * along);
}

// The same of cell c.
vec3 SourceMoment(ivec3 c, int a)
{
  return MomentAlong(ScatteringSourceAt(c), ScatteringDirectionAt(c), a);
}

// The flux-limited diffusion coefficient per channel between two cells: the reduced extinction
// sigmaTr and the fluence phi at the face, and the face's effective gradient (grad phi - 3 Q1
// along the axis). It is 1 / (3 sigma_tr) where the medium is thick and DiffuseEscapeSpeed phi /
// |gradient| where it is thin or empty (diffuse light streams out at most at that speed: |flux|
// <= DiffuseEscapeSpeed phi); at most `reach` (the grid's diagonal: phi / |grad phi| in vacuum
// is about the distance to where the light comes from) where there is no gradient.
vec3 LimitedDiffusion(vec3 sigmaTr, vec3 phi, vec3 gradient, float reach)
{
  vec3 ratio = abs(gradient) / max(phi, vec3(1e-30f));
  vec3 speed = ratio * (1.0f / DiffuseEscapeSpeed);
  vec3 d = inversesqrt(max(9.0f * sigmaTr * sigmaTr + speed * speed, vec3(1e-30f)));
  return min(d, vec3(reach));
}

// How far from a cell's centre its fluence stands for the light that reaches a face toward
// optically thin space, per channel: half a cell, or, in a cell thicker than that, the depth the
// beams reach into it, 1 / (sigma_t (1 - albedo f)). The light a beam leaves in a thick cell lies
// within that depth of the face it came through, and reaches the face again without diffusing
// from the centre: across half an optically thick cell, diffusion would hold in the light that
// a thick cloud's surface sends back, and the cell's fluence would grow with its optical depth.
vec3 SurfaceDepth(vec4 m, float h)
{
  vec3 penetration = vec3(1.0f) /
    max(m.w * (vec3(1.0f) - vec3(m.x, m.y, m.z) * PhaseForwardFraction()), vec3(1e-30f));
  return min(vec3(0.5f * h), penetration);
}

// Whether a cell is optically thin across its width h: the space a cloud's surface faces.
bool OpticallyThin(vec4 m, float h)
{
  return m.w * h < 1.0f;
}

// One half-sweep of red-black Gauss-Seidel at cell c: cells whose x + y + z has the parity
// `parity` take a new value from their neighbours', the others keep theirs.
vec4 ScatteringRelaxTexel(ivec3 c, int parity)
{
  vec4 old = ScatteringFluenceAt(c);
  if ((c.x + c.y + c.z) % 2 != parity)
  {
    return old;
  }
  float g = PhaseMeanCosine();
  vec4 m = ScatteringMediumAt(c);
  vec3 albedo = vec3(m.x, m.y, m.z);
  vec3 sigmaTr = m.w * (vec3(1.0f) - albedo * g);
  vec3 sigmaA = m.w * (vec3(1.0f) - albedo);
  vec3 phi = vec3(old.x, old.y, old.z);
  vec4 source = ScatteringSourceAt(c);
  vec4 direction = ScatteringDirectionAt(c); // read once: every face needs this cell's moment
  vec3 numerator = vec3(source.x, source.y, source.z);
  vec3 denominator = sigmaA;
  ivec3 size = ivec3(ScatteringVolumeSize);
  float reach = length(ScatteringCellSize * (ScatteringVolumeSize - 1.0f));
  for (int face = 0; face < 6; ++face)
  {
    int a = face / 2;
    int s = face % 2 == 0 ? -1 : 1;
    ivec3 n = c;
    if (a == 0) n.x += s;
    if (a == 1) n.y += s;
    if (a == 2) n.z += s;
    float h = a == 0 ? ScatteringCellSize.x : (a == 1 ? ScatteringCellSize.y : ScatteringCellSize.z);
    vec3 moment = MomentAlong(source, direction, a);
    bool outside = n.x < 0 || n.y < 0 || n.z < 0 || n.x >= size.x || n.y >= size.y || n.z >= size.z;
    if (outside)
    {
      // Marshak's vacuum condition on the grid's face: the outflow phi_face / 2, with phi_face
      // between the cell's and 0 as the diffusion across the cell's surface depth allows.
      vec3 d = LimitedDiffusion(sigmaTr, phi, 2.0f * phi / h, reach);
      denominator += d / ((SurfaceDepth(m, h) + 2.0f * d) * h);
      numerator -= 3.0f * d * (float(s) * moment) / h;
    }
    else
    {
      vec4 next = ScatteringFluenceAt(n);
      vec3 phiN = vec3(next.x, next.y, next.z);
      vec4 mN = ScatteringMediumAt(n);
      vec3 sigmaTrN = mN.w * (vec3(1.0f) - vec3(mN.x, mN.y, mN.z) * g);
      vec3 momentFace = 0.5f * (moment + SourceMoment(n, a));
      vec3 gradient = (phiN - phi) / h - 3.0f * float(s) * momentFace;
      vec3 phiFace = 0.5f * (phi + phiN);
      vec3 d;
      if (OpticallyThin(m, h) != OpticallyThin(mN, h))
      {
        // The cloud's surface: each side's diffusion over its own depth, in series.
        vec3 resistance = SurfaceDepth(m, h) / LimitedDiffusion(sigmaTr, phiFace, gradient, reach) +
          SurfaceDepth(mN, h) / LimitedDiffusion(sigmaTrN, phiFace, gradient, reach);
        d = h / max(resistance, vec3(1e-30f));
      }
      else
      {
        d = LimitedDiffusion(0.5f * (sigmaTr + sigmaTrN), phiFace, gradient, reach);
      }
      denominator += d / (h * h);
      numerator += d * phiN / (h * h) - 3.0f * d * (float(s) * momentFace) / h;
    }
  }
  return vec4(max(numerator, vec3(0.0f)) / max(denominator, vec3(1e-30f)), 0.0f);
}

// The diffuse flux at cell c over the fluence, by luminance (|flux| / phi <= 1/2 by the limiter):
// the net direction the diffuse light travels, which the march's phase weighs.
vec4 ScatteringFluxTexel(ivec3 c)
{
  float g = PhaseMeanCosine();
  vec4 m = ScatteringMediumAt(c);
  vec3 sigmaTr = m.w * (vec3(1.0f) - vec3(m.x, m.y, m.z) * g);
  vec4 here = ScatteringFluenceAt(c);
  vec3 phi = vec3(here.x, here.y, here.z);
  ivec3 size = ivec3(ScatteringVolumeSize);
  float reach = length(ScatteringCellSize * (ScatteringVolumeSize - 1.0f));
  vec3 flux = vec3(0.0f);
  for (int a = 0; a < 3; ++a)
  {
    ivec3 lo = c, hi = c;
    if (a == 0) { lo.x = max(c.x - 1, 0); hi.x = min(c.x + 1, size.x - 1); }
    if (a == 1) { lo.y = max(c.y - 1, 0); hi.y = min(c.y + 1, size.y - 1); }
    if (a == 2) { lo.z = max(c.z - 1, 0); hi.z = min(c.z + 1, size.z - 1); }
    float h = a == 0 ? ScatteringCellSize.x : (a == 1 ? ScatteringCellSize.y : ScatteringCellSize.z);
    float span = float(a == 0 ? hi.x - lo.x : (a == 1 ? hi.y - lo.y : hi.z - lo.z)) * h;
    vec4 fl = ScatteringFluenceAt(lo);
    vec4 fh = ScatteringFluenceAt(hi);
    vec3 gradient = (vec3(fh.x, fh.y, fh.z) - vec3(fl.x, fl.y, fl.z)) / max(span, 1e-30f) -
      3.0f * SourceMoment(c, a);
    vec3 d = LimitedDiffusion(sigmaTr, phi, gradient, reach);
    float along = -dot(d * gradient, vec3(1.0f));
    if (a == 0) flux.x = along;
    if (a == 1) flux.y = along;
    if (a == 2) flux.z = along;
  }
  float total = phi.x + phi.y + phi.z;
  return vec4(total > 0.0f ? flux / total : vec3(0.0f), 0.0f);
}

// The first guess on a finer grid: the coarser grid's fluence at the same place.
vec4 ScatteringProlongTexel(vec3 t)
{
  return CoarseFluenceFetch(
    t * ((ScatteringCoarseSize - 1.0f) / max(ScatteringVolumeSize - 1.0f, vec3(1.0f))));
}
