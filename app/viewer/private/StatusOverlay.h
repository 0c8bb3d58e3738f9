// The texts over the views, in the viewer's overlay renderer (a layer of its own, so that a text
// that changes never restarts the cloud's accumulation): the message line at the top left
// (what a key did, saved files, errors), wrapped to the window's width and fading out after a few
// seconds; the help (pages of two columns made from the key and mouse tables); a hint line at the
// bottom right
// ("h: keys ...") until the help has been shown once; the readout at the bottom left: the
// voxel under the pointer over the last probe (the viewer clears it when no slice is shown); and
// the progress line at the top right, while work spread over frames goes on ("multiple
// scattering: converging (k/n)"), gone when it is done; above it, the lines that stay: for a field
// with time steps the step shown and its time ("time step 3 of 0 .. 19: t = 180 s"), and that the
// 3D view draws the field coarsened to fit the GPU.
#ifndef cloudvis_StatusOverlay_h
#define cloudvis_StatusOverlay_h

#include "KeyBindings.h"

#include <vtkNew.h>

#include <array>
#include <string>
#include <vector>

class vtkRenderer;
class vtkTextActor;

namespace cloudvis
{

class StatusOverlay
{
public:
  explicit StatusOverlay(vtkRenderer* overlay);
  ~StatusOverlay();
  StatusOverlay(const StatusOverlay&) = delete;
  StatusOverlay& operator=(const StatusOverlay&) = delete;

  // Shown in full for MessageSeconds (errors twice as long), then faded out over FadeSeconds.
  static constexpr double MessageSeconds = 4.0;
  static constexpr double FadeSeconds = 1.0;

  void ShowMessage(const std::string& text, bool error);
  // The message as shown (wrapped), empty once it has faded.
  std::string GetMessage() const;

  // Advances the fading to now. Returns the seconds until the next step, negative when nothing
  // is fading; `changed` tells whether the picture changed.
  double Tick(bool& changed);

  // The help's pages (HelpPages(): the keys, the mouse): the page shown, -1 for none.
  void SetHelpPage(int page);
  int GetHelpPage() const { return this->Page; }
  int GetNumberOfHelpPages() const { return int(this->Pages.size()); }
  std::string GetHelpPageName() const; // empty when hidden
  bool GetHelpVisible() const { return this->Page >= 0; }
  // The shown help's columns in window pixels (x0, y0, x1, y1 from the bottom left), and their
  // font size: the largest at most 13 at which the page fits the views.
  std::vector<std::array<int, 4>> GetHelpBoxes() const;
  int GetHelpFontSize() const { return this->HelpFont; }
  bool GetHintVisible() const;

  void SetReadout(const std::string& text);
  std::string GetReadout() const;

  // The progress line; empty hides it.
  void SetProgress(const std::string& text);
  std::string GetProgress() const;
  // The lines above the progress (the time step shown, the 3D view coarsened); empty: none.
  void SetCorner(const std::string& text);
  std::string GetCorner() const { return this->CornerText; }

  // Hides or shows every text (for screenshots of the 3D view alone); returns what was visible.
  using Visibility = std::array<bool, 6>;
  Visibility HideAll();
  void Restore(const Visibility& visible);

  // Places the texts for a layout: the message at the top left and the hint at the bottom right
  // of `view` (the 3D view, in the overlay's normalized viewport coordinates), the readout's
  // bottom left corner at `readout`. Re-wraps the message to the view's width.
  void Place(const std::array<double, 4>& view, const std::array<double, 2>& readout);

  // Re-wraps the message to the view's width (after a resize).
  void LayOut();

private:
  vtkRenderer* Renderer;
  vtkNew<vtkTextActor> Message;
  std::array<vtkNew<vtkTextActor>, 2> Help;
  std::vector<HelpPage> Pages;
  int Page = -1;
  int HelpFont = 0;
  std::vector<std::array<int, 4>> HelpBoxes; // in the overlay's pixels
  vtkNew<vtkTextActor> Hint;
  vtkNew<vtkTextActor> Readout;
  vtkNew<vtkTextActor> Progress;
  void ShowCorner(); // Progress shows CornerText over ProgressText
  std::string CornerText;
  std::string ProgressText;
  std::string MessageText; // unwrapped
  bool Error = false;
  double ShownAt = -1.0; // steady-clock seconds; negative: no message
  bool HelpShown = false;
  std::array<double, 4> View{ { 0.0, 0.0, 1.0, 1.0 } };
};

// Seconds on the monotonic clock (CLOCK_MONOTONIC), as the viewer's state file reports times.
double MonotonicSeconds();

} // namespace cloudvis

#endif
