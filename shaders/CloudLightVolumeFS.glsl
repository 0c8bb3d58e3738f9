// The light-volume pass of vtkCloudVolumeMapper (issue 12): one fragment per texel of one slice
// of one light's block of the optical-depth volume (filters/CloudLightVolumes.h). The mapper
// splices this main() after the march shader's functions (CloudMarchFS.glsl without its main,
// with the march model's lighting), so the texel's optical depth is the shared source's
// LightVolumeTexel (shaders/transport/LightMarch.glsl, which the CPU's ComputeLightVolumes runs
// too), with the uniforms of LightVolumeMarch: uniform steps of the view's step to the volume's
// exit or to a point light.
uniform int LightVolumeLight;   // which light's block
uniform float LightVolumeSlice; // the texel's z within the block

void main()
{
  // The fragment's texel from the quad's texture coordinate, (i + 0.5) / size at its centre (using
  // it keeps the quad's vertex attribute alive in the linked program).
  vec3 texel = vec3(floor(texCoord * LightVolumeSize.xy), LightVolumeSlice);
  gl_FragData[0] = vec4(LightVolumeTexel(LightVolumeLight, texel), 0.0, 0.0, 1.0);
}
