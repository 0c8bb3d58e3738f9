// The fully resolved scene as a JSON document: every value the renderer used, defaults included
// and the camera placed, so that an exported image carries what it takes to make it again
// (`cloudvis render scene.json` on the document re-renders the same image). Exports embed it as
// metadata (docs/export.md).
//
// The document is written from the validated Scene by the scene schema (SceneSchema.cxx), the
// same table that reads it: every key of every section, defaults included. A transfer-function
// preset is spelt out point by point, a sky's sun is the direction it resolved to, and the lights
// are written even when the scene took the default sun.
#ifndef cloudvis_SceneJson_h
#define cloudvis_SceneJson_h

#include "Scene.h"

#include <nlohmann/json.hpp>

#include <array>

namespace cloudvis
{

// The camera as the renderer placed it (export/ExportRender.h ResolveCamera): position, focal
// point and the scene's view-up as given (the renderer orthogonalises it itself).
struct ResolvedCamera
{
  std::array<double, 3> Position{ { 0.0, 0.0, 1.0 } };
  std::array<double, 3> FocalPoint{ { 0.0, 0.0, 0.0 } };
  std::array<double, 3> ViewUp{ { 0.0, 1.0, 0.0 } };
};

// The resolved document, with the camera written as `camera` places it.
nlohmann::json SceneToJson(const Scene& scene, const ResolvedCamera& camera);

} // namespace cloudvis

#endif
