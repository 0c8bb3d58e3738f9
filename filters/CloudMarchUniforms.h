// What the march shader reads from its uniforms, computed on the host once for both renderers:
// vtkCloudVolumeMapper uploads a MarchUniforms as GLSL uniforms, and the CPU reference
// (CloudReferenceMarch.h) marches with the same struct. SetUpMarch builds it, in double, from
// what a renderer is given (the image's geometry, the volume's matrix, the transfer table, the
// step, the lighting and the lights) and refuses what float arithmetic cannot render
// faithfully, so the two renderers compute in the same frame and refuse the same inputs with
// the same words.
//
// The local frame. The march never computes with world coordinates: a volume 1e10 units from
// the origin would lose its detail to float rounding, and one 1e19 units wide would overflow the
// squares inside a length. It computes in a frame translated to the volume's centre and scaled
// by a power of two near the volume's smallest voxel edge, x_local = (x_world - Anchor) / Unit.
// Every length the march uses (t along a ray, the step, light distances, light-march segments,
// the derivative distance) is in local units and every extinction per local unit. The frame's
// axes are the world's, so directions and angles are the world's; and since Unit is a power of
// two, a scene scaled by a power of two (volume, camera, lights, unit distance) renders the
// very same floats.
#ifndef CloudMarchUniforms_h
#define CloudMarchUniforms_h

#include "CloudDensityTexels.h"
#include "CloudLightingParameters.h"
#include "CloudTransferTable.h"
#include "cloudvisFiltersModule.h"

#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkSmartPointer.h>

#include <glm/glm.hpp>

#include <string>
#include <vector>

class vtkImageData;
class vtkMatrix4x4;

namespace cloudvis
{
struct LightVolumes;
struct OpticalDepthGrid;
struct ScatteringGrid;
struct WholeFieldScattering;

// The most samples one view ray may take. A step that would need more along the volume's
// longest ray is refused with the smallest step the volume allows (docs/scene-format.md,
// render.step): at 65536 a ray can still take 37 samples per voxel along the diagonal of a
// 1024^3 field, while the GPU's loop, and the time a frame takes, stay bounded.
constexpr int MaxSamplesPerRay = 65536;

// What float arithmetic holds with room for the sums and products the march makes of a
// quantity (an accumulated radiance, an optical depth over a few segments): FLT_MAX / 64.
// Renderers refuse lights, extinctions and geometries whose derived quantities reach it.
constexpr double FloatLimit = FloatMax / 64.0;

// How far from the volume's centre, in local units (about voxels), a point light may be: its
// squared distance must stay within float range (3.4e38) inside the march.
constexpr double MaxPointLightDistance = 1e18;

// Where a volume's voxels lie. An index point p counts voxels from the first of the image's
// extent, voxel centres at the integers 0 .. Dimensions - 1; the world point is
// VolumeMatrix * (Origin + Direction * diag(Spacing) * (ExtentStart + p)), as VTK's image data
// and vtkProp3D define them.
struct VolumeGeometry
{
  glm::ivec3 Dimensions{ 0 };
  glm::dmat4 IndexToWorld{ 1.0 };
};

// The geometry of `image` placed by `volumeMatrix` (model to world, vtkProp3D::GetMatrix();
// null means identity).
CLOUDVISFILTERS_EXPORT VolumeGeometry GeometryOf(vtkImageData* image, vtkMatrix4x4* volumeMatrix);

// Empty when `image`'s origin, spacing and direction matrix and the volume matrix describe a
// volume a renderer can draw, else the problem naming the quantity: a spacing that is not a
// positive finite number, a non-finite origin, a direction or volume matrix that is not finite
// or is singular, a volume matrix that is not affine.
CLOUDVISFILTERS_EXPORT std::string ValidateVolumeGeometry(vtkImageData* image,
  vtkMatrix4x4* volumeMatrix);

// The march's frame for a volume (see the top of this file).
struct CLOUDVISFILTERS_EXPORT LocalFrame
{
  glm::dvec3 Anchor{ 0.0 }; // the world point at local 0: the volume's centre
  double Unit = 1.0;        // world units per local unit: a power of two
  glm::dmat4 IndexToLocal{ 1.0 };
  glm::dmat4 LocalToIndex{ 1.0 };
  double SmallestVoxelEdge = 1.0; // world units: the shortest edge of a voxel
  double LongestChord = 0.0;      // local units: the volume's longest diagonal

  glm::dvec3 ToLocal(const glm::dvec3& world) const { return (world - this->Anchor) / this->Unit; }
};

CLOUDVISFILTERS_EXPORT LocalFrame MakeLocalFrame(const VolumeGeometry& geometry);

// The shortest edge of a voxel in world units, after the volume's placement: the image's spacing
// through its direction matrix and the volume's matrix (a volume scaled by 2 has voxels twice as
// long as its image's spacing says).
CLOUDVISFILTERS_EXPORT double SmallestVoxelEdge(const VolumeGeometry& geometry);

// The world distance between samples that a renderer's sample distance means for a volume: the
// distance itself when it is > 0, else one voxel, SmallestVoxelEdge. SetUpMarch marches with it
// and the viewer's step keys scale it, so "0 means one voxel" has one meaning everywhere.
CLOUDVISFILTERS_EXPORT double EffectiveSampleDistance(const VolumeGeometry& geometry,
  double sampleDistance);

// Normalized device coordinates to the local frame, for a camera given camera-relative: its
// projection (view coordinates to normalized device coordinates), the rotation from world axes to
// view axes (rows: right, up, backward), and the eye's world position. Built from
// Anchor - eye, so no world coordinate enters the matrix: a camera and a volume both 1e10 from
// the origin keep the precision of the same scene at the origin. The DCLocalMatrix of the march
// shader; the CPU reference maps its pixels with the same matrix.
CLOUDVISFILTERS_EXPORT glm::dmat4 DeviceToLocal(const LocalFrame& frame,
  const glm::dmat4& viewToDevice,
  const glm::dmat3& worldToView,
  const glm::dvec3& eye);

// The uniforms of shaders/CloudMarchFS.glsl and the lighting models, by the GLSL's names.
struct MarchUniforms
{
  // DensityTexture: how its texels hold the density (their format; Scale and Bias are the
  // GLSL's DensityScale and DensityBias) and, for the CPU reference, Dimensions.x * .y * .z
  // texels, x fastest (the mapper uploads a texture instead).
  DensityTexels Density;
  glm::ivec3 Dimensions{ 0 };
  glm::mat4 IndexToLocal{ 1.0f };
  glm::mat3 LocalToIndex{ 1.0f }; // a local displacement in index units
  // TransferTexture: albedo and sigma_t per world unit; times ExtinctionUnit (the frame's Unit)
  // it is per local unit.
  const TransferTable* Table = nullptr;
  float ExtinctionUnit = 1.0f;
  float Step = 1.0f; // local units between samples along a view ray
  float TerminationTransmittance = 1.0f / 255.0f;
  // The samples along the longest ray through the volume, and those plus a margin: the CPU's
  // loop bound. The GPU's adds one iteration per leap over empty bricks.
  int LongestRaySamples = 1;
  int MaximumSamples = 1;

  // The lighting model and its parameters, with DerivativeDistance and LightStep resolved (0
  // means 4 and 2 voxel edges) and in local units.
  LightingParameters Lighting;
  float DerivativeSlopeScale = 1.0f; // 1 / (h in world units * density unit), docs/lighting.md
  std::vector<LocalLight> Lights;
  glm::vec3 Ambient{ 0.0f }; // AmbientColor * AmbientStrength
  // The CPU's light volumes (CloudLightVolumes.h), computed by the renderer for the march with
  // Lighting.Transmittance Volumes; without them (a caller that marches single rays, as unit tests
  // do) the march takes the nested march toward each light. The GPU binds a texture instead.
  const LightVolumes* LightDepths = nullptr;
  // The CPU's multiple-scattering volume (CloudScatteringVolume.h), computed by the renderer for
  // the march when its multiple scattering comes from the volume; without it the octaves add it.
  const ScatteringGrid* MultipleScattering = nullptr;
  // Or, on the GPU, that the mapper binds the volume's textures for the march (MultipleScattering
  // stays null). Either way TransportOf turns the volume on, with the finest grid's size
  // (ScatteringVolumeSize of Dimensions).
  bool ScatteringVolumeTextures = false;
  // Optical depth toward each light from outside the volume (CloudOpticalDepthGrid.h: other
  // pieces of a distributed field), added to every optical depth toward a light; null: none.
  // IndexToExternal maps an index point to the grid's texel coordinates. Both set by
  // SetExternalOpticalDepths; on the GPU the mapper binds the grid as a texture.
  const OpticalDepthGrid* ExternalDepths = nullptr;
  glm::mat4 IndexToExternal{ 1.0f };
  // A multiple-scattering volume solved over the whole field this volume is a piece of
  // (CloudScatteringVolume.h), read instead of its own through IndexToScattering (index points to
  // its texel coordinates); null: none. Both set by SetExternalScatteringVolume; on the GPU the
  // mapper binds it as the volume's textures.
  const WholeFieldScattering* ExternalScattering = nullptr;
  glm::mat4 IndexToScattering{ 1.0f };
};

// What a renderer is given.
struct MarchSetup
{
  VolumeGeometry Geometry;
  DensityTexels Density;                // the field's texels (DensityTexelsOf)
  const TransferTable* Table = nullptr; // sigma_t per world unit
  double SampleDistance = 0.0;          // world units; 0: the smallest voxel edge
  double TerminationTransmittance = 1.0 / 255.0;
  LightingParameters Lighting; // DerivativeDistance and LightStep in world units, 0: automatic
  std::vector<Light> Lights;
};

// Which input a problem concerns, so a caller can name it in its own terms (a scene key).
enum class MarchInput
{
  None,
  Geometry,         // the volume's geometry
  TransferFunction, // its range, its extinction (unit distance)
  Step,             // the sample distance
  Lighting,         // the lighting parameters
  Light,            // one light: MarchProblem::Light
};

struct MarchProblem
{
  MarchInput Input = MarchInput::None;
  int Light = -1;      // the light's index when Input is Light
  std::string Message; // empty when there is no problem
  explicit operator bool() const { return !this->Message.empty(); }
};

// Fills `uniforms` (all but Density) and `frame` (when not null) for `setup`, or returns why it
// cannot be rendered faithfully: an unusable geometry; a table that is empty, spans densities
// wider than float arithmetic holds, or whose extinction overflows float within the volume; a
// step outside [0, infinity) or one that needs more than MaxSamplesPerRay samples (the message
// gives the smallest step the volume allows); invalid lighting parameters or derived distances
// that round to 0 or infinity in float; more than LightingLimits::MaxLights lights; a light that is
// not finite, a directional light without direction, a point light beyond MaxPointLightDistance, or
// lights bright enough to overflow float in the radiance they make a sample send toward the eye.
CLOUDVISFILTERS_EXPORT MarchProblem SetUpMarch(const MarchSetup& setup,
  MarchUniforms& uniforms,
  LocalFrame* frame = nullptr);

// The switched-on lights of a collection, as the renderers light with them: directional or
// positional, at their transformed position and focal point (vtkLight::GetTransformedPosition),
// with their diffuse color, intensity and attenuation values. All of them: SetUpMarch refuses
// more than LightingLimits::MaxLights rather than dropping some. None for a null collection.
// Where VTK lights a cloud (a renderer's lights, a collection given from Python).
CLOUDVISFILTERS_EXPORT std::vector<Light> LightsOf(vtkLightCollection* lights);

// A light as a vtkLight, the inverse of LightsOf: a scene light (fixed in world coordinates),
// positional for point lights (cone angle 180: no spot), with the light's position, focal
// point, color as the diffuse color, intensity and attenuation values. For VTK's own mappers
// and for renderers lit the VTK way.
CLOUDVISFILTERS_EXPORT vtkSmartPointer<vtkLight> MakeLight(const Light& light);
// MakeLight of each light, in order.
CLOUDVISFILTERS_EXPORT vtkSmartPointer<vtkLightCollection> MakeLights(
  const std::vector<Light>& lights);

// The MarchSetup of what a renderer holds, in the one way the GPU mapper and the CPU renderers
// read it: `image`'s geometry placed by `volumeMatrix` (null: identity), its texels, the table,
// the step, the termination transmittance, the lighting and the lights.
CLOUDVISFILTERS_EXPORT MarchSetup MakeMarchSetup(vtkImageData* image,
  vtkMatrix4x4* volumeMatrix,
  const DensityTexels& texels,
  const TransferTable* table,
  double sampleDistance,
  double terminationTransmittance,
  const LightingParameters& lighting,
  std::vector<Light> lights);

} // namespace cloudvis

#endif
