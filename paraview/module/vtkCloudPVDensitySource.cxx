// The Cloud Density source's shape list and coverage map file, read by the scene reader of
// app/scene (compiled into this module against ParaView's VTK), so that the panel and a scene
// file accept the same values with the same messages.
#include "vtkCloudPVDensitySource.h"

#include "Scene.h"
#include "SceneField.h"

#include <vtkObjectFactory.h>

#include <exception>

vtkStandardNewMacro(vtkCloudPVDensitySource);

namespace
{
// The field section of a scene holding `keys` and the defaults, read and validated as
// `cloudvis generate` reads a scene file; throws InputError with the scene reader's message,
// which starts with `property`.
cloudvis::FieldSpec ReadFieldKeys(const nlohmann::json& keys, const char* property)
{
  const nlohmann::json document = { { "field", keys } };
  return cloudvis::SceneFromDocument(document, property, "").Field;
}
}

void vtkCloudPVDensitySource::SetShapes(const char* shapes)
{
  const std::string text = shapes ? shapes : "";
  if (text == this->Shapes)
  {
    return;
  }
  // A bare name ("box") is what a user types in the panel; JSON wants it quoted.
  nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
  if (value.is_discarded())
  {
    value = text;
  }
  try
  {
    const cloudvis::FieldSpec spec = ReadFieldKeys({ { "shape", value } }, "Shapes");
    if (spec.Description.Morph)
    {
      vtkErrorMacro(<< "Shapes: \"morph\" is not a shape here: the Morph property turns the morph "
                       "on; the shapes stay "
                    << this->Shapes);
      return;
    }
    cloudvis::FieldDescription field = this->GetField();
    field.Shapes = spec.Description.Shapes;
    this->SetField(field);
    this->Shapes = text;
  }
  catch (const std::exception& error)
  {
    vtkErrorMacro(<< error.what() << "; the shapes stay " << this->Shapes);
  }
}

void vtkCloudPVDensitySource::SetCoverageMapFile(const char* path)
{
  const std::string file = path ? path : "";
  if (file == this->CoverageMapFile)
  {
    return;
  }
  cloudvis::FieldDescription field = this->GetField();
  if (file.empty())
  {
    field.Layer.Map.reset();
  }
  else
  {
    try
    {
      // "shapes" and "noise" are coverage sources in a scene; here the text is always a path.
      const std::string asPath = (file == "shapes" || file == "noise") ? "./" + file : file;
      const cloudvis::FieldSpec spec =
        ReadFieldKeys({ { "density_model", "cloud" }, { "cloud", { { "coverage_map", asPath } } } },
          "CoverageMapFile");
      field.Layer.Map = cloudvis::MakeDensitySource(spec)->GetField().Layer.Map;
    }
    catch (const std::exception& error)
    {
      vtkErrorMacro(<< error.what() << "; the coverage map stays "
                    << (this->CoverageMapFile.empty() ? "none" : this->CoverageMapFile));
      return;
    }
  }
  // SetField keeps the coverage source: the CoverageSource property says whether the map is used.
  this->SetField(field);
  this->CoverageMapFile = file;
}

void vtkCloudPVDensitySource::SetWeatherMapScale(double scale)
{
  const cloudvis::CloudLayer& layer = this->GetField().Layer;
  this->SetWeatherMap(scale, layer.MapOctaves, layer.MapGain);
}

void vtkCloudPVDensitySource::SetWeatherMapOctaves(int octaves)
{
  const cloudvis::CloudLayer& layer = this->GetField().Layer;
  this->SetWeatherMap(layer.MapScale, octaves, layer.MapGain);
}

void vtkCloudPVDensitySource::SetWeatherMapGain(double gain)
{
  const cloudvis::CloudLayer& layer = this->GetField().Layer;
  this->SetWeatherMap(layer.MapScale, layer.MapOctaves, gain);
}

void vtkCloudPVDensitySource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Shapes: " << this->Shapes << "\n";
  os << indent << "CoverageMapFile: " << this->CoverageMapFile << "\n";
}
