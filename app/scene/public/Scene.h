// A scene file, parsed and validated: what cloudvis should show or export. A scene is a JSON
// object of sections (field, transfer_function, camera, background, render, lights, ambient,
// view); the names render.lighting takes are LightingModelTable's (CloudLightingParameters.h);
// every key of every section is one entry of the scene schema (SceneSchema.cxx), which the
// reader, --set, the resolved scene of SceneJson.h and the reference tables of
// docs/scene-format.md (SceneReferenceMarkdown) all walk. Defaults are the members' initial
// values below. Overrides from the command line
// (--set key=value, and options such as --lighting that stand for a key) are applied to the JSON
// document before validation, so a value from a file and a value from the command line are
// checked by the same code and reported with the same dotted key.
// The schema is documented in docs/scene-format.md.
#ifndef cloudvis_Scene_h
#define cloudvis_Scene_h

#include "CameraDetail.h"
#include "CloudDensityEvaluator.h"
#include "CloudDisplayTransform.h"   // DisplayCurve
#include "CloudLightingParameters.h" // LightingParameters, Light, the models' names
#include "FieldIO.h"                 // FieldReadOptions

#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace cloudvis
{

// The "field" section: either a field file to load, or where and how to generate a procedural
// field.
struct FieldSpec
{
  // Path of a field file (FieldIO.h) to load instead of generating, already resolved against the
  // scene file's folder; empty for a procedural field (then the members below Read apply).
  std::string File;
  // How File is read: field.format, field.array, field.time_step, field.missing,
  // field.max_voxels, field.raw. A generated field takes MaximumVoxels too, as the cap of
  // AutoDimensions.
  FieldReadOptions Read;
  std::array<int, 3> Dimensions{ { 128, 128, 128 } };
  // field.dimensions "auto": present when it was given. Once the whole scene is read, Dimensions
  // are chosen from the camera (ChooseCameraDetail, CameraDetail.h) and this says why.
  std::optional<CameraDetail> AutoDimensions;
  std::array<double, 6> Bounds{ { -2.0, 2.0, -2.0, 2.0, -2.0, 2.0 } };
  FieldDescription Description;
  // field.cloud.coverage_map when it names a file (resolved like File); read into
  // Description.Layer.Map once, when the scene is read, if the cloud model uses it
  // (LoadCoverageMap, SceneField.h).
  std::string CoverageMapFile;
  double Time = 0.0;
  // field.quantity, field.length_unit, field.up, field.effective_radius: what the values and
  // world units mean, for a generated field and a file alike (absent: the file's, else the
  // defaults; FieldUnits.h).
  FieldUnits Units;
  // The units the field has, Units combined with what a field file declares
  // (ResolveFieldValues, FieldIO.h): set when the scene is read for a generated field, and by
  // ProduceField (SceneField.h) once a field file is read; empty until then.
  std::optional<ResolvedFieldUnits> Resolved;

  bool FromFile() const { return !this->File.empty(); }
};

// The "transfer_function" section: what density looks like. Opacity is per UnitDistance of
// world units (the mapper turns it into the extinction sigma_t = -ln(1 - a) / u), color is the
// albedo. Points are (density, value...) with strictly increasing densities; between points the
// functions are linear, beyond the ends they hold the end values.
struct TransferFunctionSpec
{
  // Defaults chosen for the default field (densities 0 .. ~0.95, most of the cloud below 0.3):
  // thin wisps stay translucent, the core builds up without saturating, and the grey-to-white
  // color gives depth where there is no lighting.
  std::vector<std::array<double, 2>> Opacity{ { { 0.0, 0.0 } }, { { 0.02, 0.0 } },
    { { 0.5, 0.5 } }, { { 1.0, 0.8 } } };
  std::vector<std::array<double, 4>> Color{ { { 0.0, 0.55, 0.58, 0.65 } },
    { { 0.3, 0.9, 0.9, 0.92 } }, { { 1.0, 1.0, 1.0, 1.0 } } };
  double UnitDistance = 0.1;
  // transfer_function.extinction: "opacity" (the points above) or "droplets", the extinction of
  // cloud droplets, 3 LWC / (2 rho_w r_e), for an lwc field (FieldUnits.h) over densities
  // [0, LwcMax] g/m^3 (beyond it the table holds its last entry, as for any transfer function).
  enum class ExtinctionRule
  {
    Opacity,
    Droplets,
  };
  ExtinctionRule Extinction = ExtinctionRule::Opacity;
  double LwcMax = 5.0;
  // Droplets: the extinction per world unit of 1 g/m^3, from the field's resolved effective
  // radius and length unit (ResolveFieldOptics): set when the scene is read for a generated
  // field, once the file is read for a field file (0 until then: TabulatedTransferFunction
  // refuses to tabulate it).
  double DropletExtinctionPerLwc = 0.0;
  // Droplets: sigma(LWC) = DropletExtinctionPerLwc * LWC^DropletLwcPower, LWC in g/m^3. 1 for
  // droplets of one effective radius; 2/3 for a given droplet number, whose r_e grows as
  // LWC^(1/3) (field.droplet_number).
  double DropletLwcPower = 1.0;
};

// What the renderers tabulate (MakeVolumeProperty): the spec itself, or for "droplets" the spec
// with Opacity and UnitDistance replaced by points at each of the TransferTableSize densities the
// table samples (the union of [0, LwcMax] and the color points' span), opacity
// 1 - exp(-sigma(d) u), with u chosen so the densest stays well below VTK's opacity 1: the table
// then holds sigma(d) = DropletExtinctionPerLwc * d^DropletLwcPower at every entry, to float
// precision.
TransferFunctionSpec TabulatedTransferFunction(const TransferFunctionSpec& transferFunction);

// The density above which the function's opacity rises from 0: the last point of opacity 0
// before the first that is not (the first point's density when it is not 0; the last's when none
// rises). Values at or below it are transparent.
double OpacityRisesAbove(const TransferFunctionSpec& spec);

// Whether the function's opacity is 0 at every point (extinction from the opacity points): a
// scene that hides the cloud on purpose, to render the background alone.
bool HidesEveryValue(const TransferFunctionSpec& spec);

// The densities a function's points span, opacity and color points together.
std::array<double, 2> TransferFunctionSpan(const TransferFunctionSpec& spec);
// The function with its points' densities mapped linearly from TransferFunctionSpan(spec) onto
// `target` (values unchanged): the viewer's `f` and FitTransferFunctionToField. Unchanged when
// either span is empty.
TransferFunctionSpec StretchTransferFunction(const TransferFunctionSpec& spec,
  const std::array<double, 2>& target);

// The "camera" section. Absent keys are filled when the field is known (see ApplyCamera in
// export/OffscreenRender.h): the focal point is the field's centre, the position looks at it
// along -z from the distance vtkRenderer::ResetCamera picks to fit the field's bounds.
// camera.orbit: the position on a sphere around the focal point, y up. With azimuth az and
// elevation el in degrees, position = focal + distance * (cos(el) sin(az), sin(el), cos(el) cos(az)),
// so az = 0, el = 0 is the default view from +z, az = 90 looks from +x, el > 0 looks down.
struct OrbitSpec
{
  double Azimuth = 0.0;   // degrees, any
  double Elevation = 0.0; // degrees, in (-90, 90)
  std::optional<double> Distance; // world units, > 0; absent: the distance that fits the field
};

// The orbit's position around `focal` at `distance` (the orbit's own when it has one).
std::array<double, 3> OrbitPosition(const OrbitSpec& orbit,
  const std::array<double, 3>& focal,
  double distance);

struct CameraSpec
{
  std::optional<std::array<double, 3>> Position;
  std::optional<OrbitSpec> Orbit; // exclusive with Position
  std::optional<std::array<double, 3>> FocalPoint;
  std::array<double, 3> ViewUp{ { 0.0, 1.0, 0.0 } };
  double ViewAngle = 30.0; // degrees, vertical
  // Not a key: where the camera sits, seen from the focal point, when camera.position and
  // camera.orbit are absent: +z for a field whose up is y; TurnDefaultViewToUp turns it with the
  // view-up for a field whose up is another axis.
  std::array<double, 3> DefaultDirection{ { 0.0, 0.0, 1.0 } };
};

// A scene's lighting before its keys are read: LightingParameters' defaults, with the ambient
// section's own (a dim bluish light from every side; vtkCloudLightingProperty's default is none).
inline LightingParameters DefaultSceneLighting()
{
  LightingParameters lighting;
  lighting.AmbientColor = glm::vec3(0.6f, 0.6f, 0.75f);
  lighting.AmbientStrength = 0.2f;
  return lighting;
}

// The "render" section: how the mapper marches and how large the image is.
struct RenderSpec
{
  // The lighting, one value from the scene file to the renderers' uniforms: its Model is
  // render.lighting (names: LightingModelTable), its parameters render.derivative.* and
  // render.march.*, its AmbientColor and AmbientStrength the ambient section. The renderers are
  // given it whole (SceneLighting.h).
  LightingParameters Lighting = DefaultSceneLighting();
  double Step = 0.0; // world units; 0: one voxel (the smallest spacing of the field)
  bool Jitter = true;
  double ResolutionScale = 1.0;
  // render.gpu_memory: the GPU memory the renderer may take, MiB; absent: what the driver reports
  // free (no limit where it reports nothing). A field whose textures do not fit is coarsened.
  std::optional<double> GpuMemoryMiB;
  int Accumulate = 16; // frames averaged into a still
  bool Reprojection = false; // `cloudvis view`: interactive frames blend the last one, reprojected
  int SamplesPerPixel = 256; // pathtrace: paths averaged per pixel of a still
  bool SkipEmptySpace = true;
  std::array<int, 2> Size{ { 800, 600 } }; // pixels, width and height
  // Whether the scene gives render.march.effective_radius: then the droplets' phase uses it;
  // else the field's effective radius (ResolveFieldOptics), one r_e for extinction and phase.
  bool DropletRadiusGiven = false;
  int PngBits = 8;      // 8 or 16 bits per PNG channel (docs/export.md)
  bool ExrHalf = false; // EXR channels as 16-bit half floats instead of 32-bit floats
  // The display transform of PNG, compare panels and the viewer (filters/CloudDisplayTransform.h):
  // render.exposure (EV, or "auto": AutoExposure, chosen from the rendered cloud's luminance)
  // and render.display. EXR stays linear radiance.
  double ExposureEV = 0.0;
  bool AutoExposure = false;
  DisplayCurve Display = DisplayCurve::Linear;
};

// The "background" section beyond a plain color (Scene::Background): a VTK gradient, or the
// article's sky computed per pixel from the view ray (export/Background.h draws both).
enum class BackgroundType
{
  Solid,    // Scene::Background everywhere
  Gradient, // Scene::Background at the bottom edge, Top at the top edge
  Sky,      // the article's sky: a vertical gradient plus a glow around Sun
};

struct BackgroundSpec
{
  BackgroundType Type = BackgroundType::Solid;
  std::array<double, 3> Top{ { 0.0, 0.0, 0.0 } }; // Gradient: the color at the top edge
  // Sky: unit direction toward the sun (world). A scene file without background.sun gets, once
  // read, the direction toward its first directional light when it has a "lights" key, else
  // normalize(DefaultSun).
  std::optional<std::array<double, 3>> Sun;
  static constexpr std::array<double, 3> DefaultSun{ { 0.5, 0.6, 0.6 } };
};

// The "view" section: how `cloudvis view` shows the scene besides the picture itself (the
// layout, the slices and their colors, the legends), so that a scene the viewer saves opens as
// it was left. `render` checks it and ignores it.
enum class ViewLayout
{
  ThreeD, // the 3D view alone
  Four,   // the 3D view and the axial, coronal and sagittal slice views
};

// The names view.slice_colors takes, in the order the viewer's c key cycles through them.
const std::vector<std::string>& SliceColormapNames();

struct ObliqueSpec
{
  bool Visible = false;
  std::optional<std::array<double, 3>> Origin;       // world; absent: the field's centre
  std::array<double, 3> Normal{ { 1.0, 1.0, 2.0 } }; // not zero; any length
};

struct ViewSpec
{
  ViewLayout Layout = ViewLayout::ThreeD;
  std::array<bool, 3> Slices{ { false, false, false } }; // the slices across x, y and z shown
  // World coordinates of the three slices, each moved to the voxel layer nearest to it; absent:
  // the field's centre.
  std::optional<std::array<double, 3>> SlicePosition;
  ObliqueSpec Oblique;
  // The slices' [window, level] in density (window > 0); absent: the field's range.
  std::optional<std::array<double, 2>> WindowLevel;
  int SliceColors = 0; // an index of SliceColormapNames()
  bool Legends = true; // the color legends
};

// What is wrong with a slices' window and level ("" when nothing): the window must be greater than
// 0 and both ends, level -+ window / 2, finite numbers. view.window_level and the viewer's typed
// entry check with it.
std::string WindowLevelProblem(double window, double level);

// The lights of a scene without a "lights" key: one white directional sun from (6, 8, 4) toward
// the origin (docs/scene-format.md gives its intensity and why).
std::vector<Light> DefaultLights();

struct Scene
{
  // Where the scene came from, for messages: the scene file's path, or "default scene".
  std::string Source = "default scene";
  std::string Description;
  FieldSpec Field;
  TransferFunctionSpec TransferFunction;
  CameraSpec Camera;
  // The solid color, or the bottom color of a gradient; BackgroundStyle says which is drawn.
  std::array<double, 3> Background{ { 0.1, 0.12, 0.16 } };
  BackgroundSpec BackgroundStyle;
  RenderSpec Render;
  // The "lights" section (at most LightingLimits::MaxLights; DefaultLights() when the key is
  // absent), given to the renderers as they are. The "ambient" section is Render.Lighting's.
  std::vector<Light> Lights = DefaultLights();
  // The "view" section, absent from scenes that have none (the viewer's defaults apply then).
  std::optional<ViewSpec> View;
  // The validated JSON document as given, after overrides and before defaults (the fully
  // resolved one is SceneToJson's, written from the members above).
  nlohmann::json Document;
};

// The default view and lights are made for a field whose up is y: the camera looks along -z with
// y up, the sun shines from above (+y). For a field whose up (ResolvedFieldUnits::Up, from the
// file or field.up) is another axis, turns what the scene leaves to the defaults by the rotation
// that takes y to that axis (z up: y to z, z to -y, so the camera looks across the domain from
// -y, z up, and the sun shines from above): the camera's view-up and direction when the scene
// gives none of camera.position, camera.orbit and camera.view_up, and the lights when it has no
// lights section. A scene's own camera and lights are kept.
void TurnDefaultViewToUp(Scene& scene, int up);

// How a scene's transfer function met its field's values (FitTransferFunctionToField).
enum class TransferFunctionFit
{
  Kept,                  // nothing to do
  FittedToValues,        // a field file given alone: the default stretched over [min, max]
  GrownToValues,         // no transfer_function: the default widened to take the values in
  ValuesBeyondItsPoints, // the scene's own function, kept, does not cover the values
};

// The transfer function a render or a session starts with, as ParaView meets a new dataset's
// colour map (its data range when first shown, grown afterwards, a saved state's as saved): a
// field file given alone (`fieldFileAlone`: no scene, so no function of its own) has the default
// function stretched over the field's values [min, max]; a scene without a transfer_function has
// the default kept where its points cover the values, stretched to take them in where they lie
// beyond it, and stretched over them where all of them lie where the default is transparent (a
// field of mixing ratios below 1e-3 under a default that starts at 0.02); a scene's own function
// is kept as it is. The droplet extinction is physical and never stretched. The shape is kept:
// only the points' densities move, and the default's unit distance, made for the default field's
// box (`field.bounds` [-2, 2]^3), is scaled with the field's box (`bounds`, its diagonal), so a
// field in metres looks as the same field in kilometres does.
TransferFunctionFit FitTransferFunctionToField(Scene& scene,
  const std::array<double, 2>& range,
  bool fieldFileAlone,
  const double bounds[6]);

// A scene value given on the command line by an option that stands for a scene key (--lighting M
// is render.lighting = "M"). It is applied to the document like --set, after the --set
// assignments, and validated with the rest; messages about it name the option.
struct SceneOverride
{
  std::string Key; // dotted
  nlohmann::json Value;
  std::string Option; // "--lighting", for messages
};

// The one place the optics of a scene follow from its field's units `units` (Field.Resolved,
// from ResolveFieldValues: the scene's field keys, else the file's declaration, else the
// defaults): stores them in Field.Resolved; for transfer_function.extinction "droplets" sets
// DropletExtinctionPerLwc from their effective radius and length unit (refused, naming the key
// and the field file `file` when not empty, unless they are an lwc field in m or km); for
// render.march.phase "droplets" without render.march.effective_radius, makes the phase's r_e the
// field's (refused outside the phase table's [2, 30] micrometres). SceneFromDocument calls it for
// a generated field, ProduceField once a field file is read.
void ResolveFieldOptics(Scene& scene, const ResolvedFieldUnits& units, const std::string& file);

// The scene used when none is given: the article's cloud (a unit sphere plus 6 octaves of value
// noise on 128^3 voxels over [-2, 2]^3).
Scene DefaultScene();

// Reads any JSON file cloudvis reads (a scene file, a preset) into a JSON document; `what` names
// it in messages ("preset file"). Throws InputError for an unreadable file (with the OS reason)
// or malformed JSON (with line and column). The file must be a regular file of at most
// MaximumJsonFileBytes (InputFiles.h).
nlohmann::json ReadJsonFile(const std::string& path, const std::string& what);

// The reference tables of docs/scene-format.md, generated from the scene schema: Markdown, each
// table between the lines "<!-- schema:NAME -->" and "<!-- /schema -->" (`cloudvis schema`
// prints it; app.scene_docs checks that the docs hold the same tables).
std::string SceneReferenceMarkdown();

// `value` with every string and object key made valid UTF-8 by EscapeInvalidUtf8 (Utf8.h), so
// that dump() cannot throw: strings from --set and paths may hold any bytes.
nlohmann::json WithValidUtf8(nlohmann::json value);

// Applies one "key=value" assignment (the argument of --set) to a document. The key is dotted
// (field.noise); missing intermediate objects are created. Throws UsageError when the
// assignment has no '=' or an empty key part, InputError when a part of the key names a value
// that is not an object, or when the value is NaN or infinite.
void ApplyOverride(nlohmann::json& document, const std::string& assignment);

// The value of an assignment: JSON when it parses as JSON (6, "perlin", [1,2,3], true), else a
// comma-separated list of numbers as an array (128,128,128), else the text as a string (perlin).
// A key whose schema type is free text (description, field.file, transfer_function.preset) takes
// text that is not JSON as written, even "inf" or "1,2". `key` names the value in errors.
nlohmann::json ParseOverrideValue(const std::string& key, const std::string& text);

// Validates a document and turns it into a Scene. `source` prefixes every message,
// `baseDirectory` resolves relative paths inside the scene (empty: the current directory),
// `overriddenKeys` are the dotted keys set by --set, so messages about them can say so;
// `optionKeys` those set by other options (messages name the option). Throws InputError naming
// the dotted key and the problem.
Scene SceneFromDocument(const nlohmann::json& document, const std::string& source,
  const std::string& baseDirectory, const std::vector<std::string>& overriddenKeys = {},
  const std::vector<SceneOverride>& optionKeys = {});

// All of the above: reads `path` (the default scene when empty), applies the assignments in
// order, then the option overrides, validates. This is what every command that takes a scene
// calls.
Scene LoadScene(const std::string& path, const std::vector<std::string>& assignments,
  const std::vector<SceneOverride>& options = {});

// The scene of a field file given where a scene could be (`cloudvis render cloud.vdb`): the
// default scene whose field.file is `path` (relative to the current directory), with the
// assignments and option overrides applied and validated as LoadScene does, so field.format,
// field.array, field.time_step and field.raw set on the command line are checked like scene keys.
Scene LoadFieldFileScene(const std::string& path,
  const std::vector<std::string>& assignments,
  const std::vector<SceneOverride>& options = {});

// The keys of the field section that say how a field file is read ("file", "format", "array",
// "time_step", "max_voxels", "raw") and what its values mean ("quantity", "length_unit", "up",
// "effective_radius"): the only field keys a field file takes.
const std::vector<std::string>& FieldFileKeyNames();

} // namespace cloudvis

#endif
