// Numbered file series: field.file "run/les_*.nc" names the files run/les_0001.nc,
// run/les_0002.nc, ... as one time-varying field, as ParaView opens such files as one dataset.
// The `*` stands for the number and matches digits only; the files are ordered by their numbers,
// and step k of the field (field.time_step, --time-steps, the viewer's time keys) is the k-th file.
// A number missing from the progression the others make (les_0003.nc between les_0002.nc and
// les_0004.nc) is refused, naming the file, unless field.series_gaps "skip" says to read the files
// there are. Every file of a series holds one time step and the same grid (CheckSameGrid); each is
// read by its own format's reader, so a half-written file is refused as any broken file is.
// docs/data.md, "Time series", describes this for users.
#ifndef cloudvis_FieldSeries_h
#define cloudvis_FieldSeries_h

#include "FieldIO.h"

#include <string>
#include <vector>

class vtkImageData;

namespace cloudvis
{

// Whether `path` names a series: a `*` in its last component.
bool IsFileSeriesPattern(const std::string& path);

// The pattern of a series two of its files belong to: "run/les_*.nc" of "run/les_0001.nc" and
// "run/les_0002.nc" (the run of digits where they differ, and around it what they share); empty
// when they do not differ in one run of digits.
std::string SeriesPatternOf(const std::string& first, const std::string& second);

struct FileSeries
{
  std::vector<std::string> Files;   // the paths, ordered by their numbers
  std::vector<long long> Numbers;   // the number in each file's name
  std::vector<std::string> Missing; // the names the progression expects but the folder lacks
};

// Lists the files of `pattern` now (the folder is read again at every call, so a series being
// written grows). Throws InputError naming the pattern: more than one `*` or one in the folder's
// part, a folder that cannot be read, no file that matches, two files with one number, and gaps
// unless `skipGaps`.
FileSeries FindFileSeries(const std::string& pattern, bool skipGaps);

// ReadField of a series: the file of step options.TimeStep (default 0), read with the other
// options; the report is that file's, with the series' step count and a "series" line. Throws
// InputError for a step beyond the series (naming the pattern) and for a file of more than one
// time step (naming the file).
vtkSmartPointer<vtkImageData> ReadFileSeriesStep(const std::string& pattern,
  const FieldReadOptions& options,
  FieldReport* report);

// How messages name step `step` of the field file `file` once read: "run/les_0004.nc (step 3 of
// run/les_*.nc)" for a series, "fielddump.nc (time step 3)" for a file's own time axis.
std::string TimeStepName(const std::string& file, int step, const FieldReport& read);

// Throws InputError naming `name` ("les_0004.nc, step 3 of run/les_*.nc") unless `step` has the
// dimensions, spacing, origin and direction of `first`, the series' first step read: a time series
// is one field whose values change, and every consumer (a frame's camera, the viewer's slices, the
// per-step statistics) relies on its lattice staying put.
void CheckSameGrid(const std::string& name, vtkImageData* first, vtkImageData* step);

} // namespace cloudvis

#endif
