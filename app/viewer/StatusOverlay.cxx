// Implementation of StatusOverlay.h. Text widths are measured with VTK's own text renderer (the
// one that draws them), so wrapping matches what is drawn at every window size.
#include "StatusOverlay.h"

#include "KeyBindings.h"
#include "Viewer.h"

#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkStdString.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkTextRenderer.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

namespace cloudvis
{
namespace
{
constexpr int MessageFontSize = 14;
constexpr int MaximumMessageLines = 3;
constexpr int FadeSteps = 5;
const char* const HintText = "h: keys   4: four views";
constexpr int HelpFontSize = 13;

void StyleBoxedText(vtkTextActor* actor, int fontSize, double opacity)
{
  vtkTextProperty* text = actor->GetTextProperty();
  UseViewerFont(text);
  text->SetFontSize(fontSize);
  text->SetBackgroundColor(0.0, 0.0, 0.0);
  text->SetBackgroundOpacity(opacity);
  actor->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
}

// The size of `text` drawn with `property`, in pixels: width, height.
std::array<int, 2> TextSize(vtkTextProperty* property, const std::string& text, int dpi)
{
  int box[4] = { 0, 0, 0, 0 };
  vtkTextRenderer* renderer = vtkTextRenderer::GetInstance();
  if (!renderer || text.empty() ||
    !renderer->GetBoundingBox(property, vtkStdString(text), box, dpi))
  {
    return { { 0, 0 } };
  }
  return { { box[1] - box[0], box[3] - box[2] } };
}

int TextWidth(vtkTextProperty* property, const std::string& text, int dpi)
{
  return TextSize(property, text, dpi)[0];
}

// Greedy word wrap to `width` pixels, at most MaximumMessageLines lines; a word wider than a
// line is cut; what does not fit ends in "...".
std::string Wrap(vtkTextProperty* property, const std::string& text, int width, int dpi)
{
  std::istringstream words(text);
  std::vector<std::string> lines(1);
  std::string word;
  bool cut = false;
  while (words >> word && !cut)
  {
    std::string candidate = lines.back().empty() ? word : lines.back() + " " + word;
    if (TextWidth(property, candidate, dpi) <= width || lines.back().empty())
    {
      lines.back() = candidate;
      // A single word wider than the line: keep what fits.
      while (TextWidth(property, lines.back(), dpi) > width && lines.back().size() > 4)
      {
        lines.back().pop_back();
        cut = true;
      }
      continue;
    }
    if (int(lines.size()) == MaximumMessageLines)
    {
      cut = true;
      break;
    }
    lines.push_back(word);
  }
  if (cut)
  {
    std::string& last = lines.back();
    while (!last.empty() && TextWidth(property, last + "...", dpi) > width)
    {
      last.pop_back();
    }
    last += "...";
  }
  std::string wrapped;
  for (const std::string& line : lines)
  {
    wrapped += (wrapped.empty() ? "" : "\n") + line;
  }
  return wrapped;
}
} // namespace

std::string UseViewerFont(vtkTextProperty* text)
{
  static const std::string file = []
  {
    for (const char* path : { "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
           "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
           "/usr/share/fonts/truetype/liberation2/LiberationSans-Regular.ttf" })
    {
      if (std::ifstream(path).good())
      {
        return std::string(path);
      }
    }
    return std::string();
  }();
  if (file.empty())
  {
    text->SetFontFamilyToCourier();
  }
  else
  {
    text->SetFontFamily(VTK_FONT_FILE);
    text->SetFontFile(file.c_str());
  }
  return file;
}

double MonotonicSeconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

StatusOverlay::StatusOverlay(vtkRenderer* overlay)
  : Renderer(overlay)
{
  StyleBoxedText(this->Message, MessageFontSize, 0.5);
  this->Message->GetTextProperty()->SetVerticalJustificationToTop();
  this->Message->SetPosition(0.01, 0.99);
  this->Message->VisibilityOff();
  overlay->AddActor2D(this->Message);

  this->Pages = HelpPages();
  for (size_t c = 0; c < 2; ++c)
  {
    vtkTextActor* help = this->Help[c];
    StyleBoxedText(help, HelpFontSize, 0.65);
    help->GetTextProperty()->SetFontFamilyToCourier();
    help->GetTextProperty()->SetColor(1.0, 1.0, 0.85);
    help->GetTextProperty()->SetVerticalJustificationToTop();
    help->VisibilityOff();
    overlay->AddActor2D(help);
  }

  StyleBoxedText(this->Hint, 12, 0.45);
  this->Hint->GetTextProperty()->SetJustificationToRight();
  this->Hint->GetTextProperty()->SetColor(0.9, 0.9, 0.7);
  this->Hint->SetPosition(0.99, 0.01);
  this->Hint->SetInput(HintText);
  overlay->AddActor2D(this->Hint);

  StyleBoxedText(this->Readout, 12, 0.45);
  this->Readout->SetPosition(0.01, 0.01);
  this->Readout->VisibilityOff();
  overlay->AddActor2D(this->Readout);

  StyleBoxedText(this->Progress, 12, 0.45);
  this->Progress->GetTextProperty()->SetJustificationToRight();
  this->Progress->GetTextProperty()->SetVerticalJustificationToTop();
  this->Progress->GetTextProperty()->SetColor(0.85, 0.95, 0.85);
  this->Progress->SetPosition(0.99, 0.99);
  this->Progress->VisibilityOff();
  overlay->AddActor2D(this->Progress);
}

StatusOverlay::~StatusOverlay() = default;

void StatusOverlay::ShowMessage(const std::string& text, bool error)
{
  this->MessageText = text;
  this->Error = error;
  this->ShownAt = MonotonicSeconds();
  this->Message->GetTextProperty()->SetColor(
    error ? 1.0 : 0.85, error ? 0.45 : 0.95, error ? 0.4 : 0.85);
  this->Message->GetTextProperty()->SetOpacity(1.0);
  this->Message->GetTextProperty()->SetBackgroundOpacity(0.5);
  this->Message->VisibilityOn();
  this->LayOut();
}

std::string StatusOverlay::GetMessage() const
{
  const char* text = this->Message->GetInput();
  return this->Message->GetVisibility() && text ? text : "";
}

double StatusOverlay::Tick(bool& changed)
{
  changed = false;
  if (this->ShownAt < 0.0)
  {
    return -1.0;
  }
  const double shown = MessageSeconds * (this->Error ? 2.0 : 1.0);
  const double age = MonotonicSeconds() - this->ShownAt;
  if (age < shown)
  {
    return shown - age;
  }
  // Fading: the opacity falls in FadeSteps steps, then the message goes.
  const int step = int((age - shown) / FadeSeconds * FadeSteps) + 1;
  const double opacity = std::max(0.0, 1.0 - double(step) / FadeSteps);
  if (opacity <= 0.0)
  {
    this->Message->VisibilityOff();
    this->ShownAt = -1.0;
    changed = true;
    return -1.0;
  }
  if (this->Message->GetTextProperty()->GetOpacity() != opacity)
  {
    this->Message->GetTextProperty()->SetOpacity(opacity);
    this->Message->GetTextProperty()->SetBackgroundOpacity(0.5 * opacity);
    changed = true;
  }
  return shown + double(step) * FadeSeconds / FadeSteps - age;
}

void StatusOverlay::SetHelpPage(int page)
{
  this->Page = page >= 0 && page < int(this->Pages.size()) ? page : -1;
  for (size_t c = 0; c < 2; ++c)
  {
    const std::string text = this->Page >= 0 ? this->Pages[size_t(this->Page)].Columns[c] : "";
    this->Help[c]->SetInput(text.c_str());
    this->Help[c]->SetVisibility(!text.empty());
  }
  if (this->Page >= 0)
  {
    this->HelpShown = true;
    this->Hint->VisibilityOff();
  }
  this->LayOut();
}

std::string StatusOverlay::GetHelpPageName() const
{
  return this->Page >= 0 ? this->Pages[size_t(this->Page)].Name : "";
}

bool StatusOverlay::GetHintVisible() const
{
  return this->Hint->GetVisibility() != 0;
}

void StatusOverlay::SetReadout(const std::string& text)
{
  this->Readout->SetInput(text.c_str());
  this->Readout->SetVisibility(!text.empty());
}

std::string StatusOverlay::GetReadout() const
{
  const char* text = this->Readout->GetInput();
  return this->Readout->GetVisibility() && text ? text : "";
}

void StatusOverlay::SetProgress(const std::string& text)
{
  this->ProgressText = text;
  this->ShowCorner();
}

std::string StatusOverlay::GetProgress() const
{
  return this->Progress->GetVisibility() ? this->ProgressText : "";
}

void StatusOverlay::SetCorner(const std::string& text)
{
  this->CornerText = text;
  this->ShowCorner();
  this->LayOut(); // the message wraps short of the corner's lines
}

void StatusOverlay::ShowCorner()
{
  const std::string text = this->CornerText +
    (this->CornerText.empty() || this->ProgressText.empty() ? "" : "\n") + this->ProgressText;
  this->Progress->SetInput(text.c_str());
  this->Progress->SetVisibility(!text.empty());
}

StatusOverlay::Visibility StatusOverlay::HideAll()
{
  const std::array<vtkTextActor*, 6> actors = {
    this->Message, this->Help[0], this->Help[1], this->Hint, this->Readout, this->Progress
  };
  Visibility visible;
  for (size_t i = 0; i < actors.size(); ++i)
  {
    visible[i] = actors[i]->GetVisibility() != 0;
    actors[i]->VisibilityOff();
  }
  return visible;
}

void StatusOverlay::Restore(const Visibility& visible)
{
  const std::array<vtkTextActor*, 6> actors = {
    this->Message, this->Help[0], this->Help[1], this->Hint, this->Readout, this->Progress
  };
  for (size_t i = 0; i < actors.size(); ++i)
  {
    actors[i]->SetVisibility(visible[i]);
  }
}

void StatusOverlay::Place(const std::array<double, 4>& view, const std::array<double, 2>& readout)
{
  this->View = view;
  this->Message->SetPosition(view[0] + 0.01, view[3] - 0.01);
  this->Hint->SetPosition(view[2] - 0.01, view[1] + 0.01);
  this->Progress->SetPosition(view[2] - 0.01, view[3] - 0.01);
  this->Readout->SetPosition(readout[0], readout[1]);
  this->LayOut();
}

void StatusOverlay::LayOut()
{
  if (!this->Renderer->GetRenderWindow())
  {
    return;
  }
  int size[2];
  this->Renderer->GetTiledSize(&size[0], &size[1]);
  const int dpi = this->Renderer->GetRenderWindow()->GetDPI();
  // The message wraps short of the corner's lines at the top right, which stay.
  const int corner = this->CornerText.empty()
    ? 0
    : TextWidth(this->Progress->GetTextProperty(), this->CornerText, dpi) + 16;
  const int width = int((this->View[2] - this->View[0]) * size[0]) - corner;
  const std::string wrapped = this->MessageText.empty()
    ? ""
    : Wrap(this->Message->GetTextProperty(), this->MessageText, std::max(40, width - 24), dpi);
  this->Message->SetInput(wrapped.c_str());

  if (this->Page < 0)
  {
    return;
  }
  // The help page's columns side by side over the whole overlay, in the largest font (at most
  // HelpFontSize) at which they fit under the message line.
  const int margin = 8, gap = 16, top = 28;
  std::array<std::array<int, 2>, 2> columns{};
  int fontSize = HelpFontSize;
  for (; fontSize > 6; --fontSize)
  {
    for (size_t c = 0; c < 2; ++c)
    {
      this->Help[c]->GetTextProperty()->SetFontSize(fontSize);
      columns[c] = TextSize(this->Help[c]->GetTextProperty(), this->Help[c]->GetInput(), dpi);
    }
    if (columns[0][0] + columns[1][0] + gap + 2 * margin <= size[0] &&
      std::max(columns[0][1], columns[1][1]) + top + margin <= size[1])
    {
      break;
    }
  }
  const double y = 1.0 - double(top) / std::max(1, size[1]);
  this->HelpFont = fontSize;
  this->HelpBoxes.clear();
  int x = margin;
  for (size_t c = 0; c < 2; ++c)
  {
    this->Help[c]->SetPosition(double(x) / std::max(1, size[0]), y);
    if (columns[c][0] > 0)
    {
      this->HelpBoxes.push_back(
        { { x, size[1] - top - columns[c][1], x + columns[c][0], size[1] - top } });
    }
    x += columns[c][0] + gap;
  }
}

std::vector<std::array<int, 4>> StatusOverlay::GetHelpBoxes() const
{
  if (this->Page < 0)
  {
    return {};
  }
  const int* origin = this->Renderer->GetOrigin();
  std::vector<std::array<int, 4>> boxes = this->HelpBoxes;
  for (auto& box : boxes)
  {
    box = { { box[0] + origin[0], box[1] + origin[1], box[2] + origin[0], box[3] + origin[1] } };
  }
  return boxes;
}

} // namespace cloudvis
