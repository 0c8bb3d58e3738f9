// Light across the pieces of a distributed field (issue 25), without MPI or ParaView: what a
// rank's vtkCloudPieceExchange computes of its mapper's piece (ComputePieceOpticalDepths,
// ComputePieceScatteringInputs) and gives it from the other pieces (SetExternalOpticalDepths,
// SolveScatteringVolume), checked on pieces cut with vtkExtractVOI, which share one
// plane of points as ParaView's pieces do.
//
// - The depths of two pieces add up to the whole field's at every grid point (CPU alone).
// - A piece rendered with external depths: the GPU image equals the CPU reference given the
//   same depths, and clearing them brings the unshadowed image back (on both).
// - The multiple-scattering volume over the whole field (ScatteringAcrossPieces): the inputs the
//   pieces own, summed, are the whole field's; a piece reading the volume solved from them is the
//   whole field, on the GPU as on the CPU.
// - The exchange's end-to-end property: a dense slab between the sun and a cloud, cut so that the
//   slab is one piece and the cloud another; the cloud piece rendered with the slab piece's
//   depths equals the whole field rendered at once over the pixels whose rays cross the cloud
//   piece alone (a side view, the sun from above).
#include "SupportReference.h"
#include "SupportScene.h"

#include "CloudOpticalDepthGrid.h"
#include "CloudScatteringVolume.h"
#include "vtkCloudPieceExchange.h"
#include "vtkCloudReferenceRenderer.h"

#include <vtkCamera.h>
#include <vtkExtractVOI.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkOpenGLRenderWindow.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <string>

using namespace cloudvis;
using namespace cloudvis::support;

namespace
{
constexpr int Points = 40;     // per axis of the field over [-1, 1]^3
constexpr int SplitPoint = 20; // the plane of points both pieces hold
constexpr int ImageSize = 64;
constexpr float SigmaT = 8.0f; // per world unit at density 1
// The multiple-scattering volume over the whole field (ScatteringAcrossPieces): the pieces'
// summed inputs against the whole field's, relative to the largest value, and a piece reading the
// whole field's volume against the whole rendered at once, relative to the brightest radiance.
// Measured on llvmpipe: the sources (with their moments and the first guess) differ by at most
// 0.051 and RMS 0.0069 of the largest (pieces cut through the ball, at z = 13); the piece's image
// by RMS 0.0078 (1.1 8-bit levels of the linear radiance) and at most 0.023 of the brightest,
// against RMS 0.21 and 0.46 with the piece's own volume. The gates are twice that.
constexpr double SourceMaxGate = 0.1, SourceRmsGate = 0.015;
constexpr double WholeVolumeRmsGate = 0.015, WholeVolumeMaxGate = 0.045;

// The points [first, last] along `axis` of `whole`, as a piece of its own (its extent a
// sub-extent of the whole's, origin and spacing the whole's).
vtkSmartPointer<vtkImageData> Piece(vtkImageData* whole, int axis, int first, int last)
{
  int voi[6];
  whole->GetExtent(voi);
  voi[2 * axis] = first;
  voi[2 * axis + 1] = last;
  vtkNew<vtkExtractVOI> extract;
  extract->SetInputData(whole);
  extract->SetVOI(voi);
  extract->Update();
  auto piece = vtkSmartPointer<vtkImageData>::New();
  piece->DeepCopy(extract->GetOutput());
  return piece;
}

double Ramp(double x)
{
  return std::min(1.0, std::max(0.0, x));
}

// A dense slab across the top (z in [0.35, 0.75]) and a soft ball below it (centre z = -0.45):
// with the sun above, the slab shadows the ball. Soft edges keep the GPU's 8-bit filter weights
// from deciding whole samples.
vtkSmartPointer<vtkImageData> SlabOverCloud()
{
  return MakeBoxField({ Points, Points, Points },
    glm::dvec3(-1.0),
    glm::dvec3(1.0),
    [](double x, double y, double z)
    {
      const double slab = Ramp((0.2 - std::abs(z - 0.55)) / 0.08) *
        Ramp((0.9 - std::max(std::abs(x), std::abs(y))) / 0.1);
      const double r = std::sqrt(x * x + y * y + (z + 0.45) * (z + 0.45));
      return slab + Ramp((0.4 - r) / 0.15);
    });
}

// The world z of the plane of points the pieces share.
double SplitZ()
{
  return -1.0 + 2.0 * SplitPoint / (Points - 1);
}

// The common grid: the whole field's world bounds (placed by `volume`'s matrix, when given) at
// about a quarter of its resolution.
OpticalDepthGrid CommonGrid(vtkImageData* whole, vtkVolume* volume = nullptr)
{
  double model[6];
  whole->GetBounds(model);
  double bounds[6] = { VTK_DOUBLE_MAX,
    -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX,
    -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX,
    -VTK_DOUBLE_MAX };
  for (int corner = 0; corner < 8; ++corner)
  {
    double point[4] = {
      model[corner % 2], model[2 + (corner / 2) % 2], model[4 + corner / 4], 1.0
    };
    if (volume)
    {
      volume->GetMatrix()->MultiplyPoint(point, point);
    }
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = std::min(bounds[2 * a], point[a]);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], point[a]);
    }
  }
  OpticalDepthGrid grid;
  const int size = (Points - 1) / 4 + 1;
  for (int a = 0; a < 3; ++a)
  {
    grid.Origin[a] = bounds[2 * a];
    grid.Size[a] = size;
    grid.Spacing[a] = (bounds[2 * a + 1] - bounds[2 * a]) / (size - 1);
  }
  return grid;
}

// A mapper of its own drawing `piece` as `like`'s mapper draws (its lighting, step, extinction,
// the volume's property and placement, the renderer's lights), as another rank's.
struct RankMapper
{
  vtkNew<vtkCloudVolumeMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkCloudPieceExchange> Exchange;

  RankMapper(vtkImageData* piece, GpuScene& like)
  {
    auto* drawn = vtkCloudVolumeMapper::SafeDownCast(like.Mapper);
    this->Mapper->SetLightingProperty(drawn->GetLightingProperty());
    this->Mapper->SetSampleDistance(drawn->GetSampleDistance());
    this->Mapper->SetExtinctionScale(drawn->GetExtinctionScale());
    this->Mapper->SetInputData(piece);
    this->Volume->SetMapper(this->Mapper);
    this->Volume->SetProperty(like.Volume->GetProperty());
    this->Volume->SetUserMatrix(like.Volume->GetMatrix());
    this->Exchange->SetMapper(this->Mapper);
    this->Exchange->SetVolume(this->Volume);
  }
};

// `grid` filled with what `piece` adds.
OpticalDepthGrid DepthsOf(vtkImageData* piece, GpuScene& like, OpticalDepthGrid grid)
{
  RankMapper rank(piece, like);
  EXPECT_TRUE(rank.Exchange->ComputePieceOpticalDepths(like.Renderer, grid))
    << rank.Exchange->GetLastError();
  return grid;
}

// The cloud piece's external depths as a rank gets them: the sum of both pieces' grids (what an
// MPI_Allreduce of their Depths makes) less its own.
OpticalDepthGrid ExchangedDepths(vtkImageData* whole, GpuScene& cloudPiece)
{
  const OpticalDepthGrid slab = DepthsOf(
    Piece(whole, 2, SplitPoint, Points - 1), cloudPiece, CommonGrid(whole, cloudPiece.Volume));
  const OpticalDepthGrid own = DepthsOf(vtkImageData::SafeDownCast(cloudPiece.Mapper->GetInput()),
    cloudPiece,
    CommonGrid(whole, cloudPiece.Volume));
  OpticalDepthGrid total = own;
  for (std::size_t v = 0; v < total.Depths.size(); ++v)
  {
    total.Depths[v] += slab.Depths[v];
  }
  return DepthsFromOutside(total, own);
}

// How a case lights the cloud: the march, its transmittance and its multiple scattering.
struct Case
{
  std::string Name;
  LightTransmittance Transmittance = LightTransmittance::Volumes;
  MultipleScatteringModel MultipleScattering = MultipleScatteringModel::Octaves;
  // The nested march at 64 uniform segments of at least half a voxel. At its defaults (6 segments
  // growing 1.6 times) the whole field's own nested march misjudges the slab by far more than
  // the exchange errs (RMS 0.14 of the brightest against the piece with depths, whose march is
  // short and accurate): a comparison with the whole would measure that, not the exchange.
  bool FineNested = false;
  // The volume placed in the world by a vtkVolume: moved far from the origin, turned 30 degrees
  // about z and scaled 1.5 times (the grid's map from a piece's index points holds that too).
  bool Moved = false;
  // The end-to-end gates over the rows below the shared plane, relative to the brightest
  // radiance (without the multiple-scattering volume, whose gates are its own).
  double RmsGate = 3e-3;
  double MaxGate = 2e-2;
};

void PrintTo(const Case& c, std::ostream* out)
{
  *out << c.Name;
}

const Case Cases[] = {
  { "LightVolumes", LightTransmittance::Volumes, MultipleScatteringModel::Octaves },
  { "NestedMarch", LightTransmittance::Nested, MultipleScatteringModel::Octaves, true },
  { "ScatteringVolume", LightTransmittance::Volumes, MultipleScatteringModel::Volume },
  { "Moved",
    LightTransmittance::Volumes,
    MultipleScatteringModel::Octaves,
    false,
    true,
    2e-2,
    9e-2 },
};

// The scene: the field (or a piece of it) in the slab's medium, the sun above, seen from the side
// (along -y, z up) in a parallel view, so that an image row is a plane of constant z.
struct SideScene
{
  vtkNew<vtkCloudVolumeMapper> Mapper;
  GpuScene Scene{ Mapper, ImageSize, ImageSize };
  vtkNew<vtkCloudPieceExchange> Exchange; // the mapper's, as a rank's
  glm::dvec3 Centre{ 0.0 }; // where the field's centre is in the world
  double Size = 1.0;        // world units per model unit

  SideScene(const Case& c, vtkImageData* field)
  {
    this->Exchange->SetMapper(this->Mapper);
    this->Exchange->SetVolume(this->Scene.Volume);
    if (c.Moved)
    {
      this->Centre = glm::dvec3(1e3, -400.0, 300.0);
      this->Size = 1.5;
      this->Scene.Volume->SetPosition(this->Centre.x, this->Centre.y, this->Centre.z);
      this->Scene.Volume->SetOrientation(0.0, 0.0, 30.0);
      this->Scene.Volume->SetScale(this->Size);
    }
    LightingParameters lighting;
    lighting.Model = LightingModel::March;
    lighting.Transmittance = c.Transmittance;
    lighting.MultipleScattering = c.MultipleScattering;
    lighting.AmbientStrength = 0.1f;
    if (c.FineNested)
    {
      lighting.LightSteps = LightingLimits::MaxLightSteps;
      lighting.LightStepGrowth = 1.0f;
      lighting.LightStep = 0.025f;
    }
    this->Mapper->GetLightingProperty()->SetParameters(lighting);
    this->Mapper->SetSampleDistance(0.025);
    this->Mapper->JitterOff();
    this->Scene.Volume->SetProperty(LinearMedium(SigmaT, glm::vec3(0.9f)));
    this->Scene.SetInput(field);
    AddLight(this->Scene.Renderer, DirectionalLight(glm::dvec3(0.25, 0.15, 1.0), 2.0f));
    vtkCamera* camera = this->Scene.Renderer->GetActiveCamera();
    camera->SetFocalPoint(this->Centre.x, this->Centre.y, this->Centre.z);
    camera->SetPosition(this->Centre.x, this->Centre.y + 5.0, this->Centre.z);
    camera->SetViewUp(0.0, 0.0, 1.0);
    camera->ParallelProjectionOn();
    camera->SetParallelScale(1.1 * this->Size);
    camera->SetClippingRange(1.0, 10.0);
  }

  // The world z of image row y (row 0 at the bottom), and of a model z (the field's turn is
  // about z).
  double RowZ(int y) const
  {
    return this->Centre.z + 1.1 * this->Size * (2.0 * (y + 0.5) / ImageSize - 1.0);
  }
  double WorldZ(double modelZ) const { return this->Centre.z + this->Size * modelZ; }

  Image Render()
  {
    const Image image = this->Scene.RenderFloat();
    EXPECT_EQ(this->Mapper->GetLastError(), "");
    return image;
  }

  Image Reference(const OpticalDepthGrid& external,
    const WholeFieldScattering& scattering = WholeFieldScattering())
  {
    vtkNew<vtkCloudReferenceRenderer> reference;
    ConfigureReference(reference, this->Scene);
    reference->SetExternalOpticalDepths(external);
    reference->SetExternalScatteringVolume(scattering);
    reference->Update();
    return ImageOf(reference->GetOutput());
  }
};

// |a - b| over r, g, b of the pixels `mask` accepts where either shows cloud, relative to b's
// brightest there.
struct Relative
{
  size_t Pixels = 0;
  double Brightest = 0.0, Rms = 0.0, Max = 0.0;
};

Relative CompareRelative(const Image& a, const Image& b, const Mask& mask)
{
  const Mask cloud = OpacityAbove(a, b, 1e-4);
  const Mask both = [&](int x, int y) { return mask(x, y) && cloud(x, y); };
  const Difference d = Compare(a, b, 3, both);
  Relative r;
  r.Pixels = d.Count / 3;
  r.Brightest = Largest(b, 3, both);
  r.Rms = d.Rms / r.Brightest;
  r.Max = d.Max / r.Brightest;
  return r;
}

double MeanColor(const Image& image, const Mask& mask)
{
  double sum = 0.0;
  size_t count = 0;
  for (int y = 0; y < image.Height; ++y)
    for (int x = 0; x < image.Width; ++x)
      if (mask(x, y))
      {
        sum += image.At(x, y, 0) + image.At(x, y, 1) + image.At(x, y, 2);
        ++count;
      }
  return count ? sum / double(count) : 0.0;
}

bool OnLlvmpipe(GpuScene& scene)
{
  auto* window = vtkOpenGLRenderWindow::SafeDownCast(scene.Window);
  return std::string(window->ReportCapabilities()).find("llvmpipe") != std::string::npos;
}

class OpticalDepthExchange : public ::testing::TestWithParam<Case>
{
};
}

// The depths of two pieces that share a plane of points add up to the whole field's: each piece
// counts only the part of a ray inside its own box, from grid points inside it, in the other piece
// and outside both. A noisy cloud cut across x, a tilted sun and a point light beside the field.
TEST(OpticalDepthExchangeCpu, PiecesAddUpToTheWhole)
{
  const vtkSmartPointer<vtkImageData> whole = SparseCloud(Points);
  LightingParameters lighting;
  lighting.Model = LightingModel::March;
  vtkNew<vtkCloudVolumeMapper> mapper;
  mapper->GetLightingProperty()->SetParameters(lighting);
  mapper->SetLights(
    { DirectionalLight(glm::dvec3(0.6, 0.3, 0.75)), PointLight(glm::dvec3(2.6, 0.5, 1.0)) });
  vtkNew<vtkVolumeProperty> property;
  SetRampMedium(property, 1.0, 0.6);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  vtkNew<vtkCloudPieceExchange> exchange;
  exchange->SetMapper(mapper);
  exchange->SetVolume(volume);

  const auto depths = [&](vtkImageData* field)
  {
    OpticalDepthGrid grid = CommonGrid(whole);
    mapper->SetInputData(field);
    EXPECT_TRUE(exchange->ComputePieceOpticalDepths(nullptr, grid)) << exchange->GetLastError();
    EXPECT_EQ(grid.Lights, 2);
    EXPECT_EQ(grid.Depths.size(), 2 * grid.PointCount());
    return grid;
  };
  const OpticalDepthGrid all = depths(whole);
  const OpticalDepthGrid low = depths(Piece(whole, 0, 0, SplitPoint));
  const OpticalDepthGrid high = depths(Piece(whole, 0, SplitPoint, Points - 1));
  ASSERT_EQ(low.Depths.size(), all.Depths.size());
  ASSERT_EQ(high.Depths.size(), all.Depths.size());

  double largest = 0.0, largestLow = 0.0, largestHigh = 0.0, worst = 0.0;
  for (std::size_t v = 0; v < all.Depths.size(); ++v)
  {
    largest = std::max(largest, double(all.Depths[v]));
    largestLow = std::max(largestLow, double(low.Depths[v]));
    largestHigh = std::max(largestHigh, double(high.Depths[v]));
    worst = std::max(worst, std::abs(double(low.Depths[v]) + high.Depths[v] - all.Depths[v]));
  }
  std::cout << "largest depth " << largest << " (pieces " << largestLow << ", " << largestHigh
            << "); largest |low + high - whole| " << worst << " = " << worst / largest
            << " of it\n";
  // Both pieces hold cloud toward both lights: the sum is not one piece's alone.
  ASSERT_GT(largest, 2.0);
  ASSERT_GT(largestLow, 0.5);
  ASSERT_GT(largestHigh, 0.5);
  // Measured: 7.9e-4 of the largest depth, 0.006 (the trapezoid's half-voxel steps fall
  // differently in a piece and in the whole, across the noise's sharp features).
  EXPECT_LT(worst, 2e-3 * largest);
}

// The cloud piece lit through the slab piece's depths: the GPU equals the CPU reference given the
// same depths, the shadow is there (the image is much darker than without), and clearing the
// depths brings the unshadowed image back on the GPU too (what depends on them is recomputed).
TEST_P(OpticalDepthExchange, GpuMatchesCpuReference)
{
  const Case& c = GetParam();
  const vtkSmartPointer<vtkImageData> whole = SlabOverCloud();
  SideScene side(c, Piece(whole, 2, 0, SplitPoint));
  const OpticalDepthGrid external = ExchangedDepths(whole, side.Scene);

  side.Exchange->SetExternalOpticalDepths(external);
  const Image gpu = side.Render();
  const vtkTypeInt64 bytes = side.Mapper->GetGPUMemoryBytes();
  const Image cpu = side.Reference(external);
  side.Exchange->SetExternalOpticalDepths(OpticalDepthGrid());
  const Image gpuAlone = side.Render();
  const Image cpuAlone = side.Reference(OpticalDepthGrid());
  Dump(gpu, "exchange-" + c.Name + "-gpu");
  Dump(cpu, "exchange-" + c.Name + "-cpu");
  Dump(gpuAlone, "exchange-" + c.Name + "-gpu-alone");

  // The texture of the depths counts in the GPU memory: 11^3 floats, one light.
  EXPECT_GE(bytes - side.Mapper->GetGPUMemoryBytes(), 4 * vtkTypeInt64(external.PointCount()));

  const Mask all = [](int, int) { return true; };
  const Relative shadowed = CompareRelative(gpu, cpu, all);
  const Relative alone = CompareRelative(gpuAlone, cpuAlone, all);
  const double darkening = MeanColor(cpu, all) / MeanColor(cpuAlone, all);
  std::cout << c.Name << ": " << shadowed.Pixels
            << " cloud pixels; with the depths, GPU vs CPU RMS " << shadowed.Rms << ", max "
            << shadowed.Max << " of the brightest; without them RMS " << alone.Rms << ", max "
            << alone.Max << "; mean radiance with / without " << darkening << "\n";
  ASSERT_GT(shadowed.Pixels, size_t(ImageSize * ImageSize / 10));
  // The slab's optical depth, about 2.7 along the sun: the cloud is in its shadow. Measured: the
  // mean radiance falls to 0.51 of the unshadowed (the octaves, whose extinction falls off, carry
  // light through) and to 0.21 with the multiple-scattering volume.
  EXPECT_LT(darkening, 0.7);
  EXPECT_LT(MeanColor(gpu, all), 0.7 * MeanColor(gpuAlone, all));
  // Measured on llvmpipe: RMS up to 3.4e-7 and max up to 1.3e-6 of the brightest, with the
  // depths and without; the gates of render.GpuMatchesCpuReference (ten times looser elsewhere).
  const bool llvmpipe = OnLlvmpipe(side.Scene);
  const double rmsGate = llvmpipe ? 1e-5 : 1e-4, maxGate = llvmpipe ? 1e-4 : 1e-3;
  for (const Relative& d : { shadowed, alone })
  {
    EXPECT_LT(d.Rms, rmsGate);
    EXPECT_LT(d.Max, maxGate);
  }
}

// The property the distributed renderer relies on: the cloud piece with the slab piece's depths
// is the whole field, over the rows below the shared plane (whose rays, in this side view, cross
// the cloud piece alone). Without the depths the two differ by the slab's shadow.
TEST_P(OpticalDepthExchange, PieceWithDepthsMatchesWholeField)
{
  const Case& c = GetParam();
  const vtkSmartPointer<vtkImageData> whole = SlabOverCloud();
  SideScene wholeScene(c, whole);
  const Image all = wholeScene.Render();

  SideScene pieceScene(c, Piece(whole, 2, 0, SplitPoint));
  const OpticalDepthGrid external = ExchangedDepths(whole, pieceScene.Scene);
  const Image alone = pieceScene.Render();
  pieceScene.Exchange->SetExternalOpticalDepths(external);
  const Image piece = pieceScene.Render();
  Dump(all, "exchange-" + c.Name + "-whole");
  Dump(piece, "exchange-" + c.Name + "-piece");

  // Rows a voxel below the shared plane and lower; the slab's rows show in the whole field only.
  const double voxel = 2.0 / (Points - 1);
  const SideScene& at = pieceScene;
  const Mask below = [&](int, int y) { return at.RowZ(y) < at.WorldZ(SplitZ() - voxel); };
  const Mask slabRows = [&](int, int y)
  { return std::abs(at.RowZ(y) - at.WorldZ(0.55)) < 0.1 * at.Size; };
  ASSERT_GT(MeanColor(all, slabRows), 0.0) << "the side view must show the slab above the cloud";
  ASSERT_EQ(MeanColor(piece, slabRows), 0.0) << "the cloud piece must not reach the slab's rows";

  const Relative with = CompareRelative(piece, all, below);
  const Relative without = CompareRelative(alone, all, below);
  std::cout << c.Name << ": " << with.Pixels << " cloud pixels below the shared plane; piece with "
            << "depths vs whole: RMS " << with.Rms << ", max " << with.Max << " of the brightest ("
            << 255.0 * with.Rms * with.Brightest
            << " RMS 8-bit levels of the linear radiance); without depths: RMS " << without.Rms
            << ", max " << without.Max << "\n";
  // By distance below the shared plane: where the pieces' multiple scattering parts, if at the
  // face alone or everywhere.
  for (double band : { 0.15, 0.3, 0.45, 0.6 })
  {
    const Mask rows = [&](int, int y)
    {
      const double depth = (at.WorldZ(SplitZ()) - at.RowZ(y)) / at.Size;
      return depth >= band - 0.15 && depth < band;
    };
    const Relative d = CompareRelative(piece, all, rows);
    std::cout << "  " << band - 0.15 << " to " << band << " below the plane: " << d.Pixels
              << " pixels, RMS " << d.Rms * d.Brightest / with.Brightest << ", mean piece/whole "
              << MeanColor(piece, rows) / MeanColor(all, rows) << "\n";
  }
  ASSERT_GT(with.Pixels, size_t(ImageSize * ImageSize / 10));
  EXPECT_GT(without.Rms, 0.3) << "the slab must shadow the cloud";
  if (c.MultipleScattering != MultipleScatteringModel::Volume)
  {
    // Measured on llvmpipe: RMS 1.1e-3 (light volumes) and 0.9e-3 (nested), max 7.1e-3 of the
    // brightest: the coarse grid's interpolation of the slab's depth against the whole field's
    // light volumes or march (the GPU-vs-CPU differences are 1000 times smaller). Moved: RMS
    // 6.0e-3, max 2.9e-2, growing away from the plane: the world grid over the turned field's
    // box is coarser (0.27 model units, not 0.2), and the rays from the cloud's lower side pass
    // near the slab's soft edge, where its depth varies within a grid cell. At half the field's
    // resolution (21^3) instead of a quarter the four cases measure RMS 0.8e-3, 0.5e-3, 1.0e-3.
    EXPECT_LT(with.Rms, c.RmsGate);
    EXPECT_LT(with.Max, c.MaxGate);
    return;
  }
  // With a multiple-scattering volume of its own each piece solves its own diffusion: the light
  // the slab scatters no longer diffuses down to the cloud (the exchange carries optical depth,
  // not diffuse light), so the piece is darker than the whole, at every distance from the shared
  // plane (measured: 0.48 of the whole's mean radiance within 0.15 below the plane, 0.69 at 0.45
  // to 0.6; RMS 0.21, max 0.46 of the brightest over all). Why the pieces share one volume of the
  // whole field (ScatteringAcrossPieces below); gated at what it is, and still far closer than no
  // exchange (RMS 1.19).
  EXPECT_LT(with.Rms, 0.3);
  EXPECT_LT(with.Max, 0.6);
  EXPECT_LT(with.Rms, 0.25 * without.Rms);
}

// Depths the mapper cannot use are refused in words, not drawn: a grid for other lights than the
// mapper's, a grid without points to compute.
TEST(OpticalDepthExchangeRefusals, OtherLightsAndEmptyGrids)
{
  const vtkSmartPointer<vtkImageData> whole = SlabOverCloud();
  SideScene side(Cases[0], Piece(whole, 2, 0, SplitPoint));
  OpticalDepthGrid grid = CommonGrid(whole);
  grid.Lights = 2;
  grid.Depths.assign(2 * grid.PointCount(), 1.0f);
  side.Exchange->SetExternalOpticalDepths(grid);
  side.Scene.Window->Render();
  EXPECT_NE(side.Mapper->GetLastError().find("lit by 1"), std::string::npos)
    << side.Mapper->GetLastError();

  OpticalDepthGrid none = CommonGrid(whole);
  none.Size[1] = 0;
  EXPECT_FALSE(side.Exchange->ComputePieceOpticalDepths(side.Scene.Renderer, none));
  EXPECT_NE(side.Exchange->GetLastError().find("at least 1 point"), std::string::npos)
    << side.Exchange->GetLastError();
  EXPECT_TRUE(none.Depths.empty());

  // Summed scattering inputs of another length than the whole field's are refused in words, and
  // the mapper goes on with its own volume.
  const int* extent = whole->GetExtent();
  const std::size_t values = vtkCloudPieceExchange::GetScatteringInputCount(extent);
  EXPECT_EQ(values, ScatteringInputValues(glm::ivec3(Points)));
  EXPECT_FALSE(side.Exchange->SolveScatteringVolume(std::vector<float>(values - 1), extent));
  EXPECT_NE(side.Exchange->GetLastError().find("summed inputs hold"), std::string::npos)
    << side.Exchange->GetLastError();
  EXPECT_FALSE(side.Exchange->HasScatteringVolume());
  const int empty[6] = { 0, -1, 0, 0, 0, 0 };
  EXPECT_EQ(vtkCloudPieceExchange::GetScatteringInputCount(empty), 0u);

  // Without a mapper the exchange says so.
  vtkNew<vtkCloudPieceExchange> unset;
  EXPECT_FALSE(unset->ComputePieceOpticalDepths(nullptr, none));
  EXPECT_NE(unset->GetLastError().find("needs the mapper"), std::string::npos)
    << unset->GetLastError();
}

// ---- The multiple-scattering volume over the whole field ----

namespace
{
// The whole field's geometry as the ranks of `like`'s pieces know it: a piece's with the whole's
// extent.
VolumeGeometry WholeOf(vtkImageData* whole, vtkImageData* piece, GpuScene& like)
{
  return WholeFieldGeometry(piece, like.Volume->GetMatrix(), whole->GetExtent());
}

// The whole field's multiple-scattering inputs as the ranks of `pieces` make them: each piece's
// owned cells, lit with the other pieces' optical depths (the exchange), summed (what an
// MPI_Allreduce of the arrays ComputePieceScatteringInputs gives makes). `counts` gets the cells
// each piece owns with medium in them.
std::vector<float> SummedInputs(vtkImageData* whole,
  const std::vector<vtkSmartPointer<vtkImageData>>& pieces,
  GpuScene& like,
  std::vector<std::size_t>* counts = nullptr)
{
  const OpticalDepthGrid grid = CommonGrid(whole, like.Volume);
  std::vector<OpticalDepthGrid> own;
  OpticalDepthGrid total = grid;
  for (vtkImageData* piece : pieces)
  {
    own.push_back(DepthsOf(piece, like, grid));
    total.Lights = own.back().Lights;
    total.Depths.resize(own.back().Depths.size(), 0.0f);
    for (std::size_t v = 0; v < total.Depths.size(); ++v)
      total.Depths[v] += own.back().Depths[v];
  }
  const VolumeGeometry geometry = WholeOf(whole, pieces.front(), like);
  std::vector<float> sum;
  for (std::size_t i = 0; i < pieces.size(); ++i)
  {
    RankMapper rank(pieces[i], like);
    rank.Exchange->SetExternalOpticalDepths(DepthsFromOutside(total, own[i]));
    std::vector<float> values;
    EXPECT_TRUE(
      rank.Exchange->ComputePieceScatteringInputs(like.Renderer, whole->GetExtent(), values))
      << rank.Exchange->GetLastError();
    EXPECT_EQ(values.size(), vtkCloudPieceExchange::GetScatteringInputCount(whole->GetExtent()));
    sum.resize(values.size(), 0.0f);
    for (std::size_t v = 0; v < values.size(); ++v)
      sum[v] += values[v];
    if (counts)
    {
      ScatteringInputs inputs;
      EXPECT_TRUE(UnpackScatteringInputs(values, geometry, inputs));
      std::size_t cells = 0;
      for (const ScatteringGrid& level : inputs)
        for (const glm::vec4& medium : level.Medium)
          cells += medium.w > 0.0f ? 1 : 0;
      counts->push_back(cells);
    }
  }
  return sum;
}

// The summed inputs as the solve takes them: every grid's cells.
ScatteringInputs Unpacked(const std::vector<float>& sum, const VolumeGeometry& whole)
{
  ScatteringInputs inputs;
  EXPECT_TRUE(UnpackScatteringInputs(sum, whole, inputs));
  return inputs;
}

std::vector<vtkSmartPointer<vtkImageData>> TwoPieces(vtkImageData* whole, int split = SplitPoint)
{
  return { Piece(whole, 2, 0, split), Piece(whole, 2, split, Points - 1) };
}

// One input's largest |a - b| and RMS over all grids' cells and channels, and its largest |b|.
struct InputDifference
{
  double Largest = 0.0, Worst = 0.0, Rms = 0.0;
};

InputDifference CompareInputs(const ScatteringInputs& a,
  const ScatteringInputs& b,
  const std::function<glm::vec3(const ScatteringGrid&, std::size_t)>& value)
{
  InputDifference d;
  std::size_t count = 0;
  for (std::size_t level = 0; level < b.size(); ++level)
    for (std::size_t n = 0; n < b[level].Medium.size(); ++n)
    {
      const glm::vec3 x = value(a[level], n), y = value(b[level], n);
      for (int channel = 0; channel < 3; ++channel)
      {
        const double e = std::abs(double(x[channel]) - y[channel]);
        d.Largest = std::max(d.Largest, double(std::abs(y[channel])));
        d.Worst = std::max(d.Worst, e);
        d.Rms += e * e;
        ++count;
      }
    }
  d.Rms = std::sqrt(d.Rms / double(std::max<std::size_t>(count, 1)));
  return d;
}
}

// The inputs the pieces own, summed, are the whole field's: medium, source, beam direction and the
// coarsest grid's first guess, cell by cell on every grid. The whole field computed as a piece of
// itself is what its own volume starts from.
TEST(ScatteringAcrossPieces, OwnedInputsSumToTheWholeField)
{
  const vtkSmartPointer<vtkImageData> whole = SlabOverCloud();
  SideScene scene(Cases[2], whole);
  std::vector<std::size_t> counts;
  // Cut through the ball at z = 13, where the coarsest grid (4^3) has cells centred on the plane
  // the pieces share: the rule that gives such a cell one owner is in the sum.
  const int split = 13;
  const VolumeGeometry geometry = WholeOf(whole, whole, scene.Scene);
  const ScatteringInputs summed =
    Unpacked(SummedInputs(whole, TwoPieces(whole, split), scene.Scene, &counts), geometry);
  const ScatteringInputs all = Unpacked(SummedInputs(whole, { whole }, scene.Scene), geometry);
  ASSERT_EQ(summed.size(), all.size());
  ASSERT_EQ(counts.size(), 2u);
  // Each piece owns cells with medium: the sum is not one piece's.
  EXPECT_GT(counts[0], 10u);
  EXPECT_GT(counts[1], 10u);

  using Grid = ScatteringGrid;
  const InputDifference albedo =
    CompareInputs(summed, all, [](const Grid& g, std::size_t n) { return glm::vec3(g.Medium[n]); });
  const InputDifference sigma = CompareInputs(
    summed, all, [](const Grid& g, std::size_t n) { return glm::vec3(g.Medium[n].w); });
  const InputDifference source =
    CompareInputs(summed, all, [](const Grid& g, std::size_t n) { return glm::vec3(g.Source[n]); });
  // The beams' direction weighs only as the first moment of the source (a cell whose beams
  // deposit almost nothing may point anywhere).
  const InputDifference moment = CompareInputs(summed,
    all,
    [](const Grid& g, std::size_t n)
    { return glm::vec3(g.Direction[n]) * (g.Source[n].x + g.Source[n].y + g.Source[n].z); });
  const InputDifference start = CompareInputs(summed,
    all,
    [](const Grid& g, std::size_t n)
    { return n < g.Fluence.size() ? glm::vec3(g.Fluence[n]) : glm::vec3(0.0f); });
  for (const auto& named : { std::make_pair("albedo", albedo),
         std::make_pair("sigma_t", sigma),
         std::make_pair("source", source),
         std::make_pair("source moment", moment),
         std::make_pair("first guess", start) })
  {
    const InputDifference& d = named.second;
    std::cout << named.first << ": largest " << d.Largest << "; |pieces - whole| max "
              << d.Worst / d.Largest << ", RMS " << d.Rms / d.Largest << " of it\n";
  }
  ASSERT_GT(sigma.Largest, 0.1);
  ASSERT_GT(source.Largest, 0.0);
  // The medium: the same texels, read at the same points, but for the samples of the cells next
  // to the shared plane that fall beyond their piece's face, which read the face (measured:
  // extinction at most 0.93% of the largest, RMS 0.046%; albedo, whose density ramp is flat, and
  // every cell away from the plane to float rounding, 3e-7).
  EXPECT_LT(albedo.Worst, 1e-5 * albedo.Largest);
  EXPECT_LT(sigma.Worst, 2e-2 * sigma.Largest);
  EXPECT_LT(sigma.Rms, 1e-3 * sigma.Largest);
  // The sources: the beams' optical depth from the exchanged grid (a quarter of the field's
  // resolution, trilinear) where the whole field reads its own light volumes, and the cells
  // whose beams enter across the shared plane, whose entry point the piece clamps to its face.
  for (const InputDifference* d : { &source, &moment, &start })
  {
    EXPECT_LT(d->Worst, SourceMaxGate * d->Largest);
    EXPECT_LT(d->Rms, SourceRmsGate * d->Largest);
  }
}

// A piece whose march reads the volume solved over the whole field (from the pieces' summed
// inputs) is the whole field over the rows below the shared plane, as the optical depths alone
// make it for single scattering; the piece's own volume (solved over the piece alone) is not. The
// GPU image equals the CPU reference given the same volume.
TEST(ScatteringAcrossPieces, PieceReadsTheWholeFieldVolume)
{
  const Case& c = Cases[2];
  const vtkSmartPointer<vtkImageData> whole = SlabOverCloud();
  SideScene wholeScene(c, whole);
  const Image all = wholeScene.Render();

  const std::vector<vtkSmartPointer<vtkImageData>> pieces = TwoPieces(whole);
  SideScene pieceScene(c, pieces.front());
  const OpticalDepthGrid external = ExchangedDepths(whole, pieceScene.Scene);
  const std::vector<float> sum = SummedInputs(whole, pieces, pieceScene.Scene);
  // What the exchange solves, for the CPU reference.
  const VolumeGeometry geometry = WholeOf(whole, pieces.front(), pieceScene.Scene);
  const WholeFieldScattering volume = SolveWholeFieldScattering(
    pieceScene.Mapper->GetLightingProperty()->GetParameters(), geometry, Unpacked(sum, geometry));
  pieceScene.Exchange->SetExternalOpticalDepths(external);
  const Image ownVolume = pieceScene.Render();
  const vtkTypeInt64 ownBytes = pieceScene.Mapper->GetScatteringVolumeBytes();
  ASSERT_TRUE(pieceScene.Exchange->SolveScatteringVolume(sum, whole->GetExtent()))
    << pieceScene.Exchange->GetLastError();
  EXPECT_TRUE(pieceScene.Exchange->HasScatteringVolume());
  const Image piece = pieceScene.Render();
  const vtkTypeInt64 bytes = pieceScene.Mapper->GetGPUMemoryBytes();
  const Image cpu = pieceScene.Reference(external, volume);
  Dump(piece, "scattering-pieces-piece");
  Dump(cpu, "scattering-pieces-cpu");
  Dump(ownVolume, "scattering-pieces-own");
  Dump(all, "scattering-pieces-whole");

  // The mapper's own volume is released; the given one's two RGBA32F textures count.
  EXPECT_GT(ownBytes, 0);
  EXPECT_EQ(pieceScene.Mapper->GetScatteringVolumeBytes(), 0);
  const glm::ivec3 size = volume.Volume.Size;
  EXPECT_EQ(size, ScatteringVolumeSize(glm::ivec3(Points)));
  EXPECT_GE(bytes, 32 * vtkTypeInt64(size.x) * size.y * size.z);

  const double voxel = 2.0 / (Points - 1);
  const SideScene& at = pieceScene;
  const Mask below = [&](int, int y) { return at.RowZ(y) < at.WorldZ(SplitZ() - voxel); };
  const Relative with = CompareRelative(piece, all, below);
  const Relative own = CompareRelative(ownVolume, all, below);
  const Relative twin = CompareRelative(piece, cpu, [](int, int) { return true; });
  std::cout << with.Pixels << " cloud pixels below the shared plane; piece reading the whole "
            << "field's volume vs the whole: RMS " << with.Rms << ", max " << with.Max
            << " of the brightest (" << 255.0 * with.Rms * with.Brightest
            << " RMS 8-bit levels of the linear radiance); with its own volume: RMS " << own.Rms
            << ", max " << own.Max << "; GPU vs CPU RMS " << twin.Rms << ", max " << twin.Max
            << "\n";
  ASSERT_GT(with.Pixels, size_t(ImageSize * ImageSize / 10));
  EXPECT_GT(own.Rms, 0.1) << "a piece's own volume must miss the slab's diffuse light";
  EXPECT_LT(with.Rms, WholeVolumeRmsGate);
  EXPECT_LT(with.Max, WholeVolumeMaxGate);
  const bool llvmpipe = OnLlvmpipe(pieceScene.Scene);
  EXPECT_LT(twin.Rms, llvmpipe ? 1e-5 : 1e-4);
  EXPECT_LT(twin.Max, llvmpipe ? 1e-4 : 1e-3);

  // The whole field reading a volume solved from its own inputs, as a piece of itself, draws what
  // it draws with the volume it computes on the GPU: the world map is the identity's.
  ASSERT_TRUE(wholeScene.Exchange->SolveScatteringVolume(
    SummedInputs(whole, { whole }, wholeScene.Scene), whole->GetExtent()))
    << wholeScene.Exchange->GetLastError();
  const Relative same = CompareRelative(wholeScene.Render(), all, [](int, int) { return true; });
  std::cout << "the whole field reading its own inputs' solve vs its GPU volume: RMS " << same.Rms
            << ", max " << same.Max << "\n";
  EXPECT_LT(same.Rms, llvmpipe ? 1e-5 : 1e-4);
  EXPECT_LT(same.Max, llvmpipe ? 1e-4 : 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Cases,
  OpticalDepthExchange,
  ::testing::ValuesIn(Cases),
  [](const ::testing::TestParamInfo<Case>& param) { return param.param.Name; });
