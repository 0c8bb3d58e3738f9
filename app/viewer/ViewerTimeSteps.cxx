// The viewer's time steps and the read ahead of the next one (ViewerTimeSteps.h).
#include "ViewerTimeSteps.h"

#include "CloudFieldGeometry.h" // AvailableMemoryBytes
#include "Errors.h"
#include "FileNames.h"

#include <cmath>
#include <sstream>

namespace cloudvis
{
namespace
{

FieldStep ReadStep(const ViewerTimeSteps::Reader& read, int step)
{
  FieldStep result;
  result.Field = read(step, result.Report);
  return result;
}

} // namespace

ViewerTimeSteps::ViewerTimeSteps(Reader reader, int step, const FieldReport& shown)
  : Read(std::move(reader))
  , Step(step)
  , Shown(shown)
{
}

void ViewerTimeSteps::ReadAheadLater(int step, double fieldBytes)
{
  const bool fits =
    fieldBytes <= MaximumReadAheadBytes && 4.0 * fieldBytes <= double(AvailableMemoryBytes());
  this->WantedStep =
    this->Read && fits && step >= 0 && step < this->Count() && step != this->Step ? step : -1;
}

bool ViewerTimeSteps::ReadAhead()
{
  if (this->WantedStep < 0 || (this->Ahead.Field && this->AheadStep == this->WantedStep))
  {
    return false;
  }
  const int step = this->WantedStep;
  this->WantedStep = -1;
  this->Ahead = {};
  try
  {
    this->Ahead = ReadStep(this->Read, step);
    this->AheadStep = step;
  }
  catch (const InputError&)
  {
    // Said when the step is asked for: Take reads it again.
  }
  return true;
}

FieldStep ViewerTimeSteps::Take(int step)
{
  if (this->Ahead.Field && this->AheadStep == step)
  {
    FieldStep taken = std::move(this->Ahead);
    this->Ahead = {};
    return taken;
  }
  return ReadStep(this->Read, step);
}

void ViewerTimeSteps::SetShown(int step, const FieldReport& report)
{
  this->Step = step;
  this->Shown = report;
}

std::string ViewerTimeSteps::Label() const
{
  std::ostringstream text;
  text.precision(6);
  text << "time step " << this->Step << " of 0 .. " << this->Count() - 1;
  if (!std::isnan(this->Shown.Time))
  {
    text << ": t = " << this->Shown.Time
         << (this->Shown.TimeUnits.empty() ? "" : " " + this->Shown.TimeUnits);
  }
  if (this->Series())
  {
    text << (std::isnan(this->Shown.Time) ? ": " : ", ") << FileNameOf(this->Shown.StepFile);
  }
  return text.str();
}

} // namespace cloudvis
