// The field reader: cloudvis's ReadField (app/scene, compiled into this module against
// ParaView's VTK) behind a VTK image reader's pipeline requests.
#include "vtkCloudFieldReader.h"

#include "Errors.h"
#include "FieldIO.h"
#include "FieldUnits.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMatrix3x3.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <exception>

vtkStandardNewMacro(vtkCloudFieldReader);

vtkCloudFieldReader::vtkCloudFieldReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkCloudFieldReader::~vtkCloudFieldReader()
{
  this->SetFileName(nullptr);
  this->SetFormat(nullptr);
  this->SetArrayName(nullptr);
}

bool vtkCloudFieldReader::ReadFile()
{
  // The step the pipeline's time chose, else the TimeStep property's.
  const int step = this->PipelineStep >= 0 ? this->PipelineStep : this->TimeStep;
  if (this->FieldTime == this->GetMTime() && this->FieldStep == step)
  {
    return this->Field != nullptr;
  }
  this->FieldTime = this->GetMTime();
  this->FieldStep = step;
  this->Field = nullptr;
  this->TimeValues.clear();
  this->LastError.clear();
  try
  {
    if (!this->FileName || !*this->FileName)
    {
      throw cloudvis::InputError("no file name is set");
    }
    cloudvis::FieldReadOptions options;
    options.Format = this->Format ? this->Format : "";
    options.Array = this->ArrayName ? this->ArrayName : "";
    if (step >= 0)
    {
      options.TimeStep = step;
    }
    if (this->MissingAsEmpty)
    {
      options.Missing = cloudvis::MissingValueRule::Empty;
    }
    if (this->MaximumVoxels < 1)
    {
      throw cloudvis::InputError(std::string(this->FileName) + ": MaximumVoxels must be >= 1");
    }
    options.MaximumVoxels = static_cast<std::uint64_t>(this->MaximumVoxels);
    // ReadField checks the options against the format, as it checks a scene's field keys, and
    // decides the field's units (ResolveFieldValues: what the file declares, no scene here).
    cloudvis::FieldReport report;
    this->Field = cloudvis::ReadField(this->FileName, options, &report);
    // The steps ParaView's animation goes through: the time coordinate's values, else the
    // steps' numbers.
    if (report.TimeSteps > 1)
    {
      this->TimeValues = report.Times;
      if (this->TimeValues.size() != report.TimeSteps)
      {
        this->TimeValues.resize(report.TimeSteps);
        for (std::size_t i = 0; i < report.TimeSteps; ++i)
        {
          this->TimeValues[i] = double(i);
        }
      }
    }
    // The units the field has, as `cloudvis info` reports them, for ParaView's Information panel
    // and scripts: field data, one value each, which every piece cropped from the field keeps.
    const cloudvis::ResolvedFieldUnits& u = report.Resolved;
    vtkFieldData* data = this->Field->GetFieldData();
    const auto text = [data](const char* name, const std::string& value)
    {
      vtkNew<vtkStringArray> array;
      array->SetName(name);
      array->InsertNextValue(value);
      data->AddArray(array);
    };
    text("quantity", cloudvis::QuantityName(u.Quantity));
    text("length_unit", cloudvis::LengthUnitName(u.Length));
    text("up", cloudvis::AxisName(u.Up));
    vtkNew<vtkDoubleArray> radius;
    radius->SetName("effective_radius");
    radius->InsertNextValue(u.EffectiveRadius);
    data->AddArray(radius);
    vtkNew<vtkDoubleArray> droplets;
    droplets->SetName("droplet_number");
    droplets->InsertNextValue(u.DropletNumber);
    data->AddArray(droplets);
  }
  catch (const std::exception& error)
  {
    this->LastError = error.what();
    vtkErrorMacro(<< this->LastError);
  }
  return this->Field != nullptr;
}

int vtkCloudFieldReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  // A new file or new options: the step a time chose in the last file need not exist in this
  // one, which is read at TimeStep until the pipeline asks for a time of its own.
  if (this->FieldTime != this->GetMTime())
  {
    this->PipelineStep = -1;
  }
  // A file that cannot be read is reported once, by name (ReadFile), and yields an empty image:
  // failing the request would add the executive's own message, which names no file.
  if (!this->ReadFile())
  {
    const int empty[6] = { 0, -1, 0, -1, 0, -1 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    return 1;
  }
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), this->Field->GetExtent(), 6);
  outInfo->Set(vtkDataObject::ORIGIN(), this->Field->GetOrigin(), 3);
  outInfo->Set(vtkDataObject::SPACING(), this->Field->GetSpacing(), 3);
  outInfo->Set(vtkDataObject::DIRECTION(), this->Field->GetDirectionMatrix()->GetData(), 9);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_FLOAT, 1);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  if (this->TimeValues.empty())
  {
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
  }
  else
  {
    const std::vector<double>& times = this->TimeValues;
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), int(times.size()));
    const auto [first, last] = std::minmax_element(times.begin(), times.end());
    const double range[2] = { *first, *last };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
  return 1;
}

int vtkCloudFieldReader::StepAt(double time) const
{
  // The last step at or before `time` (ParaView's snap to time steps), the first before them
  // all; a time coordinate need not increase (NetCDF does not require it), so the nearest
  // below is searched in order.
  int best = -1;
  for (std::size_t i = 0; i < this->TimeValues.size(); ++i)
  {
    if (this->TimeValues[i] <= time &&
      (best < 0 || this->TimeValues[i] > this->TimeValues[std::size_t(best)]))
    {
      best = int(i);
    }
  }
  return best >= 0 ? best : 0;
}

int vtkCloudFieldReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  output->Initialize();
  // A time asked by the pipeline (ParaView's animation) chooses the step of a file with a time
  // axis; without one, the TimeStep property does.
  const bool timed =
    !this->TimeValues.empty() && outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
  this->PipelineStep =
    timed ? this->StepAt(outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP())) : -1;
  // A file that cannot be read leaves the output empty (its problem has been reported).
  if (!this->ReadFile())
  {
    return 1;
  }
  int extent[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent);
  output->ShallowCopy(this->Field);
  // Crop copies the requested sub-extent's voxels (a rank's piece) and keeps the whole otherwise.
  output->Crop(extent);
  if (!this->TimeValues.empty())
  {
    const int step = this->FieldStep >= 0 ? this->FieldStep : 0;
    output->GetInformation()->Set(
      vtkDataObject::DATA_TIME_STEP(), this->TimeValues[std::size_t(step)]);
  }
  return 1;
}

void vtkCloudFieldReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "Format: " << (this->Format ? this->Format : "(by extension)") << "\n";
  os << indent << "ArrayName: " << (this->ArrayName ? this->ArrayName : "(default)") << "\n";
  os << indent << "TimeStep: " << this->TimeStep << "\n";
  os << indent << "MissingAsEmpty: " << this->MissingAsEmpty << "\n";
  os << indent << "MaximumVoxels: " << this->MaximumVoxels << "\n";
  os << indent << "LastError: " << this->LastError << "\n";
}
