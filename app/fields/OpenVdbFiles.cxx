// OpenVDB: the reader of .vdb files and the writer of `cloudvis generate -o field.vdb`. This is
// the one translation unit that includes OpenVDB's headers (they are heavy: keep them here).
//
// Reading: one float grid (field.array names it; by default "density", else the first float grid)
// (a level set first converted to a fog volume, below) is copied onto a dense vtkImageData covering
// its active bounding box at its voxel size: VDB index (i, j, k) is image point (i, j, k), so no
// value is interpolated, and inactive voxels inside the box take the grid's background. The grid's
// transform becomes the image's geometry: a linear map (scale, translation, rotation, or any affine
// map whose axes are perpendicular) gives the origin, spacing and direction; a frustum or a sheared
// map is refused, since image data cannot represent it. The size (field.max_voxels, memory) is
// checked against the tree's active bounding box before the dense copy is allocated. OpenVDB parses
// the file in the isolated child first (IsolatedRead.h), through a stream that throws at any short
// read; in the child the copies run without TBB threads, which a forked child does not have.
//
// Writing: a FloatGrid "density" of class fog volume, background 0, built from the field with
// tools::copyFromDense, which stores no voxel equal to the background: empty space costs
// nothing. Its transform maps VDB index (i, j, k) to the field's point (i, j, k) (origin, spacing,
// direction); the file's metadata names the generator and holds the scene.
#include "FieldFormatReaders.h"

#include "AtomicFile.h"
#include "Errors.h"
#include "InputFiles.h"
#include "IsolatedRead.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>
#include <vtkPointData.h>

#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Count.h>
#include <openvdb/tools/Dense.h>
#include <openvdb/tools/LevelSetUtil.h>

#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

namespace cloudvis
{
namespace
{

// An archive written to a stream of the caller's, seekable, as io::File writes its file
// (Archive::write is protected; io::Stream writes a non-seekable archive, without the grid
// offsets that io::File needs to read it back).
class SeekableArchive : public openvdb::io::Archive
{
public:
  void WriteTo(std::ostream& out,
    const openvdb::GridCPtrVec& grids,
    const openvdb::MetaMap& metadata) const
  {
    this->write(out, grids, /*seekable=*/true, metadata);
  }
};

std::string BoxText(const openvdb::CoordBBox& box)
{
  std::ostringstream text;
  text << "[" << box.min().x() << ", " << box.min().y() << ", " << box.min().z() << "] .. ["
       << box.max().x() << ", " << box.max().y() << ", " << box.max().z() << "]";
  return text.str();
}

std::array<double, 3> BoxDimensions(const openvdb::CoordBBox& box)
{
  // In double: a hostile box can span the whole int range.
  return { { double(box.max().x()) - box.min().x() + 1.0,
    double(box.max().y()) - box.min().y() + 1.0,
    double(box.max().z()) - box.min().z() + 1.0 } };
}

// The grid field.array names, or "density", or the first float grid; the others for the report.
openvdb::GridBase::Ptr ChooseGrid(const std::string& path,
  const openvdb::GridPtrVec& grids,
  const std::string& wanted,
  std::string& others)
{
  std::string listing;
  for (const openvdb::GridBase::Ptr& grid : grids)
  {
    listing +=
      (listing.empty() ? "" : ", ") + ("\"" + grid->getName() + "\" (" + grid->valueType() + ")");
  }
  openvdb::GridBase::Ptr chosen;
  const auto named = [&grids](const std::string& name) -> openvdb::GridBase::Ptr
  {
    for (const openvdb::GridBase::Ptr& grid : grids)
    {
      if (grid->getName() == name)
      {
        return grid;
      }
    }
    return nullptr;
  };
  if (!wanted.empty())
  {
    chosen = named(wanted);
    if (!chosen)
    {
      Fail(path,
        "no grid named \"" + wanted +
          "\" (field.array); the file's grids: " + (listing.empty() ? "none" : listing));
    }
  }
  else
  {
    chosen = named("density");
    if (!chosen || !chosen->isType<openvdb::FloatGrid>())
    {
      chosen = nullptr;
      for (const openvdb::GridBase::Ptr& grid : grids)
      {
        if (grid->isType<openvdb::FloatGrid>())
        {
          chosen = grid;
          break;
        }
      }
    }
    if (!chosen)
    {
      Fail(path,
        "no float grid to read as a density; the file's grids: " +
          (listing.empty() ? "none" : listing));
    }
  }
  if (!chosen->isType<openvdb::FloatGrid>())
  {
    Fail(path,
      "grid \"" + chosen->getName() + "\" holds " + chosen->valueType() +
        " values; a density field is a float grid (the file's grids: " + listing + ")");
  }
  for (const openvdb::GridBase::Ptr& grid : grids)
  {
    if (grid != chosen)
    {
      others +=
        (others.empty() ? "" : ", ") + ("\"" + grid->getName() + "\" (" + grid->valueType() + ")");
    }
  }
  return chosen;
}

// The image geometry of a grid's transform: the world position of index (0, 0, 0) and the world
// step along each index axis. Refuses maps that are not linear.
void SetGeometry(const std::string& path,
  const openvdb::math::Transform& transform,
  vtkImageData* image)
{
  if (!transform.isLinear())
  {
    Fail(path,
      "the grid's transform is a " + transform.mapType() +
        ", which is not linear (a frustum): image data cannot represent it");
  }
  // OpenVDB's matrices act on row vectors: row r is the world step along index axis r, row 3 the
  // translation.
  const openvdb::math::Mat4d matrix = transform.baseMap()->getAffineMap()->getMat4();
  std::array<std::array<double, 3>, 3> axes{};
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      axes[r][c] = matrix(r, c);
    }
  }
  image->SetOrigin(matrix(3, 0), matrix(3, 1), matrix(3, 2));
  SetAxes(path, image, axes);
}

std::string Translated(const std::exception& e)
{
  std::string text = e.what();
  return text.empty() ? "OpenVDB could not read it" : text;
}

// The physical units a grid's metadata declares (DeclareNamedUnits; docs/data.md): what
// `grid["quantity"] = "lwc"` writes in OpenVDB's Python module, insertMeta in C++. Strings are
// StringMetadata; numbers float, double or integer metadata.
void DeclareUnits(const std::string& path, const openvdb::GridBase& grid, FieldReport& report)
{
  const auto lookup = [&grid](const std::string& name) -> std::optional<MetadataEntry>
  {
    const openvdb::Metadata::ConstPtr meta = grid[name];
    if (!meta)
    {
      return std::nullopt;
    }
    MetadataEntry entry;
    entry.TypeName = meta->typeName();
    if (const auto* s = dynamic_cast<const openvdb::StringMetadata*>(meta.get()))
    {
      entry.Text = s->value();
    }
    else if (const auto* f = dynamic_cast<const openvdb::FloatMetadata*>(meta.get()))
    {
      entry.Number = f->value();
    }
    else if (const auto* d = dynamic_cast<const openvdb::DoubleMetadata*>(meta.get()))
    {
      entry.Number = d->value();
    }
    else if (const auto* i = dynamic_cast<const openvdb::Int32Metadata*>(meta.get()))
    {
      entry.Number = i->value();
    }
    else if (const auto* l = dynamic_cast<const openvdb::Int64Metadata*>(meta.get()))
    {
      entry.Number = double(l->value());
    }
    return entry;
  };
  DeclareNamedUnits(
    path, "grid \"" + grid.getName() + "\": metadata", "grid metadata", lookup, report);
}

} // namespace

FieldFileContents ReadOpenVdbFile(const std::string& path, const FieldReadOptions& options)
{
  std::uint64_t fileBytes = 0;
  {
    const RegularInputFile file(path, "field");
    fileBytes = file.Size();
    const std::string magic = file.ReadAt(0, 4);
    // OpenVDB's magic number, 0x56444220 ("VDB " in little-endian order).
    if (magic != std::string("\x20\x42\x44\x56", 4))
    {
      Fail(path, "not an OpenVDB file (it does not start with OpenVDB's magic number)");
    }
  }
  const auto read = [&]() -> FieldFileContents
  {
    openvdb::initialize();
    const bool threaded = !InIsolatedRead();
    try
    {
      // OpenVDB's stream reader on a stream that throws at any short read: its file reader goes
      // on past the end of a truncated file with whatever its buffers held (found by the tests:
      // each read of the same truncated file gave another result). The stream reader reads
      // every grid; the one chosen is kept.
      std::ifstream in(path, std::ios::binary);
      in.exceptions(std::ios::failbit | std::ios::badbit | std::ios::eofbit);
      openvdb::io::Stream stream(in, /*delayLoad=*/false);
      const openvdb::GridPtrVecPtr grids = stream.getGrids();
      std::string others;
      const openvdb::FloatGrid::Ptr grid =
        openvdb::gridPtrCast<openvdb::FloatGrid>(ChooseGrid(path, *grids, options.Array, others));
      // A level set holds signed distances to a surface (negative inside, the background
      // outside), not densities: read as one it draws a solid block. It is converted to the fog
      // volume Houdini and Blender make of it: OpenVDB's sdfToFogVolume, the narrow band's
      // interior half a linear ramp from 0 at the surface to 1, the interior 1, the outside 0
      // (inactive). The ramp's depth is the background, clamped by sdfToFogVolume to the deepest
      // distance the grid stores (a thin interior band).
      const bool levelSet = grid->getGridClass() == openvdb::GRID_LEVEL_SET;
      const float halfBand = grid->background();
      if (levelSet)
      {
        std::optional<oneapi::tbb::global_control> serial;
        if (!threaded)
        {
          serial.emplace(oneapi::tbb::global_control::max_allowed_parallelism, 1);
        }
        openvdb::tools::sdfToFogVolume(*grid, halfBand);
      }
      openvdb::CoordBBox box;
      if (!grid->tree().evalActiveVoxelBoundingBox(box))
      {
        Fail(path, "grid \"" + grid->getName() + "\" has no active voxels: nothing to read");
      }
      const std::array<double, 3> dimensions = BoxDimensions(box);
      CheckFieldSize(path, dimensions, 4.0, options.MaximumVoxels);

      auto image = vtkSmartPointer<vtkImageData>::New();
      image->SetExtent(
        box.min().x(), box.max().x(), box.min().y(), box.max().y(), box.min().z(), box.max().z());
      SetGeometry(path, grid->transform(), image);
      vtkNew<vtkFloatArray> density;
      density->SetName(grid->getName().c_str());
      density->SetNumberOfTuples(image->GetNumberOfPoints());
      // VTK's order is x fastest: OpenVDB's LayoutXYZ.
      openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(box, density->GetPointer(0));
      openvdb::tools::copyToDense(*grid, dense, /*serial=*/!threaded);
      image->GetPointData()->SetScalars(density);

      FieldFileContents contents{ image, grid->getName(), {} };
      const openvdb::Index64 active = openvdb::tools::countActiveVoxels(grid->tree(), threaded);
      contents.Report.Add("grid",
        "\"" + grid->getName() + "\" (float, " +
          (levelSet ? std::string("level set")
                    : openvdb::GridBase::gridClassToString(grid->getGridClass())) +
          ", " + std::to_string(active) + " active voxels" + (levelSet ? " once converted" : "") +
          ", background " + Number(grid->background()) + ")" +
          (others.empty() ? "" : "; other grids (field.array): " + others));
      if (levelSet)
      {
        contents.Report.Add("converted",
          "level set converted to a fog volume (OpenVDB's sdfToFogVolume): density 0 outside the "
          "surface, rising linearly to 1 over the inner half of the narrow band (at most " +
            Number(halfBand) +
            " world units deep, the grid's background; less where the stored interior is "
            "thinner), 1 inside");
      }
      DeclareUnits(path, *grid, contents.Report);
      const std::string creator = grid->getCreator();
      if (!creator.empty())
      {
        contents.Report.Add("creator", creator);
      }
      const openvdb::Vec3d voxel = grid->voxelSize();
      contents.Report.Add("transform",
        grid->transform().mapType() + ", voxel size " + Number(voxel.x()) + " x " +
          Number(voxel.y()) + " x " + Number(voxel.z()));
      contents.Report.Add("resampled",
        "no: the active bounding box " + BoxText(box) +
          " copied voxel for voxel onto a dense grid (inactive voxels take the background)");
      return contents;
    }
    catch (const InputError&)
    {
      throw;
    }
    catch (const std::bad_alloc&)
    {
      throw;
    }
    catch (const std::ios_base::failure&)
    {
      Fail(path, "cannot read OpenVDB: the file ends before its grids do: it is truncated");
    }
    catch (const std::exception& e)
    {
      Fail(path, "cannot read OpenVDB: " + Translated(e));
    }
  };
  return ReadInIsolation(path, fileBytes, "OpenVDB's reader", read);
}

void WriteOpenVdbFile(vtkImageData* field, const std::string& path, const FieldMetadata& metadata)
{
  openvdb::initialize();
  vtkFloatArray* values = vtkFloatArray::SafeDownCast(field->GetPointData()->GetScalars());
  if (!values || values->GetNumberOfComponents() != 1)
  {
    Fail(path, "only a float density field can be written as OpenVDB");
  }
  int extent[6];
  field->GetExtent(extent);
  const openvdb::CoordBBox box(openvdb::Coord(extent[0], extent[2], extent[4]),
    openvdb::Coord(extent[1], extent[3], extent[5]));
  // Index (i, j, k) to the field's point (i, j, k): row r the world step along axis r (direction
  // column r times spacing r), row 3 the origin.
  const double* origin = field->GetOrigin();
  const double* spacing = field->GetSpacing();
  vtkMatrix3x3* direction = field->GetDirectionMatrix();
  openvdb::math::Mat4d matrix = openvdb::math::Mat4d::identity();
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      matrix(r, c) = direction->GetElement(c, r) * spacing[r];
    }
    matrix(3, r) = origin[r];
  }
  const auto transform = std::make_shared<openvdb::math::Transform>(
    openvdb::math::simplify(std::make_shared<openvdb::math::AffineMap>(matrix)));

  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setTransform(transform);
  grid->setCreator(std::string("cloudvis ") + CLOUDVIS_VERSION);
  // Only voxels that differ from the background (0) are stored: empty space costs nothing.
  openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ> dense(box, values->GetPointer(0));
  openvdb::tools::copyFromDense(dense, *grid, /*tolerance=*/0.0f);

  openvdb::MetaMap fileMetadata;
  fileMetadata.insertMeta("creator", openvdb::StringMetadata(grid->getCreator()));
  if (!metadata.Scene.empty())
  {
    fileMetadata.insertMeta("cloudvis_scene", openvdb::StringMetadata(metadata.Scene));
  }
  // Onto the checked stream of the shared atomic path (AtomicFile.h), not by name: io::File
  // writes through its own std::ofstream and never looks at it again, so on a full disk it
  // returned as if the file were whole. SeekableArchive is exactly what io::File::write does
  // with its stream (a seekable archive: grid offsets filled in, as readers of files expect).
  WriteStreamAtomically(path,
    "the field as OpenVDB",
    [&](std::ostream& out)
    {
      try
      {
        SeekableArchive().WriteTo(out, openvdb::GridCPtrVec{ grid }, fileMetadata);
      }
      catch (const std::exception& e)
      {
        Fail(path, "cannot write the field as OpenVDB: " + std::string(e.what()));
      }
    });
}

} // namespace cloudvis
