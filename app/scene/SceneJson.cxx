// Scene -> JSON, the inverse of SceneFromDocument: every section's writer comes from the same
// schema entry as its reader (SceneSchema.cxx), so each key is written with the name, the
// enumeration names and the nesting it is read with, defaults included.
#include "SceneJson.h"

#include "SceneSchema.h"

namespace cloudvis
{

nlohmann::json SceneToJson(const Scene& scene, const ResolvedCamera& camera)
{
  // The camera as placed replaces the scene's: its position and focal point are what the
  // defaults and an orbit became.
  Scene placed = scene;
  placed.Camera.Position = camera.Position;
  placed.Camera.FocalPoint = camera.FocalPoint;
  placed.Camera.ViewUp = camera.ViewUp;
  placed.Camera.Orbit.reset();
  nlohmann::json document = schema::WriteObject(schema::SceneSections(), placed);
  if (scene.Description.empty())
  {
    document.erase("description");
  }
  // Paths and --set strings may hold bytes that are not UTF-8; escaped, every dump() succeeds.
  return WithValidUtf8(std::move(document));
}

} // namespace cloudvis
