// The time steps of the field the viewer shows: a NetCDF file's time axis or a numbered file
// series (FieldSeries.h). Which step is shown, how the window names it ("time step 3 of 0 .. 19:
// t = 180 s"), and the read of the step after it in the background, so that stepping with , and .
// costs the upload and the first frame, not the read. Reads go through the command line's own
// path (ProduceField: the isolated, checked read of the format, the units resolved as `render`
// resolves them), so a step the viewer shows is the field `render --time-step N` renders.
#ifndef cloudvis_ViewerTimeSteps_h
#define cloudvis_ViewerTimeSteps_h

#include "FieldIO.h"

#include <vtkImageData.h>
#include <vtkSmartPointer.h>

#include <functional>
#include <future>
#include <string>

namespace cloudvis
{

// One time step as read: its field and what the reader said.
struct FieldStep
{
  vtkSmartPointer<vtkImageData> Field;
  FieldReport Report;
};

class ViewerTimeSteps
{
public:
  // Reads a step into its field and report (ViewerOptions::ReadTimeStep); throws InputError (a
  // step beyond the field, a file the series no longer fits).
  using Reader = std::function<vtkSmartPointer<vtkImageData>(int step, FieldReport& report)>;

  // `shown` is the report of step `step`, the one the window opened with. Without a reader the
  // field has no time steps to go to (a generated field).
  ViewerTimeSteps(Reader reader, int step, const FieldReport& shown);
  // Waits for a read in flight: its thread must not outlive what it reads into.
  ~ViewerTimeSteps();
  ViewerTimeSteps(const ViewerTimeSteps&) = delete;
  ViewerTimeSteps& operator=(const ViewerTimeSteps&) = delete;

  int Current() const { return this->Step; }
  // The steps the field held at the last read (a series being written grows).
  int Count() const { return int(this->Shown.TimeSteps); }
  // There is a time axis to step along (more than one step, or a series that may grow).
  bool Steps() const { return bool(this->Read) && (this->Count() > 1 || this->Series()); }
  bool Series() const { return !this->Shown.StepFile.empty(); }

  // Starts reading `step` in the background unless it is outside 0 .. Count() - 1, is being read
  // or was read already, or a second field of `fieldBytes` would take more than a quarter of the
  // memory available (the step is then read when it is asked for).
  void Prefetch(int step, double fieldBytes);
  // Step `step`: the background read's when it is of that step (waiting for it to finish), else
  // read now. Throws InputError; nothing changes then.
  FieldStep Take(int step);
  // The window now shows `step`, read with `report`.
  void SetShown(int step, const FieldReport& report);

  // "time step 3 of 0 .. 19: t = 180 s", with the series' file: "..., les_0004.nc".
  std::string Label() const;
  // Whether a step is being read in the background (for tests: the prefetch happened).
  bool Prefetching() const { return this->PendingStep >= 0; }

private:
  Reader Read;
  int Step = 0;
  FieldReport Shown;
  int PendingStep = -1;
  std::future<FieldStep> Pending;
};

} // namespace cloudvis

#endif
