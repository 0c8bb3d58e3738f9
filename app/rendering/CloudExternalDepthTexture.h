// The optical depths from outside the field that vtkCloudVolumeMapper was given
// (vtkCloudPieceExchange::SetExternalOpticalDepths; filters/CloudOpticalDepthGrid.h): the grid as
// the mapper holds it, and its 3-D float texture, one block per light stacked along z as the grid's
// depths are laid out, uploaded when the grid changes and read by the march and the
// multiple-scattering passes through OpticalDepthToLight (the shader maps an index point onto the
// grid itself, so the texture is the grid, unresampled: a 33^3 grid takes 144 kB per light). Its
// memory goes through the mapper's GpuMemoryBudget. Private to the module.
#ifndef CloudExternalDepthTexture_h
#define CloudExternalDepthTexture_h

#include "CloudOpticalDepthGrid.h"
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

class ExternalDepthTexture
{
public:
  // Holds a copy of the grid (an empty one: none); the texture follows at the next Update.
  void Set(const OpticalDepthGrid& grid);
  const OpticalDepthGrid& GetGrid() const { return this->Grid; }
  bool HasDepths() const { return !this->Grid.Empty(); }

  // Uploads the grid when it changed since the last upload: false with `problem` when the GPU
  // cannot hold it.
  bool Update(vtkOpenGLRenderWindow* window, GpuMemoryBudget& budget, std::string& problem);

  // When the texture last changed (for what is computed from it, as the density's upload time).
  double GetUploadTime() const { return double(this->Uploaded.GetMTime()); }
  vtkTextureObject* GetTexture() { return this->Texture; }
  long long GetBytes() const { return this->Bytes; }
  void Release(vtkWindow* window);

private:
  OpticalDepthGrid Grid;
  vtkTimeStamp Changed;  // when Set last changed the grid
  VolumeSources Sources; // the Changed it took
  vtkTimeStamp Uploaded; // when the texture last took it
  vtkNew<vtkTextureObject> Texture;
  long long Bytes = 0;
};

// Points a program's ExternalDepthTexture sampler at `external` (active) or, without one, at
// `unreadUnit` (a 3-D texture's unit: a sampler must name a unit of its own type even when the
// switch ExternalOpticalDepths keeps it from being read).
void BindExternalDepths(vtkShaderProgram* program, vtkTextureObject* external, int unreadUnit);

} // namespace cloudvis

#endif
