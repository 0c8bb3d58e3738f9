// The multiple-scattering volume's passes in vtkCloudVolumeMapper (issue 21,
// filters/CloudScatteringVolume.h states the grids and the order of the passes): one fragment per
// texel of the grid being computed, drawn into the grid's 2-D atlas of its layers
// (Accessors.glsl), but for the last pass, which writes the finished volume's 3-D textures, every
// layer in one draw (CloudScatteringVolumeGS.glsl sends the quad to each). The mapper splices
// this main() after the march shader's functions (CloudMarchFS.glsl without its main, with the
// march model's lighting), so each texel is one of the shared source's texel functions
// (shaders/transport/Scattering.glsl, which the CPU's ComputeScatteringVolume runs too);
// ScatteringPass says which. The grid's textures are read through the accessors: the medium, the
// source and its direction, the fluence of the previous half-sweep (the pass writes the other of
// two fluence textures: a half-sweep reads its neighbours' old values, as the CPU's does), the
// coarser grid's fluence.
uniform int ScatteringPass; // ScatteringVolumeTexture.cxx's PassNumber enum
uniform int ScatteringParity; // the half-sweep's cells: x + y + z of this parity
flat in int ScatteringLayer; // the texel's z in the finished volume's pass

void main()
{
  // The fragment's cell: its texel of the grid's atlas (Accessors.glsl), whose spare tiles hold
  // none; in the finished volume's pass, its texel of a 3-D texture's layer, from the quad's
  // texture coordinate, (i + 0.5) / size at its centre (using it keeps the quad's vertex
  // attribute alive in the linked program).
  ivec3 c;
  if (ScatteringPass == 5)
  {
    c = ivec3(ivec2(floor(texCoord * ScatteringVolumeSize.xy)), ScatteringLayer);
  }
  else
  {
    c = AtlasCell(ivec2(gl_FragCoord.xy), ScatteringVolumeSize, ScatteringAtlasColumns);
    if (c.z >= int(ScatteringVolumeSize.z))
    {
      discard;
    }
  }
  vec3 t = vec3(c);
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
  else // the finished volume: the finest grid's fluence and its flux
  {
    first = ScatteringFluenceAt(c);
    second = ScatteringFluxTexel(c);
  }
  gl_FragData[0] = first;
  gl_FragData[1] = second; // the source's direction, the flux; no attachment takes it otherwise
}
