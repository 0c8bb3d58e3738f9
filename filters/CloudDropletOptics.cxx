// Lorenz-Mie scattering of water droplets and the phase function table built from it. The single
// sphere follows Bohren & Huffman (1983, ch. 4 and appendix A) with the numerical choices of
// Wiscombe (1979, NCAR/TN-140+STR; 1980, Appl. Opt. 19, 1505): the logarithmic derivative D_n(m x)
// by downward recurrence, the Riccati-Bessel functions by upward recurrence, x + 4 x^(1/3) + 2
// terms, with D_n started higher than Bohren & Huffman do (see MieCoefficients). The size
// distribution integral is the costly part (one Mie series per radius, summed at 2048 angles),
// so the angular sums are blocked in fixed-size chunks of angles that stay in the L1 cache and
// run over the threads; each angle's sum runs over the radii in one fixed order, so the table
// does not depend on the number of threads.
#include "CloudDropletOptics.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace cloudvis
{
// The shared transport's droplet functions (shaders/transport/DropletPhase.glsl), reading a table.
namespace droplet
{
using namespace glm;
constexpr float Pi = 3.14159265358979f; // the transport's float pi (CloudLighting.h)
struct Source
{
  const DropletPhaseTable* Table = nullptr;
#include "../shaders/transport/DropletPhase.glsl"
};
inline vec3 Source::DropletPhaseNode(int i)
{
  return this->Table->Phase[size_t(i)];
}
inline vec3 Source::DropletCdfNode(int i)
{
  return this->Table->CDF[size_t(i)];
}
} // namespace droplet

namespace
{
constexpr double Pi = 3.14159265358979323846;

// The bounds include their float roundings: DropletPhase takes floats, and 0.01f < 0.01.
void RequireInRange(const char* quantity,
  const char* symbol,
  double value,
  double lo,
  double hi,
  const char* unit)
{
  if (std::isfinite(value) && value >= std::min(lo, double(float(lo))) &&
    value <= std::max(hi, double(float(hi))))
  {
    return;
  }
  std::ostringstream message;
  message << "cloudvis droplet optics: " << quantity << " " << symbol << " = " << value << unit
          << (std::isfinite(value) ? " is outside the valid range ["
                                   : " is not finite; valid range [")
          << lo << ", " << hi << "]" << unit;
  throw std::invalid_argument(message.str());
}

// Hale, G. M. and Querry, M. R. (1973), "Optical constants of water in the 200-nm to 200-um
// wavelength region", Appl. Opt. 12, 555-563, Table I (25 C): wavelength (um), n, k.
struct WaterIndexRow
{
  double WavelengthUm, n, k;
};
constexpr WaterIndexRow HaleQuerry1973[] = { { 0.400, 1.339, 1.86e-9 },
  { 0.425, 1.338, 1.30e-9 },
  { 0.450, 1.337, 1.02e-9 },
  { 0.475, 1.336, 9.35e-10 },
  { 0.500, 1.335, 1.00e-9 },
  { 0.525, 1.334, 1.32e-9 },
  { 0.550, 1.333, 1.96e-9 },
  { 0.575, 1.333, 3.60e-9 },
  { 0.600, 1.332, 1.09e-8 },
  { 0.625, 1.332, 1.39e-8 },
  { 0.650, 1.331, 1.64e-8 },
  { 0.675, 1.331, 2.23e-8 },
  { 0.700, 1.331, 3.35e-8 },
  { 0.725, 1.330, 9.15e-8 },
  { 0.750, 1.330, 1.56e-7 },
  { 0.775, 1.330, 1.48e-7 },
  { 0.800, 1.329, 1.25e-7 } };

// The Mie coefficients of one sphere, and its efficiencies. D is scratch space for D_n(m x).
void MieCoefficients(double x,
  std::complex<double> m,
  std::vector<std::complex<double>>& a_n,
  std::vector<std::complex<double>>& b_n,
  std::vector<std::complex<double>>& D,
  double& Q_ext,
  double& Q_sca,
  double& g)
{
  const int N = MieTermCount(x);
  const std::complex<double> mx = m * x;
  // D_n(mx) is stable downward for any m, from the arbitrary start D = 0 far enough above N and
  // |mx| for the start's error to have decayed. Bohren & Huffman's max(N, |mx|) + 15 is not far
  // enough for weakly absorbing large spheres: the error decays only beyond the turning point
  // n ~ |mx|, whose width grows as |mx|^(1/3), and at x = 10^4, m = 1.33 + 1e-5 i it left Q_sca
  // 3e-3 low. 8 |mx|^(1/3) more reaches double precision (4 already did).
  const double mxModulus = std::abs(mx);
  const int nStart = std::max(N, int(mxModulus + 8.0 * std::cbrt(mxModulus))) + 16;
  D.assign(size_t(nStart) + 1, std::complex<double>(0.0, 0.0));
  for (int n = nStart; n > 0; --n)
  {
    const std::complex<double> nOverMx = double(n) / mx;
    D[size_t(n) - 1] = nOverMx - 1.0 / (D[size_t(n)] + nOverMx);
  }

  a_n.resize(size_t(N));
  b_n.resize(size_t(N));
  // Riccati-Bessel psi_n = x j_n(x) and eta_n = x y_n(x), upward from n = -1 and 0; upward is
  // stable for psi only while n stays below about x + O(x^(1/3)), which the term count ensures.
  double psiPrev = std::cos(x), psi = std::sin(x);
  double etaPrev = std::sin(x), eta = -std::cos(x);
  double sumExt = 0.0, sumSca = 0.0, sumG = 0.0;
  std::complex<double> aPrev, bPrev;
  for (int n = 1; n <= N; ++n)
  {
    const double f = double(2 * n - 1) / x;
    const double psiNext = f * psi - psiPrev;
    const double etaNext = f * eta - etaPrev;
    psiPrev = psi;
    psi = psiNext;
    etaPrev = eta;
    eta = etaNext;
    // xi_n = x h_n^(1)(x) = psi_n + i eta_n.
    const std::complex<double> xi(psi, eta), xiPrev(psiPrev, etaPrev);
    const std::complex<double> Da = D[size_t(n)] / m + double(n) / x;
    const std::complex<double> Db = m * D[size_t(n)] + double(n) / x;
    const std::complex<double> a = (Da * psi - psiPrev) / (Da * xi - xiPrev);
    const std::complex<double> b = (Db * psi - psiPrev) / (Db * xi - xiPrev);
    a_n[size_t(n) - 1] = a;
    b_n[size_t(n) - 1] = b;
    sumExt += (2 * n + 1) * (a.real() + b.real());
    sumSca += (2 * n + 1) * (std::norm(a) + std::norm(b));
    sumG += double(2 * n + 1) / (double(n) * (n + 1)) * (a * std::conj(b)).real();
    if (n > 1)
    {
      // The n-1, n cross term of g Q_sca (Bohren & Huffman section 4.5).
      sumG += double(n - 1) * (n + 1) / n * (aPrev * std::conj(a) + bPrev * std::conj(b)).real();
    }
    aPrev = a;
    bPrev = b;
  }
  Q_ext = 2.0 / (x * x) * sumExt;
  Q_sca = 2.0 / (x * x) * sumSca;
  g = Q_sca > 0.0 ? 4.0 / (x * x) * sumG / Q_sca : 0.0;
}

// f(i) for i in [0, count) over the hardware threads. The caller makes each f(i) write only its
// own results, so the outcome does not depend on the number of threads.
template<class F>
void ParallelFor(int count, const F& f)
{
  const int threads =
    std::max(1, std::min(count, int(std::min(16u, std::thread::hardware_concurrency()))));
  std::atomic<int> next{ 0 };
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto worker = [&]()
  {
    try
    {
      for (int i = next++; i < count; i = next++)
      {
        f(i);
      }
    }
    catch (...)
    {
      std::lock_guard<std::mutex> lock(failureMutex);
      failure = std::current_exception();
      next = count;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t)
  {
    pool.emplace_back(worker);
  }
  worker();
  for (std::thread& thread : pool)
  {
    thread.join();
  }
  if (failure)
  {
    std::rethrow_exception(failure);
  }
}

// The regularised lower incomplete gamma function P(k, t): the cumulative weight of a gamma
// distribution of shape k at t scale lengths. Series below k + 1, Lentz's continued fraction
// above (both standard; Abramowitz & Stegun 6.5.29 and 6.5.31).
double RegularisedLowerGamma(double k, double t)
{
  if (t <= 0.0)
  {
    return 0.0;
  }
  const double logPrefactor = k * std::log(t) - t - std::lgamma(k);
  if (t < k + 1.0)
  {
    double term = 1.0 / k, sum = term;
    for (int n = 1; n < 100000 && std::abs(term) > 1e-17 * std::abs(sum); ++n)
    {
      term *= t / (k + n);
      sum += term;
    }
    return sum * std::exp(logPrefactor);
  }
  const double tiny = 1e-300;
  double b = t + 1.0 - k, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int n = 1; n < 100000; ++n)
  {
    const double an = -n * (n - k);
    b += 2.0;
    d = an * d + b;
    d = std::abs(d) < tiny ? tiny : d;
    c = b + an / c;
    c = std::abs(c) < tiny ? tiny : c;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16)
    {
      break;
    }
  }
  return 1.0 - std::exp(logPrefactor) * h;
}

// The t at which P(k, t) = p, by bisection (monotone; 200 halvings reach double precision).
double GammaQuantile(double k, double p)
{
  double lo = 0.0, hi = k + 50.0 * std::sqrt(k) + 50.0;
  for (int i = 0; i < 200; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (RegularisedLowerGamma(k, mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The angular sums are nearly all of the time. GCC builds them also for AVX2 and AVX-512 and
// picks one at load time (the build's -O2 targets SSE2 only): 2-2.7x faster on this project's
// machines, with the same results (no contraction into FMA under -std=c++17). Not under the address
// or thread sanitizer, whose run-time is not yet set up when the loader calls the selecting (ifunc)
// resolver; define CLOUDVIS_NO_TARGET_CLONES to opt out.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12 && defined(__x86_64__) &&           \
  defined(__linux__) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__) &&         \
  !defined(CLOUDVIS_NO_TARGET_CLONES)
#define CLOUDVIS_ANGULAR_SUM_CLONES                                                                \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define CLOUDVIS_ANGULAR_SUM_CLONES
#endif

// The angular sums run over chunks of this many angles: 7 arrays of 128 doubles stay in L1, and
// a fixed trip count lets the compiler vectorise the inner loop at -O2.
constexpr int AngleChunk = 128;
// The Mie coefficients of one batch of radii are held at once; this bounds that memory
// (terms x 32 bytes) for the widest distributions.
constexpr size_t BatchTerms = size_t(1) << 18;

// One radius of the quadrature: its weight n(r) dr and where its coefficients begin.
struct RadiusNode
{
  double x = 0.0;
  double Weight = 0.0;
  int TermCount = 0;
  size_t Offset = 0; // into the batch's coefficient array, in units of 4 doubles
};

// Adds sum over the batch's radii of Weight (|S1|^2 + |S2|^2) at chunk's angles to phaseSum.
// coefficients holds, per radius and term, (2n+1)/(n(n+1)) (a_n + b_n) and (2n+1)/(n(n+1))
// (a_n - b_n) as four doubles: with them S1 + S2 = sum c+ (pi_n + tau_n) and S1 - S2 = sum c-
// (pi_n - tau_n), and |S1|^2 + |S2|^2 = (|S1 + S2|^2 + |S1 - S2|^2) / 2, which saves a third
// of the work of summing S1 and S2 themselves.
CLOUDVIS_ANGULAR_SUM_CLONES void AccumulateChunk(const std::vector<RadiusNode>& radii,
  const std::vector<double>& coefficients,
  const std::vector<double>& recurrenceA,
  const std::vector<double>& recurrenceB,
  const double* muChunk,
  double* phaseSum)
{
  double mu[AngleChunk];
  for (int j = 0; j < AngleChunk; ++j)
  {
    mu[j] = muChunk[j];
  }
  double pi[AngleChunk], piPrev[AngleChunk];
  double sPlusRe[AngleChunk], sPlusIm[AngleChunk], sMinusRe[AngleChunk], sMinusIm[AngleChunk];
  for (const RadiusNode& radius : radii)
  {
    for (int j = 0; j < AngleChunk; ++j)
    {
      pi[j] = 1.0;     // pi_1
      piPrev[j] = 0.0; // pi_0
      sPlusRe[j] = sPlusIm[j] = sMinusRe[j] = sMinusIm[j] = 0.0;
    }
    const double* c = coefficients.data() + 4 * radius.Offset;
    for (int n = 1; n <= radius.TermCount; ++n, c += 4)
    {
      const double cPlusRe = c[0], cPlusIm = c[1], cMinusRe = c[2], cMinusIm = c[3];
      const double fn = n, fn1 = n + 1.0;
      const double A = recurrenceA[size_t(n)], B = recurrenceB[size_t(n)];
      for (int j = 0; j < AngleChunk; ++j)
      {
        const double p = pi[j], pm = piPrev[j];
        const double muPi = mu[j] * p;
        const double tau = fn * muPi - fn1 * pm;
        const double plus = p + tau, minus = p - tau;
        sPlusRe[j] += cPlusRe * plus;
        sPlusIm[j] += cPlusIm * plus;
        sMinusRe[j] += cMinusRe * minus;
        sMinusIm[j] += cMinusIm * minus;
        piPrev[j] = p;
        pi[j] = A * muPi - B * pm; // pi_{n+1}
      }
    }
    for (int j = 0; j < AngleChunk; ++j)
    {
      phaseSum[j] += radius.Weight * 0.5 *
        (sPlusRe[j] * sPlusRe[j] + sPlusIm[j] * sPlusIm[j] + sMinusRe[j] * sMinusRe[j] +
          sMinusIm[j] * sMinusIm[j]);
    }
  }
}

// The largest float below 1: where u = 1 (or more) is clamped to, so that u < CDF_{N-1}.
} // namespace

void ValidateDropletParameters(double effectiveRadiusUm,
  double effectiveVariance,
  const glm::vec3& wavelengthsUm)
{
  RequireInRange("effective radius",
    "r_e",
    effectiveRadiusUm,
    DropletEffectiveRadiusMinUm,
    DropletEffectiveRadiusMaxUm,
    " um");
  RequireInRange("effective variance",
    "v_e",
    effectiveVariance,
    DropletEffectiveVarianceMin,
    DropletEffectiveVarianceMax,
    "");
  for (int c = 0; c < 3; ++c)
  {
    RequireInRange("wavelength",
      "lambda",
      wavelengthsUm[c],
      DropletWavelengthMinUm,
      DropletWavelengthMaxUm,
      " um");
  }
}

std::complex<double> WaterRefractiveIndex(double wavelengthUm)
{
  RequireInRange(
    "wavelength", "lambda", wavelengthUm, DropletWavelengthMinUm, DropletWavelengthMaxUm, " um");
  constexpr int rows = int(sizeof(HaleQuerry1973) / sizeof(HaleQuerry1973[0]));
  int i = 0;
  while (i < rows - 2 && wavelengthUm > HaleQuerry1973[i + 1].WavelengthUm)
  {
    ++i;
  }
  const WaterIndexRow& lo = HaleQuerry1973[i];
  const WaterIndexRow& hi = HaleQuerry1973[i + 1];
  const double t = (wavelengthUm - lo.WavelengthUm) / (hi.WavelengthUm - lo.WavelengthUm);
  // k varies by orders of magnitude across the table: interpolate its logarithm.
  return { lo.n + t * (hi.n - lo.n), std::exp(std::log(lo.k) + t * std::log(hi.k / lo.k)) };
}

int MieTermCount(double x)
{
  return std::max(1, int(x + 4.0 * std::cbrt(x) + 2.0));
}

MieSphere ComputeMieSphere(double x, std::complex<double> m)
{
  if (!(x > 0.0) || !std::isfinite(x) || !(m.imag() >= 0.0) || !std::isfinite(m.real()))
  {
    std::ostringstream message;
    message << "cloudvis Mie: size parameter x = " << x
            << " must be finite and positive and m = " << m
            << " must have a finite real part and an imaginary part >= 0";
    throw std::invalid_argument(message.str());
  }
  MieSphere sphere;
  sphere.x = x;
  sphere.m = m;
  std::vector<std::complex<double>> D;
  MieCoefficients(x, m, sphere.a_n, sphere.b_n, D, sphere.Q_ext, sphere.Q_sca, sphere.g);
  return sphere;
}

void MieSphere::Amplitudes(double mu, std::complex<double>& S1, std::complex<double>& S2) const
{
  S1 = S2 = 0.0;
  double pi = 1.0, piPrev = 0.0;
  for (size_t i = 0; i < a_n.size(); ++i)
  {
    const double n = double(i + 1);
    const double tau = n * mu * pi - (n + 1.0) * piPrev;
    const double c = (2.0 * n + 1.0) / (n * (n + 1.0));
    S1 += c * (a_n[i] * pi + b_n[i] * tau);
    S2 += c * (a_n[i] * tau + b_n[i] * pi);
    const double piNext = ((2.0 * n + 1.0) * mu * pi - (n + 1.0) * piPrev) / n;
    piPrev = pi;
    pi = piNext;
  }
}

double MieSphere::Phase(double mu) const
{
  std::complex<double> S1, S2;
  Amplitudes(mu, S1, S2);
  return (std::norm(S1) + std::norm(S2)) / (2.0 * Pi * x * x * Q_sca);
}

DropletPolydisperseOptics ComputeDropletPolydisperse(double effectiveRadiusUm,
  double effectiveVariance,
  double wavelengthUm,
  const std::vector<double>& mu)
{
  ValidateDropletParameters(effectiveRadiusUm, effectiveVariance, glm::vec3(float(wavelengthUm)));
  const double r_e = effectiveRadiusUm, v_e = effectiveVariance;
  const std::complex<double> m = WaterRefractiveIndex(wavelengthUm);

  // n(r) ~ r^alpha exp(-r / b); the cross-section weight r^2 n(r) is then a gamma distribution
  // of shape 1 / v_e and scale b = r_e v_e (mean r_e, variance v_e r_e^2: the definitions of
  // r_e and v_e). Truncate it where DropletTailWeight of that weight lies beyond.
  const double alpha = (1.0 - 3.0 * v_e) / v_e;
  const double b = r_e * v_e;
  const double shape = 1.0 / v_e;
  const double rMin = b * GammaQuantile(shape, DropletTailWeight);
  const double rMax = b * GammaQuantile(shape, 1.0 - DropletTailWeight);
  const double k = 2.0 * Pi / wavelengthUm;
  const double xMin = std::max(k * rMin, 1e-3), xMax = k * rMax;
  const double sigmaX = k * r_e * std::sqrt(v_e);
  const double budgetStep = (xMax * xMax - xMin * xMin) / (2.0 * DropletTermBudget);
  const double step = std::min(
    { DropletSizeParameterStep, sigmaX / 8.0, std::max(DropletSizeParameterStepMin, budgetStep) });
  const int count = std::max(2, int(std::ceil((xMax - xMin) / step)) + 1);
  const double dx = (xMax - xMin) / (count - 1);

  std::vector<RadiusNode> radii(static_cast<size_t>(count));
  const double logAtRe = alpha * std::log(r_e) - r_e / b; // keeps r^alpha in range (alpha <= 97)
  for (int i = 0; i < count; ++i)
  {
    RadiusNode& node = radii[size_t(i)];
    node.x = xMin + i * dx;
    const double r = node.x / k;
    const double trapezoid = (i == 0 || i == count - 1) ? 0.5 : 1.0;
    node.Weight = trapezoid * std::exp(alpha * std::log(r) - r / b - logAtRe);
    node.TermCount = MieTermCount(node.x);
  }
  const int maxTerms = radii.back().TermCount;
  std::vector<double> recurrenceA(size_t(maxTerms) + 2), recurrenceB(size_t(maxTerms) + 2);
  for (int n = 1; n <= maxTerms + 1; ++n)
  {
    recurrenceA[size_t(n)] = (2.0 * n + 1.0) / n;
    recurrenceB[size_t(n)] = (n + 1.0) / n;
  }

  // Angles padded to whole chunks; the padding's sums are computed and dropped.
  const int chunks = int((mu.size() + AngleChunk - 1) / AngleChunk);
  std::vector<double> muPadded(size_t(chunks) * AngleChunk, 0.0);
  std::copy(mu.begin(), mu.end(), muPadded.begin());
  std::vector<double> phaseSum(muPadded.size(), 0.0);

  struct RadiusTotals
  {
    double Sca = 0.0, Ext = 0.0, GSca = 0.0;
  };
  std::vector<RadiusTotals> totals(static_cast<size_t>(count));
  int first = 0;
  while (first < count)
  {
    // One batch: consecutive radii whose coefficients fit BatchTerms.
    std::vector<RadiusNode> batch;
    size_t terms = 0;
    int last = first;
    while (last < count &&
      (batch.empty() || terms + size_t(radii[size_t(last)].TermCount) <= BatchTerms))
    {
      RadiusNode node = radii[size_t(last)];
      node.Offset = terms;
      terms += size_t(node.TermCount);
      batch.push_back(node);
      ++last;
    }
    std::vector<double> coefficients(4 * terms);
    ParallelFor(int(batch.size()),
      [&](int i)
      {
        const RadiusNode& node = batch[size_t(i)];
        std::vector<std::complex<double>> a_n, b_n, D;
        double Q_ext, Q_sca, g;
        MieCoefficients(node.x, m, a_n, b_n, D, Q_ext, Q_sca, g);
        RadiusTotals& total = totals[size_t(first + i)];
        const double crossSection = node.Weight * node.x * node.x;
        total.Sca = crossSection * Q_sca;
        total.Ext = crossSection * Q_ext;
        total.GSca = crossSection * Q_sca * g;
        double* c = coefficients.data() + 4 * node.Offset;
        for (int n = 1; n <= node.TermCount; ++n, c += 4)
        {
          const double f = (2.0 * n + 1.0) / (double(n) * (n + 1.0));
          const std::complex<double> plus = f * (a_n[size_t(n) - 1] + b_n[size_t(n) - 1]);
          const std::complex<double> minus = f * (a_n[size_t(n) - 1] - b_n[size_t(n) - 1]);
          c[0] = plus.real();
          c[1] = plus.imag();
          c[2] = minus.real();
          c[3] = minus.imag();
        }
      });
    ParallelFor(chunks,
      [&](int chunk)
      {
        AccumulateChunk(batch,
          coefficients,
          recurrenceA,
          recurrenceB,
          muPadded.data() + size_t(chunk) * AngleChunk,
          phaseSum.data() + size_t(chunk) * AngleChunk);
      });
    first = last;
  }

  double sca = 0.0, ext = 0.0, gSca = 0.0, geometric = 0.0;
  for (int i = 0; i < count; ++i)
  {
    sca += totals[size_t(i)].Sca;
    ext += totals[size_t(i)].Ext;
    gSca += totals[size_t(i)].GSca;
    geometric += radii[size_t(i)].Weight * radii[size_t(i)].x * radii[size_t(i)].x;
  }
  DropletPolydisperseOptics optics;
  optics.Q_ext = ext / geometric;
  optics.Q_sca = sca / geometric;
  optics.SingleScatteringAlbedo = sca / ext;
  optics.g = gSca / sca;
  optics.Phase.resize(mu.size());
  // dC/dOmega = (|S1|^2 + |S2|^2) / (2 k^2) and C_sca = pi x^2 Q_sca / k^2: the k^2 cancel.
  for (size_t j = 0; j < mu.size(); ++j)
  {
    optics.Phase[j] = phaseSum[j] / (2.0 * Pi * sca);
  }
  optics.RadiusCount = count;
  optics.RadiusMinUm = xMin / k;
  optics.RadiusMaxUm = xMax / k;
  double area = 0.0, volume = 0.0;
  for (const RadiusNode& node : radii)
  {
    const double r = node.x / k;
    area += node.Weight * r * r;
    volume += node.Weight * r * r * r;
  }
  optics.QuadratureEffectiveRadiusUm = volume / area;
  double spread = 0.0;
  for (const RadiusNode& node : radii)
  {
    const double r = node.x / k, d = r - optics.QuadratureEffectiveRadiusUm;
    spread += node.Weight * r * r * d * d;
  }
  optics.QuadratureEffectiveVariance =
    spread / (area * std::pow(optics.QuadratureEffectiveRadiusUm, 2));
  return optics;
}

DropletPhaseTable ComputeDropletPhaseTable(float effectiveRadiusUm,
  float effectiveVariance,
  glm::vec3 wavelengthsUm)
{
  ValidateDropletParameters(effectiveRadiusUm, effectiveVariance, wavelengthsUm);
  constexpr int N = DropletPhaseTable::NodeCount;
  // The nodes in double: 1 - mu_i = 2 sin^2(theta_i / 2) keeps the bin widths exact near the
  // forward peak, where they are below 1e-12.
  std::vector<double> mu(N), oneMinusMu(N);
  for (int i = 0; i < N; ++i)
  {
    const double s = double(i) / (N - 1);
    const double theta = Pi * s * s;
    mu[size_t(i)] = std::cos(theta);
    oneMinusMu[size_t(i)] = 2.0 * std::sin(0.5 * theta) * std::sin(0.5 * theta);
  }

  DropletPhaseTable table;
  table.WavelengthsUm = wavelengthsUm;
  table.r_e = effectiveRadiusUm;
  table.v_e = effectiveVariance;
  table.Phase.assign(N, glm::vec3(0.0f));
  table.CDF.assign(N, glm::vec3(0.0f));
  for (int c = 0; c < 3; ++c)
  {
    const DropletPolydisperseOptics optics =
      ComputeDropletPolydisperse(effectiveRadiusUm, effectiveVariance, wavelengthsUm[c], mu);
    table.Q_ext[c] = float(optics.Q_ext);
    table.SingleScatteringAlbedo[c] = float(optics.SingleScatteringAlbedo);

    // Renormalise for the piecewise-linear representation: the Mie values at the nodes
    // integrate to 1 only up to the trapezoid error of the node spacing.
    double integral = 0.0;
    for (int i = 0; i + 1 < N; ++i)
    {
      integral += Pi * (optics.Phase[size_t(i)] + optics.Phase[size_t(i) + 1]) *
        (oneMinusMu[size_t(i) + 1] - oneMinusMu[size_t(i)]);
    }
    for (int i = 0; i < N; ++i)
    {
      table.Phase[size_t(i)][c] = float(optics.Phase[size_t(i)] / integral);
    }

    // CDF, g and chi_2 of the stored (float) values, so that they describe exactly the function
    // the renderers evaluate. On a bin P is linear and P mu and P P_2(mu) are polynomials of
    // degree 2 and 3 in mu, which Simpson's rule integrates exactly.
    std::vector<double> cumulative(N, 0.0);
    double g = 0.0, chi_2 = 0.0;
    for (int i = 0; i + 1 < N; ++i)
    {
      const double p0 = table.Phase[size_t(i)][c], p1 = table.Phase[size_t(i) + 1][c];
      const double h = oneMinusMu[size_t(i) + 1] - oneMinusMu[size_t(i)];
      const double mu0 = mu[size_t(i)], mu1 = mu[size_t(i) + 1];
      const double muMid = 1.0 - 0.5 * (oneMinusMu[size_t(i)] + oneMinusMu[size_t(i) + 1]);
      const double pMid = 0.5 * (p0 + p1);
      auto P2 = [](double t) { return 0.5 * (3.0 * t * t - 1.0); };
      cumulative[size_t(i) + 1] = cumulative[size_t(i)] + Pi * (p0 + p1) * h;
      g += 2.0 * Pi * h / 6.0 * (p0 * mu0 + 4.0 * pMid * muMid + p1 * mu1);
      chi_2 += 2.0 * Pi * h / 6.0 * (p0 * P2(mu0) + 4.0 * pMid * P2(muMid) + p1 * P2(mu1));
    }
    const double total = cumulative[size_t(N) - 1];
    for (int i = 0; i < N; ++i)
    {
      table.CDF[size_t(i)][c] = float(cumulative[size_t(i)] / total);
    }
    table.CDF[0][c] = 0.0f;
    table.CDF[size_t(N) - 1][c] = 1.0f;
    table.g[c] = float(g / total);
    table.chi_2[c] = float(chi_2 / total);
  }
  return table;
}

glm::vec3 EvaluateDropletPhase(const DropletPhaseTable& table, float mu)
{
  // NaN reads as -1, as the clamp of a GPU does not promise.
  return droplet::Source{ &table }.DropletPhaseAt(mu > -1.0f ? mu : -1.0f);
}

float SampleDropletPhaseCosine(const DropletPhaseTable& table, int channel, float u)
{
  return droplet::Source{ &table }.SampleDropletCosine(channel, u > 0.0f ? u : 0.0f);
}

float DropletPhaseNodeOneMinusCosine(int i)
{
  return droplet::Source{}.DropletNodeOneMinusCosine(i);
}

const DropletPhaseTable& DropletPhase(float effectiveRadiusUm,
  float effectiveVariance,
  glm::vec3 wavelengthsUm)
{
  ValidateDropletParameters(effectiveRadiusUm, effectiveVariance, wavelengthsUm);
  using Key = std::array<float, 5>;
  static std::mutex cacheMutex;
  static std::map<Key, std::unique_ptr<DropletPhaseTable>> cache;
  const Key key{
    effectiveRadiusUm, effectiveVariance, wavelengthsUm.x, wavelengthsUm.y, wavelengthsUm.z
  };
  // Held while computing: a second caller for the same table waits instead of computing it again.
  std::lock_guard<std::mutex> lock(cacheMutex);
  std::unique_ptr<DropletPhaseTable>& entry = cache[key];
  if (!entry)
  {
    entry = std::make_unique<DropletPhaseTable>(
      ComputeDropletPhaseTable(effectiveRadiusUm, effectiveVariance, wavelengthsUm));
  }
  return *entry;
}

} // namespace cloudvis
