// The droplet optics behind every renderer's phase function: the Mie series against published
// exact values and the identities it must satisfy, the water refractive index table, and the
// shared table (its normalisation and CDF, its moments, the cloudbow and glory, its evaluation
// and its sampler), the refusal of bad input and the cache.
#include "CloudDropletOptics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using namespace cloudvis;

namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr int N = DropletPhaseTable::NodeCount;

// The default table most tests share (r_e = 10 um, v_e = 0.1, red/green/blue): computed once.
const DropletPhaseTable& Table10()
{
  return DropletPhase(10.0f);
}

// 1 - mu_i in double, exact where float would round mu_i to 1.
double NodeOneMinusMu(int i)
{
  const double s = double(i) / (N - 1);
  const double halfTheta = 0.5 * Pi * s * s;
  return 2.0 * std::sin(halfTheta) * std::sin(halfTheta);
}

// 2 pi * integral over [-1, 1] of the table's piecewise-linear function in one channel, and of
// the function times mu and times P_2(mu) (exact per bin: Simpson's rule on a cubic).
struct Moments
{
  double Integral = 0.0, Chi1 = 0.0, Chi2 = 0.0;
};
Moments PiecewiseLinearMoments(const DropletPhaseTable& table, int c)
{
  Moments moments;
  auto P2 = [](double mu) { return 0.5 * (3.0 * mu * mu - 1.0); };
  for (int i = 0; i + 1 < N; ++i)
  {
    const double w0 = NodeOneMinusMu(i), w1 = NodeOneMinusMu(i + 1), h = w1 - w0;
    const double p0 = table.Phase[size_t(i)][c], p1 = table.Phase[size_t(i) + 1][c];
    const double mu0 = 1.0 - w0, mu1 = 1.0 - w1, muMid = 1.0 - 0.5 * (w0 + w1);
    const double pMid = 0.5 * (p0 + p1);
    moments.Integral += 2.0 * Pi * h * pMid;
    moments.Chi1 += 2.0 * Pi * h / 6.0 * (p0 * mu0 + 4.0 * pMid * muMid + p1 * mu1);
    moments.Chi2 += 2.0 * Pi * h / 6.0 * (p0 * P2(mu0) + 4.0 * pMid * P2(muMid) + p1 * P2(mu1));
  }
  return moments;
}

// The message of the std::invalid_argument that f throws ("" if it throws none).
template<class F>
std::string InvalidArgumentMessage(F f)
{
  try
  {
    f();
  }
  catch (const std::invalid_argument& error)
  {
    return error.what();
  }
  return "";
}
} // namespace

// Wiscombe, W. J. (1979, rev. 1996), "Mie scattering calculations: advances in technique and
// fast, vector-speed computer codes", NCAR/TN-140+STR: the MIEV0 test cases as printed by his
// test driver MVTstNew.f (Q_ext, Q_sca and g Q_sca to 7 digits). Wiscombe writes m = n - i k;
// this code's convention is m = n + i k. Observed largest deviation 2.4e-7 relative (the
// rounding of the published digits); before the D_n start was moved up, the x = 10^4 water case
// was 3.4e-3 off.
TEST(DropletOptics, MieSeriesMatchesWiscombeTestCases)
{
  struct Case
  {
    double x;
    std::complex<double> m;
    double Q_ext, Q_sca, gQ_sca;
  };
  const Case cases[] = {
    { 1.0, { 1.33, 1e-5 }, 9.395198e-02, 9.392330e-02, 1.733048e-02 },
    { 100.0, { 1.33, 1e-5 }, 2.101321, 2.096594, 1.821854 },
    { 10000.0, { 1.33, 1e-5 }, 2.004089, 1.723857, 1.564987 },
    { 10.0, { 0.75, 0.0 }, 2.232265, 2.232265, 2.001164 },
    { 1000.0, { 0.75, 0.0 }, 1.997908, 1.997908, 1.688121 },
    { 100.0, { 1.5, 1.0 }, 2.097502, 1.283697, 1.091466 },
    { 10000.0, { 1.5, 1.0 }, 2.004368, 1.236574, 1.046525 },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE("x = " + std::to_string(c.x) + ", m = " + std::to_string(c.m.real()) + " + " +
      std::to_string(c.m.imag()) + " i");
    const MieSphere sphere = ComputeMieSphere(c.x, c.m);
    EXPECT_NEAR(sphere.Q_ext / c.Q_ext, 1.0, 1e-6);
    EXPECT_NEAR(sphere.Q_sca / c.Q_sca, 1.0, 1e-6);
    EXPECT_NEAR(sphere.g * sphere.Q_sca / c.gQ_sca, 1.0, 1e-6);
    EXPECT_EQ(int(sphere.a_n.size()), MieTermCount(c.x));
  }
}

// Bohren & Huffman (1983), "Absorption and Scattering of Light by Small Particles", appendix A:
// the sample run of BHMIE (m = 1.55, r = 0.525 um, wavelength 0.6328 um) prints Q_sca = 3.10543
// and Q_back = 2.92534, Q_back = 4 |S1(180 deg)|^2 / x^2 being a test of the angular functions.
// Observed deviations 1e-6 relative (the published digits).
TEST(DropletOptics, MieSeriesMatchesBohrenHuffmanExample)
{
  const double x = 2.0 * Pi * 0.525 / 0.6328;
  const MieSphere sphere = ComputeMieSphere(x, { 1.55, 0.0 });
  std::complex<double> S1, S2;
  sphere.Amplitudes(-1.0, S1, S2);
  EXPECT_NEAR(sphere.Q_sca / 3.10543, 1.0, 1e-5);
  EXPECT_NEAR(sphere.Q_ext / 3.10543, 1.0, 1e-5);
  EXPECT_NEAR(4.0 * std::norm(S1) / (x * x) / 2.92534, 1.0, 1e-5);
  // At 180 degrees S2 = -S1 for a sphere.
  EXPECT_NEAR(std::abs(S1 + S2), 0.0, 1e-9 * std::abs(S1));
}

// Two identities tie the angular sums to the coefficients: the optical theorem, Q_ext =
// 4 Re S(0) / x^2 with S1(0) = S2(0), and the phase function's unit integral over the sphere,
// here by Simpson's rule in s = sqrt(theta / pi) (dense at the forward peak, as the table is).
// Water at x = 100 and 3000 (drops of the widest tables). Observed integral errors 2e-12 (x =
// 100, 8000 intervals) and 1.1e-9 (x = 3000, 16000 intervals; 8000 leave 1e-5, the quadrature
// not the series).
TEST(DropletOptics, MieAmplitudesObeyOpticalTheoremAndUnitIntegral)
{
  for (double x : { 100.0, 3000.0 })
  {
    const int intervals = x < 1000.0 ? 8000 : 16000;
    SCOPED_TRACE("x = " + std::to_string(x));
    const MieSphere sphere = ComputeMieSphere(x, WaterRefractiveIndex(0.55));
    std::complex<double> S1, S2;
    sphere.Amplitudes(1.0, S1, S2);
    EXPECT_NEAR(std::abs(S1 - S2), 0.0, 1e-12 * std::abs(S1));
    EXPECT_NEAR(4.0 * S1.real() / (x * x) / sphere.Q_ext, 1.0, 1e-10);

    double integral = 0.0;
    for (int k = 0; k <= intervals; ++k)
    {
      const double s = double(k) / intervals, theta = Pi * s * s;
      const double weight = (k == 0 || k == intervals) ? 1.0 : (k % 2 ? 4.0 : 2.0);
      // d(Omega) = 2 pi sin(theta) d(theta), d(theta) = 2 pi s ds.
      integral += weight * sphere.Phase(std::cos(theta)) * std::sin(theta) * 2.0 * Pi * s;
    }
    integral *= 2.0 * Pi / (3.0 * intervals);
    EXPECT_NEAR(integral, 1.0, 1e-8);
  }
}

// Hale & Querry (1973), Appl. Opt. 12, 555, table I: at its rows the index is the table's, in
// between it is interpolated (the real part linearly, the imaginary part in its logarithm).
TEST(DropletOptics, WaterRefractiveIndexFollowsHaleQuerry)
{
  EXPECT_NEAR(WaterRefractiveIndex(0.55).real(), 1.333, 1e-12);
  EXPECT_NEAR(WaterRefractiveIndex(0.55).imag() / 1.96e-9, 1.0, 1e-12);
  EXPECT_NEAR(WaterRefractiveIndex(0.40).real(), 1.339, 1e-12);
  EXPECT_NEAR(WaterRefractiveIndex(0.80).imag() / 1.25e-7, 1.0, 1e-12);
  // Halfway between 0.675 (1.331, 2.23e-8) and 0.700 (1.331, 3.35e-8): the geometric mean of k.
  EXPECT_NEAR(WaterRefractiveIndex(0.6875).imag() / std::sqrt(2.23e-8 * 3.35e-8), 1.0, 1e-12);
  double previous = 2.0;
  for (double wavelength = 0.4; wavelength <= 0.8; wavelength += 0.01)
  {
    const std::complex<double> m = WaterRefractiveIndex(wavelength);
    EXPECT_GE(m.real(), 1.329);
    EXPECT_LE(m.real(), previous); // normal dispersion
    EXPECT_GT(m.imag(), 9e-10);
    EXPECT_LT(m.imag(), 1.6e-7);
    previous = m.real();
  }
}

// The table is normalised for what the renderers evaluate: the piecewise-linear function
// integrates to 1 per channel (observed |error| 1.4e-9: float rounding; without the
// renormalisation the Mie values at the nodes are 3e-5 to 5e-5 off) and the CDF runs from
// exactly 0 to exactly 1 as the cumulative integral of that function.
TEST(DropletOptics, TableIntegratesToOneAndItsCdfEndsAtOne)
{
  const DropletPhaseTable& table = Table10();
  ASSERT_EQ(int(table.Phase.size()), N);
  ASSERT_EQ(int(table.CDF.size()), N);
  for (int c = 0; c < 3; ++c)
  {
    SCOPED_TRACE("channel " + std::to_string(c));
    EXPECT_NEAR(PiecewiseLinearMoments(table, c).Integral, 1.0, 1e-8);
    EXPECT_EQ(table.CDF[0][c], 0.0f);
    EXPECT_EQ(table.CDF[size_t(N) - 1][c], 1.0f);
    double cumulative = 0.0, largestDeviation = 0.0;
    for (int i = 0; i + 1 < N; ++i)
    {
      EXPECT_GE(table.Phase[size_t(i)][c], 0.0f);
      EXPECT_LE(table.CDF[size_t(i)][c], table.CDF[size_t(i) + 1][c]);
      cumulative += Pi * (double(table.Phase[size_t(i)][c]) + table.Phase[size_t(i) + 1][c]) *
        (NodeOneMinusMu(i + 1) - NodeOneMinusMu(i));
      largestDeviation =
        std::max(largestDeviation, std::abs(cumulative - table.CDF[size_t(i) + 1][c]));
    }
    EXPECT_LT(largestDeviation, 2e-7); // observed 3.1e-8: float rounding of the CDF
  }
}

// g and chi_2 are those of the piecewise-linear function (observed 3e-8: float rounding), and
// that function's g agrees with g from the Mie coefficients (observed 5e-6), which no angular
// quadrature enters: the angular sums and the nodes resolve the forward peak.
TEST(DropletOptics, MomentsAreThoseOfThePiecewiseLinearFunction)
{
  const DropletPhaseTable& table = Table10();
  for (int c = 0; c < 3; ++c)
  {
    SCOPED_TRACE("channel " + std::to_string(c));
    const Moments moments = PiecewiseLinearMoments(table, c);
    // Half a float ulp at 0.8 is 3e-8; the trapezoid rule instead of the exact integral would
    // be 2.4e-7 off.
    EXPECT_NEAR(table.g[c], moments.Chi1, 1e-7);
    EXPECT_NEAR(table.chi_2[c], moments.Chi2, 1e-7);
    const DropletPolydisperseOptics bulk =
      ComputeDropletPolydisperse(table.r_e, table.v_e, table.WavelengthsUm[c], {});
    EXPECT_NEAR(table.g[c], bulk.g, 5e-5);
    EXPECT_NEAR(table.Q_ext[c], bulk.Q_ext, 1e-6);
    // Large drops: Q_ext near its limit 2, albedo near 1 in the visible.
    EXPECT_NEAR(table.Q_ext[c], 2.09, 0.03);
    EXPECT_GT(table.SingleScatteringAlbedo[c], 0.99999f);
    // A forward peak far sharper than Henyey-Greenstein's with the same g (chi_2 = g^2).
    EXPECT_GT(table.chi_2[c], table.g[c] * table.g[c] + 0.03f);
  }
}

// The radius quadrature integrates the modified gamma distribution of Hansen & Travis (1974):
// its nodes and weights reproduce the r_e and v_e asked for across the valid ranges. Observed
// relative deviations up to 5.6e-5 in r_e and 8.2e-4 in v_e, both from the truncated tails,
// which hold 1e-5 of the weight each (a wrong exponent, (1 - 2 v_e) / v_e, makes r_e 10% off).
TEST(DropletOptics, RadiusQuadratureReproducesEffectiveRadiusAndVariance)
{
  for (double r_e : { 2.0, 10.0, 30.0 })
  {
    for (double v_e : { 0.01, 0.1, 0.3 })
    {
      // The red end: the fewest radii, the coarsest step in r (and seconds fewer than blue).
      SCOPED_TRACE("r_e " + std::to_string(r_e) + ", v_e " + std::to_string(v_e));
      const DropletPolydisperseOptics optics = ComputeDropletPolydisperse(r_e, v_e, 0.8, {});
      EXPECT_NEAR(optics.QuadratureEffectiveRadiusUm / r_e, 1.0, 5e-4);
      EXPECT_NEAR(optics.QuadratureEffectiveVariance / v_e, 1.0, 5e-3);
      EXPECT_LT(optics.RadiusMinUm, r_e);
      EXPECT_GT(optics.RadiusMaxUm, r_e);
    }
  }
}

// Hu, Y. X. and Stamnes, K. (1993), "An accurate parameterization of the radiative properties of
// water clouds suitable for use in climate models", J. Climate 6, 728-742, as tabulated in AER's
// RRTMG_SW (rrtmg_sw_init.f90, asyliq1, band 25 = 16000-22650 cm^-1, i.e. 0.44-0.625 um, which
// holds 550 nm): g = 0.8630578 at r_e = 9.5 um and 0.8644587 at 10.5 um, so 0.86376 at 10 um.
// Observed: 0.86410 at 550 nm (v_e = 0.1), 0.04% above; the brief's 1% becomes 0.3%, 7x that.
TEST(DropletOptics, AsymmetryAt550nmMatchesHuStamnes)
{
  const DropletPhaseTable& table = Table10();
  ASSERT_EQ(table.WavelengthsUm.y, 0.55f);
  EXPECT_NEAR(table.g.y / 0.86376, 1.0, 3e-3);
}

// The primary cloudbow: its maximum between 130 and 150 degrees. Descartes' angle for m = 1.333
// is 137.9 degrees; for cloud droplets interference moves the maximum to larger scattering
// angles (Fraser 1983, J. Opt. Soc. Am. 73, 1626; Airy theory gives 139.8 degrees for 10-um drops
// and is known to underestimate the shift at such sizes). Observed at 550 nm: 141.51 degrees
// (the node of largest value; red 141.67, blue 141.36), 6.3-7.2 times the phase function at 125
// degrees. The glory: a backscatter peak, P(180 deg) 3.7-4.7 times P(175 deg).
TEST(DropletOptics, CloudbowAndGlory)
{
  const DropletPhaseTable& table = Table10();
  for (int c = 0; c < 3; ++c)
  {
    SCOPED_TRACE("channel " + std::to_string(c));
    int bow = -1;
    for (int i = 0; i < N; ++i)
    {
      const double degrees = DropletPhaseNodeAngle(i) * 180.0 / Pi;
      if (degrees > 130.0 && degrees < 150.0 &&
        (bow < 0 || table.Phase[size_t(i)][c] > table.Phase[size_t(bow)][c]))
      {
        bow = i;
      }
    }
    const double bowDegrees = DropletPhaseNodeAngle(bow) * 180.0 / Pi;
    EXPECT_GT(bowDegrees, 140.8);
    EXPECT_LT(bowDegrees, 142.6);
    // A real maximum, well above the dark band the bow rises from.
    const float at125 = EvaluateDropletPhase(table, float(std::cos(125.0 * Pi / 180.0)))[c];
    EXPECT_GT(table.Phase[size_t(bow)][c], 5.0f * at125);

    const float at180 = EvaluateDropletPhase(table, -1.0f)[c];
    const float at175 = EvaluateDropletPhase(table, float(std::cos(175.0 * Pi / 180.0)))[c];
    EXPECT_GT(at180, 3.0f * at175);
  }
  const double green = DropletPhaseNodeAngle(1815) * 180.0 / Pi;
  EXPECT_NEAR(green, 141.51, 0.01); // the node the maximum was observed at
  EXPECT_GE(table.Phase[1815].y, table.Phase[1814].y);
  EXPECT_GE(table.Phase[1815].y, table.Phase[1816].y);
}

// EvaluateDropletPhase is the piecewise-linear function in mu: it returns the node values at the
// nodes, the mean of two nodes halfway between them in mu, and clamps mu outside [-1, 1].
TEST(DropletOptics, EvaluationIsPiecewiseLinearInMu)
{
  const DropletPhaseTable& table = Table10();
  for (int i = 40; i + 1 < N; i += 37)
  {
    SCOPED_TRACE("node " + std::to_string(i));
    const float muNode = 1.0f - DropletPhaseNodeOneMinusCosine(i);
    const glm::vec3 atNode = EvaluateDropletPhase(table, muNode);
    const float muMid =
      1.0f - 0.5f * (DropletPhaseNodeOneMinusCosine(i) + DropletPhaseNodeOneMinusCosine(i + 1));
    const glm::vec3 atMid = EvaluateDropletPhase(table, muMid);
    for (int c = 0; c < 3; ++c)
    {
      const float p0 = table.Phase[size_t(i)][c], p1 = table.Phase[size_t(i) + 1][c];
      // Float mu resolves a bin to about 6e-8 / (bin width in mu) of its width.
      const float resolution =
        6e-8f / (DropletPhaseNodeOneMinusCosine(i + 1) - DropletPhaseNodeOneMinusCosine(i));
      EXPECT_NEAR(atNode[c], p0, 1e-5f * p0 + resolution * std::abs(p1 - p0));
      EXPECT_NEAR(atMid[c], 0.5f * (p0 + p1), 1e-5f * p0 + resolution * std::abs(p1 - p0));
    }
  }
  EXPECT_EQ(EvaluateDropletPhase(table, 1.0f), table.Phase[0]);
  EXPECT_EQ(EvaluateDropletPhase(table, 2.0f), table.Phase[0]);
  EXPECT_EQ(EvaluateDropletPhase(table, -1.0f), table.Phase[size_t(N) - 1]);
  EXPECT_EQ(EvaluateDropletPhase(table, -3.0f), table.Phase[size_t(N) - 1]);
}

// Sampling: 200k fixed-seed samples per channel, histogrammed in 64 groups of 32 bins, match the
// table's probabilities (observed chi-square 58.6, 61.0 and 81.8 for 63 degrees of freedom).
TEST(DropletOptics, SamplingMatchesTheTableProbabilities)
{
  const DropletPhaseTable& table = Table10();
  constexpr int groups = 64, perGroup = N / groups, samples = 200000;
  std::mt19937 random(12345);
  for (int c = 0; c < 3; ++c)
  {
    SCOPED_TRACE("channel " + std::to_string(c));
    std::vector<int> histogram(groups, 0);
    for (int s = 0; s < samples; ++s)
    {
      const float u = float(random() >> 8) * (1.0f / 16777216.0f); // [0, 1) in float
      const float mu = SampleDropletPhaseCosine(table, c, u);
      ASSERT_GE(mu, -1.0f);
      ASSERT_LE(mu, 1.0f);
      const float theta = 2.0f * std::asin(std::sqrt(0.5f * (1.0f - mu)));
      const int bin = std::min(N - 2, int(DropletPhaseNodeCoordinate(theta)));
      histogram[size_t(std::min(groups - 1, bin / perGroup))]++;
    }
    double chiSquare = 0.0;
    for (int g = 0; g < groups; ++g)
    {
      const int end = std::min(N - 1, (g + 1) * perGroup);
      const double expected =
        samples * (double(table.CDF[size_t(end)][c]) - table.CDF[size_t(g * perGroup)][c]);
      chiSquare += (histogram[size_t(g)] - expected) * (histogram[size_t(g)] - expected) / expected;
    }
    EXPECT_LT(chiSquare, 110.0);
  }
}

// Inside a bin the sampler inverts the linear-in-mu density exactly: every u in [CDF_i,
// CDF_{i+1}) lands in bin i, u = CDF_i at mu_i, and the fraction of the bin's probability below
// the returned mu is f = (u - CDF_i) / (CDF_{i+1} - CDF_i), computed from the float u actually
// passed: near 1 a float u resolves a backward bin's probability (1e-5) only to 6e-8. Observed
// 4.2e-5 in bins of width 1e-3 in mu and more, where float mu resolves the position inside the bin
// to 1e-4. A constant density is sampled uniformly.
TEST(DropletOptics, SamplingInsideABinInvertsTheLinearDensity)
{
  const DropletPhaseTable& table = Table10();
  for (int c = 0; c < 3; ++c)
  {
    for (int i : { 0, 1, 5, 30, 100, 500, 1000, 1500, 1815, 2000, 2040, N - 2 })
    {
      SCOPED_TRACE("channel " + std::to_string(c) + ", bin " + std::to_string(i));
      const float c0 = table.CDF[size_t(i)][c], c1 = table.CDF[size_t(i) + 1][c];
      const float muHigh = 1.0f - DropletPhaseNodeOneMinusCosine(i);
      const float muLow = 1.0f - DropletPhaseNodeOneMinusCosine(i + 1);
      if (c1 > c0)
      {
        EXPECT_EQ(SampleDropletPhaseCosine(table, c, c0), muHigh);
      }
      for (int k = 0; k < 64; ++k)
      {
        const float u = c0 + (c1 - c0) * (k + 0.5f) / 64.0f;
        if (!(u >= c0 && u < c1))
        {
          continue;
        }
        const float mu = SampleDropletPhaseCosine(table, c, u);
        EXPECT_LE(mu, muHigh);
        EXPECT_GE(mu, muLow);
      }
      const double w0 = DropletPhaseNodeOneMinusCosine(i),
                   w1 = DropletPhaseNodeOneMinusCosine(i + 1);
      if (w1 - w0 < 1e-3)
      {
        continue; // float mu cannot resolve the position inside the bin well enough
      }
      const double p0 = table.Phase[size_t(i)][c], p1 = table.Phase[size_t(i) + 1][c];
      for (double target : { 0.1, 0.5, 0.9 })
      {
        const float u = float(c0 + target * (c1 - c0));
        const double f = (double(u) - c0) / (double(c1) - c0);
        const float mu = SampleDropletPhaseCosine(table, c, u);
        const double t = ((1.0 - double(mu)) - w0) / (w1 - w0);
        const double fraction = (p0 * t + 0.5 * (p1 - p0) * t * t) / (0.5 * (p0 + p1));
        EXPECT_NEAR(fraction, f, 1e-4);
      }
    }
  }

  // A flat table: the sampler is then exactly uniform in mu over every bin.
  DropletPhaseTable flat;
  flat.Phase.assign(N, glm::vec3(float(1.0 / (4.0 * Pi))));
  flat.CDF.assign(N, glm::vec3(0.0f));
  for (int i = 0; i < N; ++i)
  {
    flat.CDF[size_t(i)] = glm::vec3(float(0.5 * NodeOneMinusMu(i)));
  }
  flat.CDF[size_t(N) - 1] = glm::vec3(1.0f);
  for (float u : { 0.1f, 0.25f, 0.5f, 0.75f, 0.9f })
  {
    EXPECT_NEAR(SampleDropletPhaseCosine(flat, 1, u), 1.0f - 2.0f * u, 2e-6f);
  }
  // The ends and garbage stay inside [-1, 1].
  for (float u : { 0.0f, 1.0f, -1.0f, 2.0f, std::numeric_limits<float>::quiet_NaN() })
  {
    const float mu = SampleDropletPhaseCosine(flat, 0, u);
    EXPECT_GE(mu, -1.0f);
    EXPECT_LE(mu, 1.0f);
  }
}

TEST(DropletOptics, NodeCoordinateInvertsNodeAngle)
{
  for (int i = 0; i < N; i += 89)
  {
    EXPECT_NEAR(DropletPhaseNodeCoordinate(DropletPhaseNodeAngle(i)), float(i), 1e-3f * (i + 1));
  }
  EXPECT_EQ(DropletPhaseNodeAngle(0), 0.0f);
  EXPECT_NEAR(DropletPhaseNodeAngle(N - 1), float(Pi), 1e-6f);
}

// Bad input is refused with a message that names the quantity, the value and the range.
TEST(DropletOptics, BadInputIsRefusedNamingTheQuantity)
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  std::string message = InvalidArgumentMessage([] { DropletPhase(1.5f); });
  EXPECT_NE(message.find("r_e = 1.5 um"), std::string::npos) << message;
  EXPECT_NE(message.find("[2, 30] um"), std::string::npos) << message;
  message = InvalidArgumentMessage([] { DropletPhase(31.0f); });
  EXPECT_NE(message.find("r_e = 31"), std::string::npos) << message;
  message = InvalidArgumentMessage([&] { DropletPhase(nan); });
  EXPECT_NE(message.find("r_e"), std::string::npos) << message;
  EXPECT_NE(message.find("not finite"), std::string::npos) << message;
  message = InvalidArgumentMessage([] { DropletPhase(10.0f, 0.35f); });
  EXPECT_NE(message.find("v_e = 0.35"), std::string::npos) << message;
  EXPECT_NE(message.find("[0.01, 0.3]"), std::string::npos) << message;
  message = InvalidArgumentMessage([&] { DropletPhase(10.0f, inf); });
  EXPECT_NE(message.find("v_e"), std::string::npos) << message;
  message =
    InvalidArgumentMessage([] { DropletPhase(10.0f, 0.1f, glm::vec3(0.68f, 0.9f, 0.44f)); });
  EXPECT_NE(message.find("wavelength lambda = 0.9 um"), std::string::npos) << message;
  EXPECT_NE(message.find("[0.4, 0.8] um"), std::string::npos) << message;
  message = InvalidArgumentMessage([&] { ComputeDropletPhaseTable(10.0f, 0.1f, glm::vec3(nan)); });
  EXPECT_NE(message.find("wavelength"), std::string::npos) << message;
  message = InvalidArgumentMessage([] { WaterRefractiveIndex(0.3); });
  EXPECT_NE(message.find("wavelength lambda = 0.3"), std::string::npos) << message;
  message = InvalidArgumentMessage([] { ComputeMieSphere(-1.0, { 1.33, 0.0 }); });
  EXPECT_NE(message.find("x = -1"), std::string::npos) << message;
  message = InvalidArgumentMessage([] { ComputeDropletPolydisperse(10.0, 0.005, 0.55, {}); });
  EXPECT_NE(message.find("v_e = 0.005"), std::string::npos) << message;
  // The ends of the ranges are valid, also as floats (0.01f is below 0.01).
  EXPECT_EQ(
    InvalidArgumentMessage([] { ValidateDropletParameters(2.0f, 0.01f, glm::vec3(0.4f)); }), "");
  EXPECT_EQ(
    InvalidArgumentMessage([] { ValidateDropletParameters(30.0f, 0.3f, glm::vec3(0.8f)); }), "");
}

// The cache: one table per exact parameter set, the same object for every caller and thread.
TEST(DropletOptics, CacheReturnsOneTablePerParametersToAllThreads)
{
  std::vector<const DropletPhaseTable*> seen(4, nullptr);
  std::vector<std::thread> threads;
  for (size_t t = 0; t < seen.size(); ++t)
  {
    threads.emplace_back([&seen, t] { seen[t] = &DropletPhase(2.0f, 0.01f); });
  }
  for (std::thread& thread : threads)
  {
    thread.join();
  }
  for (const DropletPhaseTable* table : seen)
  {
    EXPECT_EQ(table, seen[0]);
  }
  EXPECT_EQ(seen[0]->r_e, 2.0f);
  EXPECT_EQ(seen[0]->v_e, 0.01f);
  EXPECT_EQ(&DropletPhase(2.0f, 0.01f, DefaultDropletWavelengthsUm), seen[0]);
  EXPECT_NE(&DropletPhase(2.0f, 0.02f), seen[0]);
  EXPECT_EQ(&Table10(), &DropletPhase(10.0f, 0.1f, glm::vec3(0.68f, 0.55f, 0.44f)));
}
