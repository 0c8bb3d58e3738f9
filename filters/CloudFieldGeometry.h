// Where a procedural field is sampled: a box of world bounds and a number of voxels per axis,
// as in vtkSampleFunction's model bounds. Shared by the source and the application so both
// refuse the same bad geometry with the same words.
#ifndef CloudFieldGeometry_h
#define CloudFieldGeometry_h

#include "cloudvisFiltersModule.h"

#include <cstdint>
#include <string>

class vtkDataArray;
class vtkInformation;
class vtkInformationIntegerVectorKey;

namespace cloudvis
{

// Origin and spacing of a lattice that puts its first and last voxels on the bounds.
CLOUDVISFILTERS_EXPORT void LatticeFromBounds(
  const int dimensions[3], const double bounds[6], double origin[3], double spacing[3]);

// Bytes of physical memory this process can still take (MemAvailable), or 0 when unknown.
CLOUDVISFILTERS_EXPORT std::uint64_t AvailableMemoryBytes();

// Empty when dimensions and bounds describe a lattice, else the problem: dimensions below 1, or
// bounds that are not finite or not increasing.
CLOUDVISFILTERS_EXPORT std::string ValidateFieldGeometry(const int dimensions[3],
  const double bounds[6]);

// Empty when `extent` (as VTK writes extents: first and last index per axis), at `bytesPerVoxel`,
// fits in the memory available, else the problem, stating how much it needs. It is the extent a
// source is asked to fill that must fit, not its whole extent: a process that generates one piece
// of a field larger than its memory needs only the piece's.
CLOUDVISFILTERS_EXPORT std::string ValidateExtentMemory(const int extent[6], int bytesPerVoxel = 4);

// Copies the extent `key` (WHOLE_EXTENT, UPDATE_EXTENT) holds in the pipeline information `info`
// into `extent`; empty when it holds one, else the problem. VTK runs an algorithm's later passes
// even after an upstream RequestInformation refused its parameters (vtkVolume updates its mapper
// to render regardless), with extents that were never set: read unchecked, such an extent is
// whatever the stack held, and a source asked to fill it allocates gigabytes or throws.
CLOUDVISFILTERS_EXPORT std::string PipelineExtent(vtkInformation* info,
  vtkInformationIntegerVectorKey* key,
  int extent[6]);

// For a filter that needs its whole input (every voxel may matter to every output value): sets
// the input's UPDATE_EXTENT to its WHOLE_EXTENT in `inputInfo`; empty, else the problem.
CLOUDVISFILTERS_EXPORT std::string RequestWholeExtent(vtkInformation* inputInfo);

// Empty when `extent` lies inside `whole` or holds no voxel (nothing to fill), else the problem.
CLOUDVISFILTERS_EXPORT std::string ValidateSubExtent(const int extent[6], const int whole[6]);

// Empty when `scalars` can be rendered as a density (one component of float, unsigned char or
// unsigned short), else the problem, naming the array.
CLOUDVISFILTERS_EXPORT std::string ValidateDensityScalars(vtkDataArray* scalars);

// Empty when every value of `scalars` (already valid for ValidateDensityScalars) is a finite
// number, else the problem, naming the array and how many values are NaN or infinite. Renderers
// call it whenever the data change: a NaN density has no extinction and no color.
CLOUDVISFILTERS_EXPORT std::string ValidateDensityValues(vtkDataArray* scalars);

// "1.5 GiB", "300 MiB": sizes people can read in messages.
CLOUDVISFILTERS_EXPORT std::string FormatBytes(double bytes);

} // namespace cloudvis

#endif
