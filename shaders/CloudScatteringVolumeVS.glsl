//VTK::System::Dec

// The multiple-scattering volume's passes draw the layers of a grid in one instanced draw of the
// full-screen quad (CloudScatteringVolumeTexture.cxx): instance k is layer ScatteringFirstLayer +
// k (0 unless a progressive computation splits the pass). This is VTK's
// full-screen quad vertex shader (vtkOpenGLRenderUtilities) with the instance passed on to the
// geometry shader (CloudScatteringVolumeGS.glsl), which sends the quad to its layer.
in vec4 ndCoordIn;
in vec2 texCoordIn;
out vec2 layerTexCoord;
flat out int layerOfVertex;
uniform int ScatteringFirstLayer;

void main()
{
  gl_Position = ndCoordIn;
  layerTexCoord = texCoordIn;
  layerOfVertex = ScatteringFirstLayer + gl_InstanceID;
}
