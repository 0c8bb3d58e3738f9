// The multiple-scattering volume solved over a whole distributed field that vtkCloudVolumeMapper
// was given (vtkCloudPieceExchange::SolveScatteringVolume; filters/CloudScatteringVolume.h): the
// volume as the mapper holds it, and its fluence and flux as two RGBA32F 3-D textures, uploaded
// when it changes and bound for the march in place of the mapper's own volume (the shader maps its
// input's index points onto the whole field's grid itself: 33^3 texels take 1.1 MiB for both at a
// 128^3 field). Its memory goes through the mapper's GpuMemoryBudget. Private to the module.
#ifndef CloudExternalScatteringTexture_h
#define CloudExternalScatteringTexture_h

#include "CloudScatteringVolume.h"
#include "CloudVolumeSources.h"

#include <vtkNew.h>
#include <vtkTextureObject.h>
#include <vtkTimeStamp.h>

#include <string>

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkWindow;

namespace cloudvis
{
class GpuMemoryBudget;

class ExternalScatteringTexture
{
public:
  // Holds a copy of the volume (an empty one: none); the textures follow at the next Update.
  void Set(const WholeFieldScattering& volume);
  const WholeFieldScattering& GetVolume() const { return this->Volume; }
  bool HasVolume() const { return !this->Volume.Empty(); }

  // Uploads the volume when it changed since the last upload: false with `problem` when the GPU
  // cannot hold it.
  bool Update(vtkOpenGLRenderWindow* window, GpuMemoryBudget& budget, std::string& problem);

  // When the textures last changed (what the march's accumulation depends on).
  double GetUploadTime() const { return double(this->Uploaded.GetMTime()); }
  long long GetBytes() const { return this->Bytes; }

  // Binds the fluence and flux as the march's ScatteringVolumeTexture and ScatteringFluxTexture.
  void Activate(vtkShaderProgram* march);
  void Deactivate();
  void Release(vtkWindow* window);

private:
  WholeFieldScattering Volume;
  vtkTimeStamp Changed;  // when Set last changed the volume
  VolumeSources Sources; // the Changed they took
  vtkTimeStamp Uploaded; // when the textures last took it
  vtkNew<vtkTextureObject> Fluence;
  vtkNew<vtkTextureObject> Flux;
  long long Bytes = 0;
};

} // namespace cloudvis

#endif
