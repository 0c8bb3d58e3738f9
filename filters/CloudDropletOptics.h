// The scattering of light by cloud droplets, from first principles: Lorenz-Mie theory for one
// homogeneous water sphere, integrated over the modified gamma size distribution of Hansen &
// Travis (1974) and tabulated once per (r_e, v_e, wavelengths) as the one phase function both
// renderers read. The table is defined as a piecewise-linear function of mu = cos(theta) between
// fixed nodes, normalised, integrated and inverted in exactly that representation, so that what
// the GPU evaluates, what the CPU reference evaluates, what the path tracer samples and the g and
// chi_2 a delta-Eddington truncation takes are one and the same function, not four
// approximations of the Mie result. EvaluateDropletPhase and SampleDropletPhaseCosine are written
// to be ported line by line to GLSL (plain loops, no std:: algorithms).
#ifndef CloudDropletOptics_h
#define CloudDropletOptics_h

#include "cloudvisFiltersModule.h"

#include <glm/glm.hpp>

#include <cmath>
#include <complex>
#include <vector>

namespace cloudvis
{

// Where the tables are valid and affordable. r_e: 2-30 um spans fog, stratus, cumulus and drizzle
// onset (clouds' r_e are 5-20 um); below 2 um is haze rather than cloud, and the cost of a table,
// computed once per process, grows as r_e^2 and with v_e (about 0.2 s at 10 um, 0.6 s at 20 um,
// 7 s at 30 um with v_e = 0.3, 35 s at 50 um with v_e = 0.5, on two cores): the ranges stop
// where a first render would stall for more than a few seconds. The Mie code itself has no such
// limits. v_e: 0.01 (nearly monodisperse) to 0.3 (broad; clouds' are 0.05-0.2).
// Wavelength: the span of the water refractive index table below (visible light).
constexpr double DropletEffectiveRadiusMinUm = 2.0;
constexpr double DropletEffectiveRadiusMaxUm = 30.0;
constexpr double DropletEffectiveVarianceMin = 0.01;
constexpr double DropletEffectiveVarianceMax = 0.3;
constexpr double DropletWavelengthMinUm = 0.4;
constexpr double DropletWavelengthMaxUm = 0.8;

// Hansen & Travis's "typical" water cloud value, also the MODIS retrieval's assumption.
constexpr float DefaultDropletEffectiveVariance = 0.1f;
// Red, green and blue as representative single wavelengths of the renderer's three channels.
constexpr glm::vec3 DefaultDropletWavelengthsUm{ 0.68f, 0.55f, 0.44f };

// Throws std::invalid_argument naming the quantity, its value and the valid range when r_e, v_e
// or a wavelength is outside the ranges above or is not finite.
CLOUDVISFILTERS_EXPORT void ValidateDropletParameters(double effectiveRadiusUm,
  double effectiveVariance,
  const glm::vec3& wavelengthsUm);

// The complex refractive index m = n + i k of pure liquid water (k > 0 absorbs, the convention of
// Bohren & Huffman with time dependence exp(-i omega t)), from Hale & Querry (1973), interpolated.
// Throws std::invalid_argument outside [DropletWavelengthMinUm, DropletWavelengthMaxUm].
CLOUDVISFILTERS_EXPORT std::complex<double> WaterRefractiveIndex(double wavelengthUm);

// The number of terms of the Mie series for size parameter x: x + 4 x^(1/3) + 2 (Bohren &
// Huffman; Wiscombe 1980), at least 1.
CLOUDVISFILTERS_EXPORT int MieTermCount(double x);

// Lorenz-Mie scattering by one homogeneous sphere of size parameter x = 2 pi r / wavelength and
// relative refractive index m (imaginary part >= 0). Stable for x up to at least 10^4.
struct CLOUDVISFILTERS_EXPORT MieSphere
{
  double x = 0.0;
  std::complex<double> m{ 1.0, 0.0 };
  // a_n and b_n for n = 1 .. MieTermCount(x), stored at index n - 1.
  std::vector<std::complex<double>> a_n;
  std::vector<std::complex<double>> b_n;
  double Q_ext = 0.0;
  double Q_sca = 0.0;
  // The asymmetry parameter <cos theta>, from the coefficients (not from an angular quadrature).
  double g = 0.0;

  // The amplitude scattering functions S1 (perpendicular) and S2 (parallel) at mu = cos theta.
  void Amplitudes(double mu, std::complex<double>& S1, std::complex<double>& S2) const;
  // The unpolarised phase function (|S1|^2 + |S2|^2) / (2 pi x^2 Q_sca) in 1/sr: its integral
  // over the sphere is 1.
  double Phase(double mu) const;
};

CLOUDVISFILTERS_EXPORT MieSphere ComputeMieSphere(double x, std::complex<double> m);

// Bulk optics of water droplets with the modified gamma distribution of Hansen & Travis (1974),
// n(r) ~ r^((1 - 3 v_e) / v_e) exp(-r / (r_e v_e)), at one wavelength.
struct CLOUDVISFILTERS_EXPORT DropletPolydisperseOptics
{
  // Cross-section weighted efficiencies <C> / <pi r^2> (so sigma_ext = Q_ext * 3 LWC / (4 rho_w
  // r_e)) and the single-scattering albedo <C_sca> / <C_ext>.
  double Q_ext = 0.0;
  double Q_sca = 0.0;
  double SingleScatteringAlbedo = 0.0;
  // <g C_sca> / <C_sca>, from the Mie coefficients.
  double g = 0.0;
  // The bulk phase function in 1/sr at the requested cosines, weighted by C_sca n(r). With no
  // cosines only the efficiencies and g are computed, which takes milliseconds.
  std::vector<double> Phase;
  // The radius quadrature that was used (for reports and tests), and the effective radius
  // <r^3> / <r^2> and variance <(r - r_e)^2 r^2> / (r_e^2 <r^2>) of its nodes and weights, which
  // reproduce the requested r_e and v_e when distribution, truncation and step are right.
  int RadiusCount = 0;
  double RadiusMinUm = 0.0;
  double RadiusMaxUm = 0.0;
  double QuadratureEffectiveRadiusUm = 0.0;
  double QuadratureEffectiveVariance = 0.0;
};

// The quadrature: the trapezoidal rule with a uniform step Delta x in size parameter over the
// radii where the cross-section weighted distribution holds all but DropletTailWeight of its
// weight at either end. The step is what a budget of DropletTermBudget Mie terms per wavelength
// allows, (x_max^2 - x_min^2) / (2 budget), but at least DropletSizeParameterStepMin and at most
// DropletSizeParameterStep and sigma_x / 8 (sigma_x = x_e sqrt(v_e), the width of that
// distribution). Small drops need the fine steps: their ripple resonances are narrow but weigh
// much, and Delta x = 0.5 leaves g 2e-3 off at r_e = 2 um, v_e = 0.1 (converged by 0.02); at
// r_e = 10 um Delta x = 0.5 leaves 3e-4. The Mie coefficients and the angular sums are spread
// over threads; every result depends only on the arguments, never on the thread count.
constexpr double DropletSizeParameterStep = 0.5;
constexpr double DropletSizeParameterStepMin = 0.01;
constexpr double DropletTermBudget = 150000.0;
constexpr double DropletTailWeight = 1e-5;
CLOUDVISFILTERS_EXPORT DropletPolydisperseOptics ComputeDropletPolydisperse(
  double effectiveRadiusUm,
  double effectiveVariance,
  double wavelengthUm,
  const std::vector<double>& mu);

// The nodes of a table (the GLSL's DropletPhaseNodeCount, substituted by the mapper).
constexpr int DropletPhaseNodeCount = 2048;

// The phase function table shared by the GPU and CPU renderers. Node i sits at scattering angle
// theta_i = pi (i / (N - 1))^2, dense near the forward peak. Between two nodes the function is
// LINEAR IN mu = cos(theta). Phase, CDF, g and chi_2 are all of that piecewise-linear function:
// 2 pi * integral of P dmu over [-1, 1] is 1 per channel, CDF_i = 2 pi * integral of P from mu_i
// to 1 (CDF_0 = 0, CDF_{N-1} = 1), chi_l = 2 pi * integral of P P_l(mu) dmu (chi_1 = g; for
// Henyey-Greenstein chi_l = g^l).
struct CLOUDVISFILTERS_EXPORT DropletPhaseTable
{
  static constexpr int NodeCount = DropletPhaseNodeCount;
  glm::vec3 WavelengthsUm = DefaultDropletWavelengthsUm;
  float r_e = 0.0f; // um
  float v_e = 0.0f;
  // Per node, per channel (red, green, blue): the phase function in 1/sr.
  std::vector<glm::vec3> Phase;
  // Per node, per channel: 2 pi * integral of P dmu from mu_i to 1.
  std::vector<glm::vec3> CDF;
  // chi_1 and chi_2 of the piecewise-linear function, per channel. chi_2 is the forward fraction
  // f of a delta-Eddington truncation.
  glm::vec3 g{ 0.0f };
  glm::vec3 chi_2{ 0.0f };
  // The bulk Q_ext and single-scattering albedo per channel (cross-section weighted, as in
  // DropletPolydisperseOptics), for renderers that turn liquid water into extinction.
  glm::vec3 Q_ext{ 0.0f };
  glm::vec3 SingleScatteringAlbedo{ 0.0f };
};

// theta_i = pi (i / (N - 1))^2.
inline float DropletPhaseNodeAngle(int i)
{
  const float s = float(i) / float(DropletPhaseTable::NodeCount - 1);
  return 3.14159265358979f * s * s;
}

// The inverse of DropletPhaseNodeAngle: sqrt(theta / pi) (N - 1); its floor is the bin of theta.
inline float DropletPhaseNodeCoordinate(float theta)
{
  return std::sqrt(theta / 3.14159265358979f) * float(DropletPhaseTable::NodeCount - 1);
}

// 1 - mu_i = 2 sin^2(theta_i / 2): the form that keeps its precision in float at the forward
// nodes, where mu_i itself rounds to 1 (theta below about 3e-4 rad).
CLOUDVISFILTERS_EXPORT float DropletPhaseNodeOneMinusCosine(int i);

// The table's piecewise-linear phase function (1/sr) at mu, per channel; mu is clamped to
// [-1, 1] (NaN reads as -1).
// It and the two functions around it are the shared transport's (DropletNodeOneMinusCosine,
// DropletPhaseAt, SampleDropletCosine in shaders/transport/DropletPhase.glsl), which the GPU runs.
CLOUDVISFILTERS_EXPORT glm::vec3 EvaluateDropletPhase(const DropletPhaseTable& table, float mu);

// The inverse of the table's CDF in channel 0, 1 or 2 at u in [0, 1): the cosine of a scattering
// angle distributed exactly as the piecewise-linear phase function (up to float rounding).
CLOUDVISFILTERS_EXPORT float SampleDropletPhaseCosine(const DropletPhaseTable& table,
  int channel,
  float u);

// Builds a table (no cache); validates its arguments as ValidateDropletParameters does.
CLOUDVISFILTERS_EXPORT DropletPhaseTable ComputeDropletPhaseTable(float effectiveRadiusUm,
  float effectiveVariance,
  glm::vec3 wavelengthsUm);

// The table for these exact parameters, computed on first use and kept for the life of the
// process; safe to call from several threads. The reference stays valid.
CLOUDVISFILTERS_EXPORT const DropletPhaseTable& DropletPhase(float effectiveRadiusUm,
  float effectiveVariance = DefaultDropletEffectiveVariance,
  glm::vec3 wavelengthsUm = DefaultDropletWavelengthsUm);

} // namespace cloudvis

#endif
