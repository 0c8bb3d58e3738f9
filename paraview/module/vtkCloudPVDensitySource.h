/**
 * @class   vtkCloudPVDensitySource
 * @brief   the Cloud Density source as ParaView's property panel sets it
 *
 * vtkCloudDensitySource with the two values of a scene's field section that have no single
 * Set method a ParaView property could call: the list of shapes (ParaView has no widget for a
 * list of structures) and the coverage map's file. Both are read by cloudvis's scene reader, so
 * they take exactly what a scene file takes and are refused with the scene's messages:
 *
 * - SetShapes takes the text of a scene's `field.shape` key: a shape name ("sphere"), a shape
 *   object or a JSON array of names and objects (docs/scene-format.md, "Shapes"), such as
 *   `[{"type": "sphere", "radius": 0.8}, {"type": "box", "center": [1, 0, 0]}]`. One text is one
 *   property: a ParaView state file, Python trace and undo keep it whole, and a scene's list is
 *   copied in unchanged. "morph" is the Morph property's, not a shape.
 * - SetCoverageMapFile takes the path of `field.cloud.coverage_map`: a 2-D image or field file,
 *   read into the coverage map; the CoverageSource property still says whether it is used.
 *
 * - SetWeatherMapScale, SetWeatherMapOctaves and SetWeatherMapGain set one argument of
 *   SetWeatherMap each: a property's elements all have one type, and the octaves are whole.
 *
 * A refused value leaves the source as it was and reports the scene reader's message through
 * vtkErrorMacro.
 */
#ifndef vtkCloudPVDensitySource_h
#define vtkCloudPVDensitySource_h

#include "cloudvisParaViewModule.h"
#include "vtkCloudDensitySource.h"

#include <string> // for the texts set

class CLOUDVISPARAVIEW_EXPORT vtkCloudPVDensitySource : public vtkCloudDensitySource
{
public:
  static vtkCloudPVDensitySource* New();
  vtkTypeMacro(vtkCloudPVDensitySource, vtkCloudDensitySource);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The shapes, as the text of a scene's field.shape. Default "sphere" (the unit sphere).
   */
  void SetShapes(const char* shapes);
  const char* GetShapes() const { return this->Shapes.c_str(); }
  ///@}

  ///@{
  /**
   * The coverage map's file (field.cloud.coverage_map as a path); empty for none. Default empty.
   */
  void SetCoverageMapFile(const char* path);
  const char* GetCoverageMapFile() const { return this->CoverageMapFile.c_str(); }
  ///@}

  ///@{
  /**
   * The procedural weather map's scale, octaves and gain (field.cloud.map_scale, map_octaves,
   * map_gain), one at a time. Defaults 4, 6 and 0.6.
   */
  void SetWeatherMapScale(double scale);
  void SetWeatherMapOctaves(int octaves);
  void SetWeatherMapGain(double gain);
  ///@}

protected:
  vtkCloudPVDensitySource() = default;
  ~vtkCloudPVDensitySource() override = default;

  std::string Shapes = "sphere";
  std::string CoverageMapFile;

private:
  vtkCloudPVDensitySource(const vtkCloudPVDensitySource&) = delete;
  void operator=(const vtkCloudPVDensitySource&) = delete;
};

#endif
