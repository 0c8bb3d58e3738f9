// The lighting models' shared mathematics (filters/CloudLighting.h) and the pieces of the CPU
// march that have exact answers (filters/CloudReferenceMarch.h): the phase functions integrate
// to 1, the scattered fraction behaves as docs/lighting.md says, the trilinear fetch reproduces
// a linear field and clamps at the edges, and the light march's optical depth through a
// homogeneous slab is sigma_t * L, so a slab lit from behind transmits exp(-sigma_t L).
#include "CloudLightVolumes.h"
#include "CloudLighting.h"
#include "CloudReferenceMarch.h"
#include "CloudTransferTable.h"
#include "SupportFixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

using namespace cloudvis;

namespace
{
// 2 pi * integral over mu in [-1, 1] of f(mu), Simpson's rule: the integral over the sphere of
// a function of the angle to one axis.
double IntegrateOverSphere(const std::function<double(float)>& f)
{
  const int intervals = 20000; // even; g = 0.9 peaks within ~0.01 of mu = 1
  const double h = 2.0 / intervals;
  double sum = f(-1.0f) + f(1.0f);
  for (int i = 1; i < intervals; ++i)
  {
    sum += (i % 2 ? 4.0 : 2.0) * f(static_cast<float>(-1.0 + i * h));
  }
  return 2.0 * 3.14159265358979323846 * sum * h / 3.0;
}

using support::LinearTable;

// A volume of n voxels per axis filled by density(i, j, k), with uniforms for the light march.
struct Volume
{
  std::vector<float> Density;
  TransferTable Table;
  MarchUniforms Uniforms;

  Volume(glm::ivec3 n, float spacing, const std::function<float(int, int, int)>& density,
    float sigma_t)
    : Table(LinearTable(sigma_t))
  {
    for (int k = 0; k < n.z; ++k)
      for (int j = 0; j < n.y; ++j)
        for (int i = 0; i < n.x; ++i)
          this->Density.push_back(density(i, j, k));
    this->Uniforms.Density.Values = this->Density.data();
    this->Uniforms.Dimensions = n;
    // A frame whose unit is the world's: local lengths are world lengths.
    this->Uniforms.IndexToLocal = glm::mat4(glm::mat3(spacing));
    this->Uniforms.LocalToIndex = glm::mat3(1.0f / spacing);
    this->Uniforms.Table = &this->Table;
    this->Uniforms.Lighting.LightStep = spacing;
    this->Uniforms.Lighting.LightStepGrowth = 1.0f;
    this->Uniforms.Lighting.LightSteps = 64;
  }
};
}

TEST(Lighting, HenyeyGreensteinIntegratesToOne)
{
  for (float g : { -0.8f, -0.3f, 0.0f, 0.5f, 0.9f })
  {
    EXPECT_NEAR(IntegrateOverSphere([g](float mu) { return HenyeyGreenstein(g, mu); }), 1.0, 1e-3)
      << "g = " << g;
  }
}

TEST(Lighting, HenyeyGreensteinIsIsotropicAtZeroAndForwardForPositiveG)
{
  for (float mu : { -1.0f, -0.4f, 0.0f, 0.7f, 1.0f })
  {
    EXPECT_FLOAT_EQ(HenyeyGreenstein(0.0f, mu), 1.0f / (4.0f * Pi));
  }
  for (float g : { 0.2f, 0.5f, 0.9f })
  {
    EXPECT_GT(HenyeyGreenstein(g, 1.0f), HenyeyGreenstein(g, -1.0f)) << g;
    EXPECT_LT(HenyeyGreenstein(-g, 1.0f), HenyeyGreenstein(-g, -1.0f)) << -g;
  }
}

TEST(Lighting, TwoLobePhaseIntegratesToOneForAnyWeight)
{
  LightingParameters p;
  for (float w : { 0.0f, 0.3f, 0.8f, 1.0f })
  {
    p.PhaseLobeWeight = w;
    for (float scale : { 1.0f, 0.5f, 0.125f })
    {
      EXPECT_NEAR(IntegrateOverSphere([&](float mu) { return Phase(p, mu, scale).x; }), 1.0, 1e-3)
        << "w = " << w << ", eccentricity scale " << scale;
    }
  }
}

// An albedo of 1: the scattered fraction is the same in every channel.
const glm::vec3 White(1.0f);

TEST(Lighting, ScatteredFractionIsSingleScatteringWithoutOctaves)
{
  LightingParameters p;
  p.MultipleScatteringOctaves = 0;
  for (float mu : { -1.0f, -0.2f, 0.5f, 1.0f })
  {
    EXPECT_FLOAT_EQ(ScatteredFraction(p, mu, 0.0f, White).x, Phase(p, mu, 1.0f).x) << mu;
    EXPECT_NEAR(
      ScatteredFraction(p, mu, 1.5f, White).x, Phase(p, mu, 1.0f).x * std::exp(-1.5f), 1e-6f);
  }
}

TEST(Lighting, ScatteredFractionFallsWithOpticalDepth)
{
  LightingParameters p; // three octaves by default
  for (float mu : { -0.9f, 0.0f, 0.9f })
  {
    float previous = ScatteredFraction(p, mu, 0.0f, White).x;
    for (float tau : { 0.1f, 0.5f, 1.0f, 3.0f, 10.0f })
    {
      const float f = ScatteredFraction(p, mu, tau, White).x;
      EXPECT_LT(f, previous) << "mu " << mu << ", tau " << tau;
      previous = f;
    }
  }
}

TEST(Lighting, ScatteredFractionMatchesTheOctaveSum)
{
  // docs/lighting.md: F = sum_{n=0..N} a^n P(mu, c^n) exp(-b^n tau), written out independently.
  LightingParameters p;
  p.MultipleScatteringOctaves = 4;
  p.ScatteringFalloff = 0.6f;
  p.ExtinctionFalloff = 0.4f;
  p.EccentricityFalloff = 0.7f;
  for (float tau : { 0.0f, 0.7f, 2.5f })
  {
    double expected = 0.0;
    for (int n = 0; n <= 4; ++n)
    {
      expected += std::pow(0.6, n) * Phase(p, 0.3f, float(std::pow(0.7, n))).x *
        std::exp(-std::pow(0.4, n) * tau);
    }
    EXPECT_NEAR(ScatteredFraction(p, 0.3f, tau, White).x, expected, 1e-5 * expected) << tau;
  }
}

TEST(Lighting, OctaveNCarriesTheAlbedoNMoreTimes)
{
  // Light scattered n + 1 times is multiplied by the albedo n + 1 times; the caller multiplies
  // once, so octave n carries albedo^n, per channel: F = sum a^n albedo^n P(mu, c^n) exp(-b^n tau).
  LightingParameters p;
  p.MultipleScatteringOctaves = 3;
  p.ScatteringFalloff = p.ExtinctionFalloff = p.EccentricityFalloff = 0.5f; // as written below
  const glm::vec3 albedo(1.0f, 0.9f, 0.5f);
  for (float tau : { 0.0f, 1.2f })
  {
    const glm::vec3 f = ScatteredFraction(p, 0.2f, tau, albedo);
    for (int channel = 0; channel < 3; ++channel)
    {
      double expected = 0.0;
      for (int n = 0; n <= 3; ++n)
      {
        expected += std::pow(0.5 * albedo[channel], n) * Phase(p, 0.2f, float(std::pow(0.5, n))).x *
          std::exp(-std::pow(0.5, n) * tau);
      }
      EXPECT_NEAR(f[channel], expected, 1e-5 * expected)
        << "channel " << channel << ", tau " << tau;
    }
    // Without octaves the albedo plays no part: single scattering carries it once, outside.
    p.MultipleScatteringOctaves = 0;
    EXPECT_EQ(ScatteredFraction(p, 0.2f, tau, albedo), ScatteredFraction(p, 0.2f, tau, White));
    p.MultipleScatteringOctaves = 3;
  }
}

TEST(Lighting, PowderZeroChangesNothingAndOneDarkensThinRegionsToZero)
{
  LightingParameters p;
  LightingParameters withPowder = p;
  for (float tau : { 0.0f, 0.3f, 2.0f })
  {
    p.PowderStrength = 0.0f;
    withPowder.PowderStrength = 1.0f;
    const float plain = ScatteredFraction(p, 0.4f, tau, White).x;
    EXPECT_FLOAT_EQ(plain, ScatteredFraction(p, 0.4f, tau, White).x);
    EXPECT_NEAR(ScatteredFraction(withPowder, 0.4f, tau, White).x,
      plain * (1.0f - std::exp(-2.0f * tau)),
      1e-6f);
    withPowder.PowderStrength = 0.5f;
    EXPECT_NEAR(ScatteredFraction(withPowder, 0.4f, tau, White).x,
      plain * (1.0f - 0.5f * std::exp(-2.0f * tau)),
      1e-6f);
  }
  withPowder.PowderStrength = 1.0f;
  EXPECT_EQ(ScatteredFraction(withPowder, 0.4f, 0.0f, White).x, 0.0f);
}

TEST(Lighting, SampleLightGivesDirectionDistanceAndFalloff)
{
  Light sun;
  sun.Position = glm::dvec3(3.0, 0.0, 0.0);
  sun.FocalPoint = glm::dvec3(1.0, 0.0, 0.0);
  EXPECT_EQ(DirectionTowardLight(sun), glm::dvec3(1.0, 0.0, 0.0));
  sun.Position = glm::dvec3(1e300, 0.0, 1e300); // any distance along its direction
  EXPECT_NEAR(DirectionTowardLight(sun).z, std::sqrt(0.5), 1e-15);
  LocalLight local;
  local.Direction = glm::vec3(1.0f, 0.0f, 0.0f);
  const LightSample s = SampleLight(local, glm::vec3(5.0f, 5.0f, 5.0f));
  EXPECT_FLOAT_EQ(s.Direction.x, 1.0f);
  EXPECT_EQ(s.Distance, 1e30f); // as the GLSL's
  EXPECT_EQ(s.Falloff, 1.0f);

  LocalLight bulb;
  bulb.Positional = true;
  bulb.Position = glm::vec3(0.0f, 4.0f, 0.0f);
  bulb.Attenuation = glm::vec3(0.0f, 0.0f, 1.0f);
  const LightSample b = SampleLight(bulb, glm::vec3(0.0f, 2.0f, 0.0f));
  EXPECT_FLOAT_EQ(b.Direction.y, 1.0f);
  EXPECT_FLOAT_EQ(b.Distance, 2.0f);
  EXPECT_FLOAT_EQ(b.Falloff, 0.25f);
}

TEST(ReferenceMarch, TrilinearFetchReproducesALinearFieldAndClampsAtTheEdges)
{
  const Volume v({ 5, 6, 7 }, 1.0f, [](int i, int j, int k) { return float(i + 2 * j + 3 * k); },
    1.0f);
  for (glm::vec3 p : { glm::vec3(1.25f, 2.5f, 0.75f), glm::vec3(3.9f, 0.1f, 5.5f),
         glm::vec3(0.0f), glm::vec3(4.0f, 5.0f, 6.0f) })
  {
    EXPECT_NEAR(DensityAt(v.Uniforms, p), p.x + 2.0f * p.y + 3.0f * p.z, 1e-4f);
  }
  // CLAMP_TO_EDGE: outside the lattice the edge voxels repeat.
  EXPECT_NEAR(DensityAt(v.Uniforms, glm::vec3(-3.0f, 1.0f, 1.0f)), 0.0f + 2.0f + 3.0f, 1e-5f);
  EXPECT_NEAR(DensityAt(v.Uniforms, glm::vec3(-0.5f, 1.0f, 1.0f)), 5.0f, 1e-5f);
  EXPECT_NEAR(DensityAt(v.Uniforms, glm::vec3(4.6f, 9.0f, 1.0f)), 4.0f + 10.0f + 3.0f, 1e-5f);
  EXPECT_TRUE(InsideVolume(v.Uniforms, glm::vec3(4.0f, 5.0f, 6.0f)));
  EXPECT_FALSE(InsideVolume(v.Uniforms, glm::vec3(4.01f, 5.0f, 6.0f)));
  EXPECT_FALSE(InsideVolume(v.Uniforms, glm::vec3(1.0f, -0.01f, 1.0f)));
}

TEST(ReferenceMarch, IntersectBoxHandlesAxisParallelRays)
{
  const glm::vec2 t = IntersectBox(
    glm::vec3(0.5f, 0.5f, 5.0f), glm::vec3(0.0f, 0.0f, -2.0f), glm::vec3(0.0f), glm::vec3(1.0f));
  EXPECT_FLOAT_EQ(t.x, 2.0f);
  EXPECT_FLOAT_EQ(t.y, 2.5f);
  const glm::vec2 miss = IntersectBox(
    glm::vec3(1.5f, 0.5f, 5.0f), glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(0.0f), glm::vec3(1.0f));
  EXPECT_GE(miss.x, miss.y);
}

TEST(ReferenceMarch, LightMarchThroughAHomogeneousSlabGivesSigmaTimesLength)
{
  // Density 1 in the slab of voxels 20..30 along x; the trilinear ramps on either side add half
  // a voxel each, so the slab is L = 11 voxels thick. The 42 voxels from x = 5 to the exit at 47
  // in one-voxel segments put every kink of the piecewise-linear profile on a segment end: the
  // trapezoid rule is exact.
  const float spacing = 0.05f, sigma_t = 2.0f;
  Volume v(
    { 48, 4, 4 },
    spacing,
    [](int i, int, int) { return i >= 20 && i <= 30 ? 1.0f : 0.0f; },
    sigma_t);
  const glm::vec3 p(5.0f, 1.5f, 1.5f);
  const float L = 11.0f * spacing;
  const float tau = LightOpticalDepth(
    v.Uniforms, p, 0.0f, LocalToIndex(v.Uniforms, glm::vec3(1.0f, 0.0f, 0.0f)), INFINITY);
  EXPECT_NEAR(tau, sigma_t * L, 1e-4f * sigma_t * L);
  // The slab lit from behind transmits exp(-sigma_t L) to the sample.
  EXPECT_NEAR(std::exp(-tau), std::exp(-sigma_t * L), 1e-4f * std::exp(-sigma_t * L));
  // Toward -x there is nothing between the sample and the volume's edge.
  EXPECT_EQ(
    LightOpticalDepth(
      v.Uniforms, p, 0.0f, LocalToIndex(v.Uniforms, glm::vec3(-1.0f, 0.0f, 0.0f)), INFINITY),
    0.0f);
  // The sample's own extinction weighs half the first segment (one voxel here).
  EXPECT_NEAR(
    LightOpticalDepth(
      v.Uniforms, p, 3.0f, LocalToIndex(v.Uniforms, glm::vec3(-1.0f, 0.0f, 0.0f)), INFINITY),
    0.5f * 3.0f * spacing,
    1e-6f);
}

TEST(ReferenceMarch, LightMarchReachesTheVolumesExitOrAPointLightWhateverItsSteps)
{
  // A uniform field: tau is sigma_t times the way to the exit (42 voxels from x = 5, and the
  // margin LightBoxMargin the light march's box has beyond the volume's faces) or to a
  // point light, however few segments and however they grow (the trapezoid rule is exact on a
  // constant). Before issue 15 six growing segments stopped after about 53 voxels whatever lay
  // beyond, and a few one-voxel segments after a few voxels.
  const float spacing = 0.05f, sigma_t = 2.0f;
  Volume v(
    { 48, 4, 4 }, spacing, [](int, int, int) { return 1.0f; }, sigma_t);
  const glm::vec3 p(5.0f, 1.5f, 1.5f);
  const glm::vec3 towardX = LocalToIndex(v.Uniforms, glm::vec3(1.0f, 0.0f, 0.0f));
  struct Steps
  {
    int Count;
    float First; // voxels
    float Growth;
  };
  for (const Steps steps : { Steps{ 64, 1.0f, 1.0f },
         Steps{ 6, 2.0f, 1.6f },
         Steps{ 2, 0.5f, 1.0f },
         Steps{ 3, 30.0f, 2.0f } })
  {
    v.Uniforms.Lighting.LightSteps = steps.Count;
    v.Uniforms.Lighting.LightStep = steps.First * spacing;
    v.Uniforms.Lighting.LightStepGrowth = steps.Growth;
    EXPECT_NEAR(LightOpticalDepth(v.Uniforms, p, sigma_t, towardX, INFINITY),
      sigma_t * (42.0f + LightBoxMargin) * spacing,
      1e-5f)
      << steps.Count << " steps";
    // A point light 15 voxels away: the way ends there.
    EXPECT_NEAR(LightOpticalDepth(v.Uniforms, p, sigma_t, towardX, 15.0f * spacing),
      sigma_t * 15.0f * spacing,
      1e-5f)
      << steps.Count << " steps";
  }
}

TEST(ReferenceMarch, ASampleAHairOutsideAFaceGetsItsShadow)
{
  // A sample on the face y = 3 that rounding put just outside, lit along the face: its light
  // starts on the face and crosses the 42 voxels to the exit, plus LightBoxMargin (before issue 15:
  // no shadow at all).
  const float spacing = 0.05f, sigma_t = 2.0f;
  const Volume v(
    { 48, 4, 4 }, spacing, [](int, int, int) { return 1.0f; }, sigma_t);
  const glm::vec3 outside(5.0f, 3.0f + 2e-6f, 1.5f);
  ASSERT_FALSE(InsideVolume(v.Uniforms, outside));
  EXPECT_NEAR(LightOpticalDepth(v.Uniforms,
                outside,
                sigma_t,
                LocalToIndex(v.Uniforms, glm::vec3(1.0f, 0.0f, 0.0f)),
                INFINITY),
    sigma_t * (42.0f + LightBoxMargin) * spacing,
    1e-5f);
}

TEST(LightVolumes, HoldTheOpticalDepthTowardEachLightAndTheMarchInterpolatesThem)
{
  // A uniform field of 33 x 9 x 9 voxels: the grid has 17 x 5 x 5 texels per light, corner-aligned.
  // Toward a sun along +x the optical depth is sigma_t times the way to the exit, linear in x, so
  // the trilinear lookup between texels is exact anywhere; toward a point light inside the field
  // it is sigma_t times the distance to the light.
  const float spacing = 0.05f, sigma_t = 2.0f;
  Volume v(
    { 33, 9, 9 }, spacing, [](int, int, int) { return 1.0f; }, sigma_t);
  v.Uniforms.Step = 0.5f * spacing; // the volumes' own march: uniform steps of the view's step
  v.Uniforms.LongestRaySamples = 80;
  LocalLight sun;
  sun.Direction = glm::vec3(1.0f, 0.0f, 0.0f);
  sun.IndexDirection = LocalToIndex(v.Uniforms, sun.Direction);
  sun.Radiance = glm::vec3(1.0f);
  LocalLight lamp;
  lamp.Positional = true;
  lamp.Position = LocalOfIndex(v.Uniforms, glm::vec3(16.0f, 4.0f, 4.0f));
  lamp.Attenuation = glm::vec3(1.0f, 0.0f, 0.0f);
  v.Uniforms.Lights = { sun, lamp };
  LightVolumes volumes;
  ComputeLightVolumes(v.Uniforms, volumes);
  EXPECT_EQ(volumes.Size, glm::ivec3(17, 5, 5));
  EXPECT_EQ(volumes.Depth.size(), std::size_t(17 * 5 * 5 * 2));
  for (const glm::vec3 p : { glm::vec3(0.0f, 0.0f, 0.0f),
         glm::vec3(3.3f, 1.7f, 6.1f),
         glm::vec3(31.9f, 8.0f, 0.4f),
         glm::vec3(32.0f, 4.0f, 4.0f) })
  {
    EXPECT_NEAR(LightVolumeDepth(volumes, v.Uniforms, 0, p),
      sigma_t * (32.0f - p.x + LightBoxMargin) * spacing,
      1e-4f)
      << p.x << " " << p.y << " " << p.z;
  }
  // The lamp's block, at texel centres (between them the distance is not linear).
  for (const glm::vec3 p : { glm::vec3(0.0f, 0.0f, 0.0f), glm::vec3(32.0f, 8.0f, 2.0f) })
  {
    EXPECT_NEAR(LightVolumeDepth(volumes, v.Uniforms, 1, p),
      sigma_t * glm::length(p - glm::vec3(16.0f, 4.0f, 4.0f)) * spacing,
      1e-4f);
  }
  // The march reads them when it is given them, and marches toward each light when not: toward
  // the sun both are exact on this field, so a ray's color is the same.
  v.Uniforms.Lights = { sun };
  ComputeLightVolumes(v.Uniforms, volumes);
  v.Uniforms.Lighting.Model = LightingModel::March;
  v.Uniforms.Step = spacing;
  v.Uniforms.MaximumSamples = 200;
  const glm::vec3 nearPoint = LocalOfIndex(v.Uniforms, glm::vec3(-5.0f, 3.3f, 2.2f));
  const glm::vec3 farPoint = LocalOfIndex(v.Uniforms, glm::vec3(40.0f, 5.1f, 6.0f));
  const glm::vec4 nested = MarchRay(v.Uniforms, nearPoint, farPoint);
  v.Uniforms.LightDepths = &volumes;
  const glm::vec4 fromVolumes = MarchRay(v.Uniforms, nearPoint, farPoint);
  ASSERT_GT(nested.r, 0.0f);
  EXPECT_NEAR(fromVolumes.r, nested.r, 2e-3f * nested.r);
  EXPECT_EQ(fromVolumes.a, nested.a);
  v.Uniforms.Lighting.Transmittance = LightTransmittance::Nested; // the quality setting
  EXPECT_EQ(MarchRay(v.Uniforms, nearPoint, farPoint), nested);
}

TEST(ReferenceMarch, AutomaticDistancesAreFourAndTwoVoxelsInLocalUnits)
{
  // Voxels of 0.3 world units: the frame's unit is 0.25, the nearest power of two.
  std::vector<float> density(8, 0.0f);
  TransferTable table = LinearTable(1.0f);
  MarchSetup setup;
  setup.Geometry.Dimensions = glm::ivec3(2);
  setup.Geometry.IndexToWorld = glm::dmat4(glm::dmat3(0.3));
  setup.Table = &table;
  MarchUniforms u;
  LocalFrame frame;
  ASSERT_FALSE(SetUpMarch(setup, u, &frame)) << SetUpMarch(setup, u).Message;
  EXPECT_EQ(frame.Unit, 0.25);
  EXPECT_FLOAT_EQ(u.Lighting.DerivativeDistance, 4.0f * 0.3f / 0.25f);
  EXPECT_FLOAT_EQ(u.Lighting.LightStep, 2.0f * 0.3f / 0.25f);
  EXPECT_FLOAT_EQ(u.Step, 0.3f / 0.25f) << "one voxel by default";
  setup.Lighting.DerivativeDistance = 0.3f;
  setup.Lighting.LightStep = 0.1f;
  ASSERT_FALSE(SetUpMarch(setup, u));
  EXPECT_FLOAT_EQ(u.Lighting.DerivativeDistance, 0.3f / 0.25f);
  EXPECT_FLOAT_EQ(u.Lighting.LightStep, 0.1f / 0.25f);
}
