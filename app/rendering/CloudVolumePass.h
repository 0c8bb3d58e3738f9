// What the mapper's passes over a light-transport volume share (the light volumes,
// CloudLightVolumeTexture.h; the multiple-scattering volume, CloudScatteringVolumeTexture.h): a
// program made of the march shader's functions and the pass's own main() (PassShaderSource),
// compiled for the kinds of the lights and again when they change; the march's textures and
// uniforms it reads; the GL state a pass over texels needs; and the framebuffer its layers are
// rendered into. Private to the module.
#ifndef CloudVolumePass_h
#define CloudVolumePass_h

#include <memory>
#include <string>

class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;

namespace cloudvis
{
struct MarchUniforms;

// What a volume pass reads besides the uniforms: the march's textures and empty-space settings.
struct VolumePassInputs
{
  vtkTextureObject* Density = nullptr;
  vtkTextureObject* Transfer = nullptr;
  vtkTextureObject* Occupancy = nullptr;
  vtkTextureObject* DropletPhase = nullptr; // the droplets' phase table (or its placeholder)
  const int* BrickCount = nullptr;
  int BrickSize = 1;
  bool SkipEmptySpace = true;
  // The optical depths from outside the field (CloudExternalDepthTexture.h) when the march adds
  // them; null: none.
  vtkTextureObject* ExternalDepths = nullptr;
  // Changes of the density texture, the transfer table and the external depths (their upload
  // times; the last -1 without them).
  double DensityTime = 0.0;
  double TableTime = 0.0;
  double ExternalDepthsTime = -1.0;
};

// The shaders of a pass: its fragment main() (spliced after the march's functions), and a vertex
// and a geometry shader of its own (null: VTK's full-screen quad's, and none).
struct VolumePassShaders
{
  const char* FragmentMain = nullptr;
  const char* Vertex = nullptr;
  const char* Geometry = nullptr;
};

class VolumePass
{
public:
  VolumePass();
  ~VolumePass();

  // Makes the pass's program current (compiled for u's kinds of lights) with u's uniforms set
  // and the inputs bound; saves and sets the GL state (no blending, depth test or scissor) and
  // binds the pass's framebuffer. Null with `problem` when the program fails to compile or link
  // (`what` names the pass); then nothing is bound. End() undoes the rest.
  vtkShaderProgram* Begin(vtkOpenGLRenderWindow* window,
    const MarchUniforms& u,
    const VolumePassInputs& inputs,
    const VolumePassShaders& shaders,
    const std::string& what,
    std::string& problem);
  // Detaches the framebuffer's colour attachments, restores the framebuffer binding and the GL
  // state, and unbinds the inputs.
  void End();

  // The full-screen quad the program draws with.
  vtkOpenGLQuadHelper& Quad() { return *this->Pass; }
  void Release();

private:
  struct SavedState;
  std::unique_ptr<vtkOpenGLQuadHelper> Pass;
  std::string Key; // the kinds of lights the program was compiled for
  unsigned int Framebuffer = 0;
  std::unique_ptr<SavedState> Saved; // between Begin and End
};

} // namespace cloudvis

#endif
