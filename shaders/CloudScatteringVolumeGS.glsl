//VTK::System::Dec

// Sends each triangle of the multiple-scattering volume's full-screen quad to the layer of the 3-D
// texture its instance stands for (gl_Layer, a layered framebuffer attachment), and tells the
// fragment shader (CloudScatteringVolumeFS.glsl) which layer that is: one draw per pass instead
// of one per layer.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in vec2 layerTexCoord[];
flat in int layerOfVertex[];
out vec2 texCoord;
flat out int ScatteringLayer;

void main()
{
  for (int i = 0; i < 3; ++i)
  {
    gl_Position = gl_in[i].gl_Position;
    texCoord = layerTexCoord[i];
    gl_Layer = layerOfVertex[i];
    ScatteringLayer = layerOfVertex[i];
    EmitVertex();
  }
  EndPrimitive();
}
