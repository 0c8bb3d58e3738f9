// The scene schema: every key of a scene file, written once (SceneSchema.cxx). The reader
// (SceneFromDocument), --set, the resolved scene written into exports (SceneToJson) and the
// reference tables of docs/scene-format.md (SceneReferenceMarkdown) all walk these tables.
#ifndef cloudvis_SceneSchema_h
#define cloudvis_SceneSchema_h

#include "Scene.h"
#include "Schema.h"

namespace cloudvis
{
namespace schema
{

// The sections of a scene file, in the order the docs list them.
const Keys<Scene>& SceneSections();

// The objects inside the sections, for the docs.
// The field section: the keys of a field read from a file (file, format, array, ...), then those
// of a generated one (dimensions, bounds, noise, ...); a section takes keys of one kind only.
const Keys<FieldSpec>& FieldKeys();
const Keys<FieldSpec>& FieldFileKeys();
const Keys<FieldSpec>& GeneratedFieldKeys();
// The keys both kinds take: quantity, length_unit, up, effective_radius.
const Keys<FieldSpec>& FieldUnitKeys();
const Keys<RawLayout>& RawKeys(); // field.raw
const Keys<FieldSpec>& CloudKeys(); // field.cloud
const Keys<Shape>& ShapeKeys();
const Keys<TransferFunctionSpec>& TransferFunctionKeys();
const Keys<CameraSpec>& CameraKeys();
const Keys<OrbitSpec>& OrbitKeys();
const Keys<Scene>& BackgroundKeys(); // used by the types of BackgroundTypes()
const Keys<RenderSpec>& RenderKeys();
const Keys<LightingParameters>& DerivativeKeys();
const Keys<LightingParameters>& MarchKeys();
const Keys<Light>& LightKeys(); // used by the types of LightTypes()
const Keys<LightingParameters>& AmbientKeys(); // the ambient section: Render.Lighting's
// The view section (ViewSchema.cxx): the section's key, its keys and view.oblique's.
Key<Scene> ViewSection();
const Keys<ViewSpec>& ViewKeys();
const Keys<ObliqueSpec>& ObliqueKeys();

const std::vector<Name>& ShapeTypes();
const std::vector<Name>& BackgroundTypes();
const std::vector<Name>& LightTypes();
// A sky without background.sun takes its sun from the lights section, which may come after the
// background in the document: resolved once the whole scene is read.
void ResolveSkySun(const json& document, Scene& scene);

// The optics that follow from the field's units (ResolveFieldOptics in Scene.h), refusals
// naming the key through `context`.
void ResolveFieldOptics(const Context& context,
  Scene& scene,
  const ResolvedFieldUnits& units,
  const std::string& file);
// Once the whole scene is read: whether it gives render.march.effective_radius; for a generated
// field, ResolveFieldOptics with the scene's units; for a field file, what the scene's own keys
// already contradict (the rest waits for the file).
void ResolveDroplets(const Context& context, const nlohmann::json& document, Scene& scene);
// Once the whole scene is read: field.dimensions "auto" chosen from the camera and render.size
// (ChooseCameraDetail); refused, naming the key, without a camera position to choose from.
void ResolveAutoDimensions(const Context& context, Scene& scene);

} // namespace schema
} // namespace cloudvis

#endif
