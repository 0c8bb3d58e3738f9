// The bar is 30 cells wide; "\033[K" clears what a longer previous line left behind.
#include "Progress.h"

#include <algorithm>
#include <cmath>
#include <unistd.h>

namespace cloudvis
{

Progress::Progress(std::ostream& out, bool enabled)
  : Out(out)
  , IsEnabled(enabled)
{
}

Progress::~Progress()
{
  this->Finish();
}

bool Progress::StderrIsTerminal()
{
  return ::isatty(STDERR_FILENO) == 1;
}

void Progress::Update(const std::string& label, double fraction)
{
  if (!this->IsEnabled)
  {
    return;
  }
  fraction = std::min(std::max(fraction, 0.0), 1.0);
  const int percent = int(std::floor(fraction * 100.0));
  if (this->Shown && percent == this->LastPercent && label == this->LastLabel)
  {
    return;
  }
  constexpr int cells = 30;
  const int filled = int(std::floor(fraction * cells));
  this->Out << "\r" << label << " [" << std::string(size_t(filled), '#')
            << std::string(size_t(cells - filled), '.') << "] " << (percent < 10 ? "  " : percent < 100 ? " " : "")
            << percent << "%\033[K" << std::flush;
  this->Shown = true;
  this->LastPercent = percent;
  this->LastLabel = label;
}

void Progress::Finish()
{
  if (this->IsEnabled && this->Shown)
  {
    this->Out << "\r\033[K" << std::flush;
  }
  this->Shown = false;
  this->LastPercent = -1;
  this->LastLabel.clear();
}

} // namespace cloudvis
