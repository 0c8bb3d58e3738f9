// VTK reports reader and writer failures through the global vtkOutputWindow; swapping in a
// collecting window for the duration of one operation is VTK's own supported way to route them.
#include "VtkMessageCapture.h"

#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>

namespace cloudvis
{
namespace
{

class vtkCloudCollectingOutputWindow : public vtkOutputWindow
{
public:
  static vtkCloudCollectingOutputWindow* New();
  vtkTypeMacro(vtkCloudCollectingOutputWindow, vtkOutputWindow);

  void PrintSelf(ostream& os, vtkIndent indent) override
  {
    this->Superclass::PrintSelf(os, indent);
    os << indent << "Messages: " << this->Messages.size() << "\n";
  }

  void DisplayText(const char* text) override { this->Add(text); }
  void DisplayErrorText(const char* text) override { this->Add(text); }
  void DisplayWarningText(const char* text) override { this->Add(text); }
  void DisplayGenericWarningText(const char* text) override { this->Add(text); }
  void DisplayDebugText(const char*) override {}

  std::vector<std::string> Messages;

protected:
  vtkCloudCollectingOutputWindow() = default;
  ~vtkCloudCollectingOutputWindow() override = default;

private:
  // VTK's messages read "ERROR: In /path/file.cxx, line 123\nvtkClass (0x...): what\n\n"; the
  // user needs only the last part.
  void Add(const char* text)
  {
    std::string message = text ? text : "";
    // The executive's "Algorithm ... returned failure for request" follows every reader error
    // and only dumps pipeline state.
    if (message.find("returned failure for request") != std::string::npos)
    {
      return;
    }
    const auto classEnd = message.find("): ");
    if (classEnd != std::string::npos)
    {
      message.erase(0, classEnd + 3);
    }
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
    {
      message.pop_back();
    }
    for (char& c : message)
    {
      c = c == '\n' ? ' ' : c;
    }
    if (!message.empty())
    {
      this->Messages.push_back(message);
    }
  }

  vtkCloudCollectingOutputWindow(const vtkCloudCollectingOutputWindow&) = delete;
  void operator=(const vtkCloudCollectingOutputWindow&) = delete;
};
vtkStandardNewMacro(vtkCloudCollectingOutputWindow);

} // namespace

VtkMessageCapture::VtkMessageCapture()
  : Previous(vtkOutputWindow::GetInstance())
  , Collector(vtkSmartPointer<vtkCloudCollectingOutputWindow>::New())
  , PreviousStderrVerbosity(vtkLogger::GetCurrentVerbosityCutoff())
{
  vtkOutputWindow::SetInstance(this->Collector);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

VtkMessageCapture::~VtkMessageCapture()
{
  vtkLogger::SetStderrVerbosity(this->PreviousStderrVerbosity);
  vtkOutputWindow::SetInstance(this->Previous);
}

const std::vector<std::string>& VtkMessageCapture::Messages() const
{
  return static_cast<vtkCloudCollectingOutputWindow*>(this->Collector.Get())->Messages;
}

std::string VtkMessageCapture::Summary() const
{
  std::string summary;
  for (const std::string& message : this->Messages())
  {
    summary += (summary.empty() ? "" : "; ") + message;
  }
  return summary;
}

std::string VtkMessageCapture::WithVtkReason(const std::string& problem) const
{
  std::string unsaid;
  for (const std::string& message : this->Messages())
  {
    if (problem.find(message) == std::string::npos)
    {
      unsaid += (unsaid.empty() ? "" : "; ") + message;
    }
  }
  return unsaid.empty() ? problem : problem + " (VTK: " + unsaid + ")";
}

} // namespace cloudvis
