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
  if (this->FieldTime == this->GetMTime())
  {
    return this->Field != nullptr;
  }
  this->FieldTime = this->GetMTime();
  this->Field = nullptr;
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
    if (this->TimeStep >= 0)
    {
      options.TimeStep = this->TimeStep;
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
  return 1;
}

int vtkCloudFieldReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkImageData* output = vtkImageData::GetData(outInfo);
  output->Initialize();
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
