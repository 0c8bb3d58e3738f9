//VTK::System::Dec

// The multiple-scattering volume's passes draw every layer of a grid in one instanced draw of the
// full-screen quad (CloudScatteringVolumeTexture.cxx): instance k is layer k. This is VTK's
// full-screen quad vertex shader (vtkOpenGLRenderUtilities) with the instance passed on to the
// geometry shader (CloudScatteringVolumeGS.glsl), which sends the quad to its layer.
in vec4 ndCoordIn;
in vec2 texCoordIn;
out vec2 layerTexCoord;
flat out int layerOfVertex;

void main()
{
  gl_Position = ndCoordIn;
  layerTexCoord = texCoordIn;
  layerOfVertex = gl_InstanceID;
}
