// Drawing a field coarser when it does not fit the GPU's memory (FieldCoarsening.h).
#include "FieldCoarsening.h"

#include "VtkMessageCapture.h"
#include "vtkCloudVolumeMapper.h"

#include <vtkImageData.h>
#include <vtkImageShrink3D.h>
#include <vtkMatrix3x3.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>

#include <string>
#include <vector>

namespace cloudvis
{
namespace
{

std::string Voxels(vtkImageData* image)
{
  const int* d = image->GetDimensions();
  return std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " + std::to_string(d[2]);
}

// RenderCoarsenedToFit's note: what was done, and the refusal of the field as drawn before.
std::string CoarseningNote(vtkImageData* field,
  vtkImageData* coarse,
  int factor,
  const std::string& problem)
{
  return "the field was coarsened " + std::to_string(factor) + "x (" + Voxels(coarse) +
    " voxels drawn for " + Voxels(field) + ") to fit the GPU's memory: " + problem;
}

} // namespace

vtkSmartPointer<vtkImageData> CoarsenField(vtkImageData* field, int factor)
{
  if (factor <= 1)
  {
    return field;
  }
  vtkNew<vtkImageShrink3D> shrink;
  shrink->SetInputData(field);
  shrink->SetShrinkFactors(factor, factor, factor);
  shrink->AveragingOn();
  shrink->Update();
  vtkSmartPointer<vtkImageData> coarse = vtkSmartPointer<vtkImageData>::New();
  coarse->ShallowCopy(shrink->GetOutput());
  // VTK places each averaged voxel at its block's first voxel; the average stands for the
  // block's centre, (factor - 1) / 2 voxels on along each axis of the lattice.
  const double* spacing = field->GetSpacing();
  const double* direction = field->GetDirectionMatrix()->GetData();
  double origin[3];
  field->GetOrigin(origin);
  const double half = 0.5 * (factor - 1);
  for (int row = 0; row < 3; ++row)
  {
    for (int axis = 0; axis < 3; ++axis)
    {
      origin[row] += direction[3 * row + axis] * half * spacing[axis];
    }
  }
  coarse->SetOrigin(origin);
  coarse->SetSpacing(spacing[0] * factor, spacing[1] * factor, spacing[2] * factor);
  coarse->SetDirectionMatrix(field->GetDirectionMatrix());
  return coarse;
}

int RenderCoarsenedToFit(const std::vector<vtkCloudVolumeMapper*>& mappers,
  vtkImageData* field,
  int factor,
  const std::function<void()>& render,
  std::string& note)
{
  const int* d = field->GetDimensions();
  const auto refused = [&]() -> vtkCloudVolumeMapper*
  {
    for (vtkCloudVolumeMapper* mapper : mappers)
    {
      if (mapper->GetLastErrorIsGpuMemory())
      {
        return mapper;
      }
    }
    return nullptr;
  };
  const auto coarserFits = [&]
  {
    return factor < MaximumCoarsening && d[0] >= 4 * factor && d[1] >= 4 * factor &&
      d[2] >= 4 * factor;
  };
  // A refusal that a coarser field answers is no error: VTK's report of it is held back, and
  // passed on when the render failed for another reason.
  const auto attempt = [&]
  {
    if (!coarserFits())
    {
      render();
      return;
    }
    std::vector<std::string> held;
    {
      const VtkMessageCapture quiet;
      render();
      held = quiet.Messages();
    }
    if (!refused())
    {
      for (const std::string& message : held)
      {
        vtkOutputWindowDisplayErrorText(message.c_str());
      }
    }
  };
  attempt();
  while (refused() && coarserFits())
  {
    const std::string problem = refused()->GetLastError();
    factor *= 2;
    const vtkSmartPointer<vtkImageData> coarse = CoarsenField(field, factor);
    for (vtkCloudVolumeMapper* mapper : mappers)
    {
      mapper->SetInputData(coarse);
    }
    note = CoarseningNote(field, coarse, factor, problem);
    attempt();
  }
  return factor;
}

} // namespace cloudvis
