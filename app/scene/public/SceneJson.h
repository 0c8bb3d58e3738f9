// The fully resolved scene as a JSON document: every value the renderer used, defaults included
// and the camera placed, so that an exported image carries what it takes to make it again
// (`cloudvis render scene.json` on the document re-renders the same image). Exports embed it as
// metadata (docs/export.md).
//
// The document is built from the Scene's document (the user's keys after overrides) with every
// key this module knows written over it from the validated Scene. A key it does not know (a
// section added later) keeps the user's value, so the embedded scene still re-renders; only that
// key's default is then implicit.
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
