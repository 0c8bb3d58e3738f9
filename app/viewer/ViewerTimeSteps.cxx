// The viewer's time steps and their background read (ViewerTimeSteps.h).
#include "ViewerTimeSteps.h"

#include "CloudFieldGeometry.h" // AvailableMemoryBytes
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

ViewerTimeSteps::~ViewerTimeSteps()
{
  if (this->Pending.valid())
  {
    this->Pending.wait();
  }
}

void ViewerTimeSteps::Prefetch(int step, double fieldBytes)
{
  if (!this->Read || step < 0 || step >= this->Count() || step == this->PendingStep ||
    step == this->Step || 4.0 * fieldBytes > double(AvailableMemoryBytes()))
  {
    return;
  }
  if (this->Pending.valid())
  {
    // One read at a time: the one in flight is of a step the user has turned away from.
    this->Pending.wait();
  }
  this->PendingStep = step;
  this->Pending =
    std::async(std::launch::async, [read = this->Read, step] { return ReadStep(read, step); });
}

FieldStep ViewerTimeSteps::Take(int step)
{
  if (this->PendingStep == step && this->Pending.valid())
  {
    this->PendingStep = -1;
    return this->Pending.get(); // rethrows the read's InputError
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
