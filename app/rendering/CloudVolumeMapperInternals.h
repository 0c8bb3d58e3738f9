// What vtkCloudVolumeMapper's sources share (its settings, vtkCloudVolumeMapper.cxx; the march,
// vtkCloudVolumeMapperMarch.cxx; the composite, vtkCloudVolumeMapperComposite.cxx; the
// read-backs, vtkCloudVolumeMapperReadBack.cxx): the
// mapper's GPU resources (its Internals), the temporal reprojection's constants and two small
// helpers. Private to the module.
#ifndef CloudVolumeMapperInternals_h
#define CloudVolumeMapperInternals_h

#include "vtkCloudVolumeMapper.h"

#include "CloudDensityTexture.h"
#include "CloudDropletPhaseTexture.h"
#include "CloudExternalDepthTexture.h"
#include "CloudExternalScatteringTexture.h"
#include "CloudJitterTexture.h"
#include "CloudLightVolumeTexture.h"
#include "CloudMarchShader.h"
#include "CloudOccupancyTexture.h"
#include "CloudPathTraceInputs.h"
#include "CloudScatteringVolumeTexture.h"
#include "CloudTransferTexture.h"
#include "CloudViewTargets.h"

#include <vtkOpenGLQuadHelper.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkShaderProgram.h>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <map>
#include <memory>
#include <string>

namespace cloudvis
{
namespace mapper
{
// Temporal reprojection: the share of the reprojected history in each interactive frame; how
// many march steps its depth may differ by from the current frame's (beyond the depths the low
// resolution blurs together) before it is rejected; the turn of a pixel's ray since the last
// image at which its share has faded to nothing (a cloud is seen through: what lies behind the
// point changes with the angle). Measured on the sparse cloud (tests/render, docs/viewer.md): a
// weight of 0.7 or 0.9 hardly differs after one frame; a fade at 12 degrees keeps most of the
// gain at 1 to 3 degrees a frame and stays below the low-resolution frame's error at 6.
constexpr float HistoryWeight = 0.9f;
constexpr double HistoryDepthSteps = 4.0;
constexpr double HistoryFadeDegrees = 12.0;

inline vtkOpenGLRenderWindow* WindowOf(vtkRenderer* renderer)
{
  return vtkOpenGLRenderWindow::SafeDownCast(renderer->GetRenderWindow());
}

// A double matrix uploaded as the float mat4 uniform `name` (GLM's column-major order is GL's).
inline void SetMatrix(vtkShaderProgram* program, const char* name, const glm::dmat4& m)
{
  glm::mat4 f(m);
  program->SetUniformMatrix4x4(name, glm::value_ptr(f));
}
} // namespace mapper
} // namespace cloudvis

struct vtkCloudVolumeMapper::Internals
{
  cloudvis::DensityTexture Density;
  cloudvis::TransferTexture Transfer;
  cloudvis::DropletPhaseTexture DropletPhase; // the droplets' phase table
  cloudvis::OccupancyTexture Occupancy;
  cloudvis::JitterTexture Jitter;
  cloudvis::ExtinctionBoundsTexture ExtinctionBounds; // the path tracer's, made on first use
  cloudvis::LightVolumeTexture LightVolumes;
  cloudvis::ScatteringVolumeTexture Scattering; // the march's multiple scattering
  cloudvis::ExternalDepthTexture External;      // optical depths from outside the field
  cloudvis::ExternalScatteringTexture ExternalScattering; // a whole field's volume, read instead
  cloudvis::MarchPrograms March;
  std::unique_ptr<vtkOpenGLQuadHelper> Composite;
  std::map<vtkRenderer*, std::unique_ptr<cloudvis::ViewTargets>> Views; // keys: identities only
  std::string ReportedError; // reported once, until a render succeeds again

  cloudvis::ViewTargets& ViewOf(vtkRenderer* renderer)
  {
    auto& view = this->Views[renderer];
    if (!view)
    {
      view = std::make_unique<cloudvis::ViewTargets>();
    }
    return *view;
  }

  long long TextureBytes() const
  {
    return this->Density.GetBytes() + this->Transfer.GetBytes() +
      this->DropletPhase.GetBytes() + this->Occupancy.GetBytes() +
      this->Jitter.GetBytes() + this->ExtinctionBounds.GetBytes() + this->LightVolumes.GetBytes() +
      this->Scattering.GetBytes() + this->External.GetBytes() + this->ExternalScattering.GetBytes();
  }

  long long Bytes() const
  {
    long long bytes = this->TextureBytes();
    for (const auto& view : this->Views)
    {
      bytes += view.second->GetBytes();
    }
    return bytes;
  }
};

#endif
