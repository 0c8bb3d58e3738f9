// The phase function of cloud droplets, tabulated (filters/CloudDropletOptics.h computes the
// table from Lorenz-Mie theory over a gamma size distribution): its evaluation and its exact
// sampling, written once for the GPU (spliced into the march and the path tracer with the rest
// of the transport) and the C++ (the CPU renderers, and the table's own EvaluateDropletPhase and
// SampleDropletPhaseCosine). Common subset of GLSL 1.50 and C++/glm, as Medium.glsl states.
//
// Node i of DropletPhaseNodeCount sits at the scattering angle theta_i = pi (i / (N - 1))^2,
// dense toward the forward peak; between two nodes the function is linear in mu = cos(theta).
// The accessors DropletPhaseNode(i) and DropletCdfNode(i) return node i's phase (1/sr, per
// channel) and its cumulative distribution 2 pi * integral of P from mu_i to 1.

// The table's node i: its phase, and its cumulative distribution (each language's accessor:
// shaders/transport/Accessors.glsl, filters/CloudTransport.h, filters/CloudDropletOptics.cxx).
vec3 DropletPhaseNode(int i);
vec3 DropletCdfNode(int i);

// 1 - mu_i = 2 sin^2(theta_i / 2): exact in float at the forward nodes, where mu_i rounds to 1.
float DropletNodeOneMinusCosine(int i)
{
  float s = float(i) / float(DropletPhaseNodeCount - 1);
  float theta = Pi * s * s;
  float halfSine = sin(0.5f * theta);
  return 2.0f * halfSine * halfSine;
}

// The tabulated phase function at mu, per channel (1/sr).
vec3 DropletPhaseAt(float mu)
{
  // Work in w = 1 - mu: the forward bins are far narrower than float's spacing of mu near 1.
  // theta = 2 asin(sqrt(w / 2)) is accurate at small angles, where acos(mu) is not; the two
  // loops then correct a bin that rounding put one off.
  float w = 1.0f - clamp(mu, -1.0f, 1.0f);
  float theta = 2.0f * asin(sqrt(0.5f * w));
  int i = int(sqrt(theta / Pi) * float(DropletPhaseNodeCount - 1));
  i = clamp(i, 0, DropletPhaseNodeCount - 2);
  while (i > 0 && w < DropletNodeOneMinusCosine(i))
  {
    i -= 1;
  }
  while (i < DropletPhaseNodeCount - 2 && w > DropletNodeOneMinusCosine(i + 1))
  {
    i += 1;
  }
  float w0 = DropletNodeOneMinusCosine(i);
  float w1 = DropletNodeOneMinusCosine(i + 1);
  float t = w1 > w0 ? clamp((w - w0) / (w1 - w0), 0.0f, 1.0f) : 0.0f;
  return mix(DropletPhaseNode(i), DropletPhaseNode(i + 1), t);
}

// The cosine of a scattering angle drawn from channel c's tabulated phase by inverting its
// distribution at u in [0, 1): exact for the piecewise-linear function, up to float rounding.
float SampleDropletCosine(int c, float u)
{
  u = clamp(u, 0.0f, 0.99999994f);
  // The bin with CDF_lo <= u < CDF_hi (CDF_0 = 0, CDF_{N-1} = 1): it has positive probability.
  int lo = 0;
  int hi = DropletPhaseNodeCount - 1;
  while (hi - lo > 1)
  {
    int mid = (lo + hi) / 2;
    if (DropletCdfNode(mid)[c] <= u)
    {
      lo = mid;
    }
    else
    {
      hi = mid;
    }
  }
  float c0 = DropletCdfNode(lo)[c];
  float c1 = DropletCdfNode(hi)[c];
  float f = (u - c0) / (c1 - c0);
  // Inside the bin the density is linear in t = (w - w_lo) / (w_hi - w_lo), from p0 to p1, and
  // its normalised integral is f: (p1 - p0) / 2 t^2 + p0 t = f (p0 + p1) / 2. The root in the
  // form 2c / (b + sqrt(b^2 + 4ac)) has no cancellation, is exact (t = f) for a constant
  // density and gives t = 1 at f = 1.
  float p0 = DropletPhaseNode(lo)[c];
  float p1 = DropletPhaseNode(hi)[c];
  float denominator = p0 + sqrt((1.0f - f) * p0 * p0 + f * p1 * p1);
  float t = denominator > 0.0f ? clamp(f * (p0 + p1) / denominator, 0.0f, 1.0f) : f;
  float w0 = DropletNodeOneMinusCosine(lo);
  float w1 = DropletNodeOneMinusCosine(hi);
  return 1.0f - (w0 + t * (w1 - w0));
}
