// The multiple-scattering volume's passes in vtkCloudVolumeMapper (issue 21,
// filters/CloudScatteringVolume.h states the grids and the order of the passes): one fragment per
// texel of the grid being computed, every layer in one draw (CloudScatteringVolumeGS.glsl sends
// the quad to each). The mapper splices this main() after the march
// shader's functions (CloudMarchFS.glsl without its main, with the march model's lighting), so
// each texel is one of the shared source's texel functions (shaders/transport/Transport.glsl, "The
// multiple-scattering volume", which the CPU's ComputeScatteringVolume runs too); ScatteringPass
// says which. The grid's textures are read through the accessors (Accessors.glsl): the medium,
// the source and its direction, the fluence of the previous half-sweep (the pass writes the other
// of two fluence textures: a half-sweep reads its neighbours' old values, as the CPU's does), the
// coarser grid's fluence.
uniform int ScatteringPass; // ScatteringVolumeTexture.cxx's Pass enum
uniform int ScatteringParity; // the half-sweep's cells: x + y + z of this parity
flat in int ScatteringLayer; // the texel's z

void main()
{
  // The fragment's texel from the quad's texture coordinate, (i + 0.5) / size at its centre (using
  // it keeps the quad's vertex attribute alive in the linked program).
  vec3 t = vec3(floor(texCoord * ScatteringVolumeSize.xy), float(ScatteringLayer));
  ivec3 c = ivec3(t);
  vec4 second = vec4(0.0);
  vec4 first;
  if (ScatteringPass == 0)
  {
    first = ScatteringMediumTexel(t);
  }
  else if (ScatteringPass == 1)
  {
    ScatteringSourceTexel(t, ScatteringMediumAt(c), first, second);
  }
  else if (ScatteringPass == 2)
  {
    first = ScatteringStartTexel(t, ScatteringMediumAt(c));
  }
  else if (ScatteringPass == 3)
  {
    first = ScatteringProlongTexel(t);
  }
  else if (ScatteringPass == 4)
  {
    first = ScatteringRelaxTexel(c, ScatteringParity);
  }
  else
  {
    first = ScatteringFluxTexel(c);
  }
  gl_FragData[0] = first;
  gl_FragData[1] = second; // the source pass's direction; no attachment takes it otherwise
}
