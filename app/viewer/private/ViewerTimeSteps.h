// The time steps of the field the viewer shows: a NetCDF file's time axis or a numbered file
// series (FieldSeries.h). Which step is shown, how the window names it ("time step 3 of 0 .. 19:
// t = 180 s"), and the read ahead of the step after it while the window is idle, so that stepping
// with , and . costs the upload and the first frame, not the read. Reads go through the command
// line's own path (ProduceField: the isolated, checked read of the format, the units resolved as
// `render` resolves them), so a step the viewer shows is the field `render --time-step N` renders.
// The read ahead runs on the viewer's own thread, in the live loop's idle time (LiveLoop.h), not
// on a thread of its own: an isolated read forks, and a child forked while another thread of the
// process is inside the allocator or TBB's loops (the window rendering) can wait forever.
#ifndef cloudvis_ViewerTimeSteps_h
#define cloudvis_ViewerTimeSteps_h

#include "FieldIO.h"

#include <vtkImageData.h>
#include <vtkSmartPointer.h>

#include <functional>
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

  int Current() const { return this->Step; }
  // The steps the field held at the last read (a series being written grows).
  int Count() const { return int(this->Shown.TimeSteps); }
  // There is a time axis to step along (more than one step, or a series that may grow).
  bool Steps() const { return bool(this->Read) && (this->Count() > 1 || this->Series()); }
  bool Series() const { return !this->Shown.StepFile.empty(); }

  // The largest step read ahead: a bigger one would hold up the window's input for seconds.
  static constexpr double MaximumReadAheadBytes = 256.0 * 1048576.0;
  // Asks for `step` to be read ahead, unless it is outside 0 .. Count() - 1 or is the step shown,
  // or a step of `fieldBytes` is above MaximumReadAheadBytes or two would take more than a
  // quarter of the memory available (the step is then read when it is asked for).
  void ReadAheadLater(int step, double fieldBytes);
  // Reads the step asked for, if it is not read yet: the live loop's idle work. Returns whether
  // it read. A step that cannot be read is not kept: Take reads it again and says why.
  bool ReadAhead();
  // Step `step`: the one read ahead when it is that step, else read now. Throws InputError;
  // nothing changes then.
  FieldStep Take(int step);
  // The window now shows `step`, read with `report`.
  void SetShown(int step, const FieldReport& report);

  // "time step 3 of 0 .. 19: t = 180 s", with the series' file: "..., les_0004.nc".
  std::string Label() const;
  // The step read ahead and waiting to be shown, -1 for none (the state file's "read_ahead").
  int ReadAheadStep() const { return this->Ahead.Field ? this->AheadStep : -1; }

private:
  Reader Read;
  int Step = 0;
  FieldReport Shown;
  int WantedStep = -1; // asked for by ReadAheadLater
  int AheadStep = -1;  // of Ahead
  FieldStep Ahead;
};

} // namespace cloudvis

#endif
