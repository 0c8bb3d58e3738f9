// Collects what VTK would print to its output window while an object of this class lives, so a
// failing reader or writer becomes one clean "cloudvis: error:" line that quotes VTK's own
// explanation instead of a multi-line vtkErrorMacro dump on stderr. VTK 9 also logs each error
// through vtkLogger straight to stderr, so that is silenced for the same scope.
#ifndef cloudvis_VtkMessageCapture_h
#define cloudvis_VtkMessageCapture_h

#include <vtkLogger.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

class vtkOutputWindow;

namespace cloudvis
{

class VtkMessageCapture
{
public:
  VtkMessageCapture();
  ~VtkMessageCapture();
  VtkMessageCapture(const VtkMessageCapture&) = delete;
  VtkMessageCapture& operator=(const VtkMessageCapture&) = delete;

  // Error and warning texts seen so far, stripped of VTK's "ERROR: In file, line N" preamble.
  const std::vector<std::string>& Messages() const;

  // The messages joined by "; ", or empty.
  std::string Summary() const;

  // `problem` followed by " (VTK: SUMMARY)", or `problem` alone when VTK said nothing or nothing
  // the problem does not already say (a message cloudvis itself passed through VTK's error
  // macro). The one way a refusal quotes VTK.
  std::string WithVtkReason(const std::string& problem) const;

private:
  vtkSmartPointer<vtkOutputWindow> Previous;
  vtkSmartPointer<vtkOutputWindow> Collector;
  vtkLogger::Verbosity PreviousStderrVerbosity;
};

} // namespace cloudvis

#endif
