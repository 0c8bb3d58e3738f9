// Lighting model "none": emission-absorption. A sample emits its transfer-function color;
// no light reaches it from elsewhere.
vec3 SourceTerm(vec3 p, float density, vec3 albedo, vec3 d)
{
  return albedo;
}
