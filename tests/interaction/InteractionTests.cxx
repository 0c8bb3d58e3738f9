// Recorded sessions of `cloudvis view`, replayed headless (Xvfb) on a small window and a small
// field: each builds the viewer, plays a recording from tests/recordings
// (vtkInteractorEventRecorder's text format, written by hand) and checks what the session changed:
// the viewer's state, the scene it saves, the files it writes and the images it shows. Window 480 x
// 400: the 3D view is 480 x 300 above the editor's 480 x 100.
#include "Errors.h"
#include "Scene.h"
#include "SceneField.h"
#include "SupportImages.h"
#include "SupportRun.h"
#include "Viewer.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkStdString.h>
#include <vtkTextProperty.h>
#include <vtkTextRenderer.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <sys/stat.h>

namespace cloudvis
{
namespace
{

const std::string Recordings = CLOUDVIS_RECORDINGS;
const std::string WorkRoot = CLOUDVIS_WORK_DIR;

std::string FreshDirectory(const std::string& name)
{
  const std::string directory = WorkRoot + "/" + name;
  const std::string command = "rm -rf '" + directory + "' && mkdir -p '" + directory + "'";
  EXPECT_EQ(std::system(command.c_str()), 0);
  return directory;
}

bool Exists(const std::string& path)
{
  struct stat info;
  return ::stat(path.c_str(), &info) == 0;
}

nlohmann::json ReadJson(const std::string& path)
{
  const std::string text = support::ReadText(path);
  EXPECT_FALSE(text.empty()) << path;
  return nlohmann::json::parse(text);
}

using support::ReadPng;
using Pixels = support::Image;

// Root-mean-square difference in 8-bit levels; infinite when the sizes differ.
double Rms(const Pixels& a, const Pixels& b)
{
  return support::Compare(a, b).RmsLevels();
}

// The default cloud on 48^3 voxels, seen from above and to the side so that every slice plane
// shows its face; accumulation kept short.
Scene SmallScene(const std::vector<std::string>& extra = {})
{
  std::vector<std::string> assignments = {
    "field.dimensions=48", "render.accumulate=4", "camera.orbit={\"azimuth\":35,\"elevation\":30}"
  };
  assignments.insert(assignments.end(), extra.begin(), extra.end());
  return LoadScene("", assignments);
}

struct Session
{
  std::ostringstream Messages;
  std::unique_ptr<Viewer> View;

  explicit Session(const std::string& directory,
    const Scene& scene = SmallScene(),
    std::array<int, 2> windowSize = { { 480, 400 } })
  {
    ViewerOptions options;
    options.WindowSize = windowSize;
    options.OutputDirectory = directory;
    options.Messages = &this->Messages;
    this->View = std::make_unique<Viewer>(scene, ProduceField(scene), options);
  }
};

TEST(Interaction, LayoutScreenshot)
{
  const std::string directory = FreshDirectory("layout");
  Session session(directory);
  session.View->PressKey("x", 'x');
  session.View->PressKey("z", 'z');
  session.View->PressKey("o", 'o');
  session.View->PressKey("h", 'h');
  session.View->SaveWindowImage(directory + "/window.png");
  const Pixels window = ReadPng(directory + "/window.png");
  ASSERT_EQ(window.Width, 480);
  ASSERT_EQ(window.Height, 400);
  const ViewerState state = session.View->State();
  EXPECT_TRUE(state.SliceVisible[0]);
  EXPECT_FALSE(state.SliceVisible[1]);
  EXPECT_TRUE(state.SliceVisible[2]);
  EXPECT_TRUE(state.ObliqueVisible);
  EXPECT_GT(state.ObliqueCutPoints, 100);
  EXPECT_TRUE(state.HelpVisible);
  EXPECT_EQ(state.ViewSize[0], 480);
  EXPECT_EQ(state.ViewSize[1], 300);
}

TEST(Interaction, SliceDragMovesThePlaneAndTheProbe)
{
  const std::string directory = FreshDirectory("slice-drag");
  Session session(directory);
  const double before = session.View->State().SlicePosition[2];
  // The cursor shows the value under it while Control + left button is down: probe the slice's
  // centre, move the slice with the middle button, probe the same pixel again.
  const std::string all = support::ReadText(Recordings + "/slice-drag.log");
  const size_t release = all.find("LeftButtonReleaseEvent");
  const size_t middle = all.find("MiddleButtonPressEvent");
  ASSERT_NE(release, std::string::npos);
  ASSERT_NE(middle, std::string::npos);
  session.View->PlayString(all.substr(0, release));
  const ViewerState probed = session.View->State();
  session.View->SaveWindowImage(directory + "/probed.png");
  EXPECT_TRUE(probed.SliceVisible[2]);
  ASSERT_FALSE(std::isnan(probed.ProbedValue[2])) << "the left click did not probe the z slice";
  session.View->PlayString("# StreamVersion 1.1\n" + all.substr(release));
  session.View->PlayString("# StreamVersion 1.1\nMouseMoveEvent 240 250 0 0 0 0\n"
                           "LeftButtonPressEvent 240 250 2 0 0 0\n");
  const ViewerState moved = session.View->State();
  EXPECT_GT(std::abs(moved.SlicePosition[2] - before), 0.05)
    << "the middle drag did not move the z slice from " << before;
  EXPECT_NE(moved.ProbedValue[2], probed.ProbedValue[2]);
  session.View->SaveWindowImage(directory + "/window.png");
  session.View->PlayString("# StreamVersion 1.1\nLeftButtonReleaseEvent 240 250 2 0 0 0\n");
}

TEST(Interaction, TransferFunctionPointChangesFunctionAndImage)
{
  const std::string directory = FreshDirectory("tf-point");
  Session session(directory);
  const TransferFunctionSpec before = session.View->State().TransferFunction;
  session.View->PlayFile(Recordings + "/tf-point.log");
  const ViewerState after = session.View->State();
  EXPECT_EQ(after.TransferFunction.Opacity.size(), before.Opacity.size() + 1)
    << session.Messages.str();
  const nlohmann::json saved = session.View->CurrentSceneJson();
  EXPECT_NE(saved["transfer_function"]["opacity"], nlohmann::json(before.Opacity));
  const Pixels first = ReadPng(directory + "/cloudvis-screenshot-001.png");
  const Pixels second = ReadPng(directory + "/cloudvis-screenshot-002.png");
  EXPECT_GT(Rms(first, second), 1.0);
  session.View->SaveWindowImage(directory + "/window.png");
}

TEST(Interaction, LightingModelCyclesAndChangesTheImage)
{
  const std::string directory = FreshDirectory("lighting");
  Session session(directory);
  EXPECT_EQ(session.View->State().Lighting, LightingModel::None);
  session.View->PlayFile(Recordings + "/keys-lighting.log");
  EXPECT_EQ(session.View->State().Lighting, LightingModel::Derivative);
  const nlohmann::json saved = ReadJson(directory + "/cloudvis-view-001.json");
  EXPECT_EQ(saved["render"]["lighting"], "derivative");
  const Pixels none = ReadPng(directory + "/cloudvis-screenshot-001.png");
  const Pixels derivative = ReadPng(directory + "/cloudvis-screenshot-002.png");
  EXPECT_GT(Rms(none, derivative), 2.0);
  // Two more presses: march, then none again.
  session.View->PressKey("m", 'm');
  EXPECT_EQ(session.View->State().Lighting, LightingModel::March);
  session.View->PressKey("m", 'm');
  EXPECT_EQ(session.View->State().Lighting, LightingModel::None);
}

TEST(Interaction, ScreenshotWritesReadablePngAndExr)
{
  const std::string directory = FreshDirectory("screenshot");
  Session session(directory);
  session.View->PressKey("s", 's');
  const Pixels png = ReadPng(directory + "/cloudvis-screenshot-001.png");
  EXPECT_EQ(png.Width, 480);
  EXPECT_EQ(png.Height, 300);
  const support::Exr exr = support::ReadExr(directory + "/cloudvis-screenshot-001.exr");
  EXPECT_EQ(exr.Width, 480);
  EXPECT_EQ(exr.Height, 300);
  // The next one takes the next number.
  session.View->PressKey("s", 's');
  EXPECT_TRUE(Exists(directory + "/cloudvis-screenshot-002.png"));
  EXPECT_TRUE(Exists(directory + "/cloudvis-screenshot-002.exr"));
}

// The saved scene renders what the window showed, after a drag and with the light moved by the
// arrow keys over a sky whose sun the scene left to the light: the scene file carries the moved
// light and the sun as it was resolved when the scene was read (the sky does not follow the
// light when it moves, so a scene without the sun would be rendered under another sky). The
// screenshot's EXR is the 3D view's float image, the cloud `render` exports (its PNG adds the
// outline, the orientation marker and the legends).
TEST(Interaction, SavedSceneRerendersToTheScreenshot)
{
  const std::string directory = FreshDirectory("rerender");
  std::array<double, 3> light;
  {
    // The light, and so the sun, ahead of the camera: the sun's glow fills the middle of the view.
    Session session(directory,
      SmallScene({ "render.lighting=derivative",
        "background={\"type\":\"sky\"}",
        "lights=[{\"type\":\"directional\",\"position\":[-3,-1.5,-4]}]" }));
    for (const char* key : { "Left", "Left", "Left", "Up" })
    {
      session.View->PressKey(key, 0);
    }
    light = session.View->State().FirstLightPosition;
    session.View->PlayFile(Recordings + "/rotate-save.log");
  }
  const std::string scene = directory + "/cloudvis-view-001.json";
  const nlohmann::json saved = ReadJson(scene);
  EXPECT_EQ(saved["render"]["size"], nlohmann::json({ 480, 300 }));
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_FLOAT_EQ(saved["lights"][0]["position"][c].get<float>(), float(light[size_t(c)])) << c;
  }
  EXPECT_TRUE(saved["background"].contains("sun")) << saved["background"].dump();
  const support::CommandResult render =
    support::RunCloudvis({ "render", scene, "-o", directory + "/render.exr" });
  ASSERT_EQ(render.Status, 0) << render.Err;
  const support::Exr shown = support::ReadExr(directory + "/cloudvis-screenshot-001.exr");
  const support::Exr rendered = support::ReadExr(directory + "/render.exr");
  ASSERT_EQ(shown.Width, rendered.Width);
  ASSERT_EQ(shown.Height, rendered.Height);
  // In 8-bit levels of the premultiplied color.
  double sum = 0.0;
  size_t count = 0;
  for (const char* channel : { "R", "G", "B" })
  {
    const auto& a = shown.Channels.at(channel);
    const auto& b = rendered.Channels.at(channel);
    for (size_t i = 0; i < a.size(); ++i)
    {
      const double d = 255.0 * (double(a[i]) - double(b[i]));
      sum += d * d;
      ++count;
    }
  }
  EXPECT_LT(std::sqrt(sum / double(count)), 2.0);
}

TEST(Interaction, MalformedPresetsKeepTheSession)
{
  const std::string directory = FreshDirectory("bad-presets");
  const std::string presets = directory + "/presets";
  ASSERT_EQ(::mkdir(presets.c_str(), 0777), 0);
  support::WriteText(presets + "/a-malformed.json", "{\"opacity\": [[0, 0], [1, 1]");
  support::WriteText(presets + "/b-empty.json", "{\"opacity\": [], \"color\": [[0, 1, 1, 1]]}");
  ::setenv("CLOUDVIS_PRESET_DIR", presets.c_str(), 1);
  Session session(directory);
  const TransferFunctionSpec before = session.View->State().TransferFunction;
  session.View->PlayFile(Recordings + "/presets.log");
  ::unsetenv("CLOUDVIS_PRESET_DIR");
  const ViewerState after = session.View->State();
  EXPECT_EQ(after.TransferFunction.Opacity, before.Opacity);
  EXPECT_EQ(after.Lighting, LightingModel::Derivative); // the keys after the errors still work
  EXPECT_TRUE(Exists(directory + "/cloudvis-screenshot-001.png"));
  const std::string messages = session.Messages.str();
  EXPECT_NE(messages.find("cloudvis: error: "), std::string::npos) << messages;
  EXPECT_NE(messages.find("a-malformed.json"), std::string::npos) << messages;
  EXPECT_NE(messages.find("b-empty.json"), std::string::npos) << messages;
  EXPECT_NE(messages.find("the transfer function is unchanged"), std::string::npos) << messages;
}

// A preset file that is a FIFO would block the viewer forever if opened as a file: it is refused
// by name, like every file cloudvis reads (docs/reliability.md), and the session goes on.
TEST(Interaction, PresetThatIsNotARegularFileIsRefusedByName)
{
  const std::string directory = FreshDirectory("fifo-preset");
  const std::string presets = directory + "/presets";
  ASSERT_EQ(::mkdir(presets.c_str(), 0777), 0);
  ASSERT_EQ(::mkfifo((presets + "/a-pipe.json").c_str(), 0666), 0);
  ::setenv("CLOUDVIS_PRESET_DIR", presets.c_str(), 1);
  Session session(directory);
  const TransferFunctionSpec before = session.View->State().TransferFunction;
  session.View->PressKey("p", 'p');
  ::unsetenv("CLOUDVIS_PRESET_DIR");
  EXPECT_EQ(session.View->State().TransferFunction.Opacity, before.Opacity);
  const std::string messages = session.Messages.str();
  EXPECT_NE(messages.find("a-pipe.json: cannot read preset file: it is a FIFO (named pipe), not a "
                          "regular file; the transfer function is unchanged"),
    std::string::npos)
    << messages;
}

// An output folder whose name is not UTF-8 (Latin-1 "café"): the screenshot is written there, and
// the message and the state (--state-file's JSON, which could not be written otherwise) show
// the byte as \xe9.
TEST(Interaction, OutputFolderThatIsNotUtf8IsEscapedInMessagesAndState)
{
  const std::string directory = FreshDirectory("not-utf8") + "/caf\xe9";
  ASSERT_EQ(::mkdir(directory.c_str(), 0777), 0);
  Session session(directory);
  session.View->PressKey("s", 's');
  EXPECT_TRUE(Exists(directory + "/cloudvis-screenshot-001.png"));
  const std::string messages = session.Messages.str();
  EXPECT_NE(messages.find("caf\\xe9/cloudvis-screenshot-001.png"), std::string::npos) << messages;
  EXPECT_EQ(messages.find("caf\xe9"), std::string::npos) << "a raw byte reached the messages";
  std::string state;
  ASSERT_NO_THROW(state = ViewerStateJson(session.View->State()).dump());
  EXPECT_NE(state.find("caf\\\\xe9/cloudvis-screenshot-001.png"), std::string::npos) << state;
}

TEST(Interaction, ShippedPresetsLoad)
{
  const std::string directory = FreshDirectory("presets");
  Session session(directory);
  session.View->PressKey("p", 'p');
  const ViewerState state = session.View->State();
  EXPECT_FALSE(state.Preset.empty()) << session.Messages.str();
  session.View->PressKey("P", 'P');
  const nlohmann::json preset = ReadJson(directory + "/cloudvis-preset-001.json");
  EXPECT_EQ(preset["opacity"].size(), state.TransferFunction.Opacity.size());
}

TEST(Interaction, UnwritableScreenshotDirectoryKeepsTheSession)
{
  const std::string directory = FreshDirectory("unwritable") + "/missing";
  Session session(directory);
  session.View->PressKey("s", 's');
  session.View->PressKey("w", 'w');
  session.View->PressKey("m", 'm');
  const ViewerState state = session.View->State();
  EXPECT_EQ(state.Lighting, LightingModel::Derivative);
  EXPECT_TRUE(state.SavedFiles.empty());
  const std::string messages = session.Messages.str();
  EXPECT_NE(
    messages.find("cloudvis: error: " + directory + "/cloudvis-screenshot-001.png: cannot write"),
    std::string::npos)
    << messages;
  EXPECT_NE(messages.find("cloudvis-view-001.json: cannot write"), std::string::npos) << messages;
}

TEST(Interaction, KeysChangeStepResolutionLightAndHistogram)
{
  const std::string directory = FreshDirectory("keys");
  Session session(directory);
  const ViewerState before = session.View->State();
  session.View->PressKey("plus", '+');
  session.View->PressKey("bracketleft", '[');
  session.View->PressKey("Left", 0);
  session.View->PressKey("Up", 0);
  session.View->PressKey("l", 'l');
  session.View->PressKey("f", 'f');
  const ViewerState after = session.View->State();
  EXPECT_NEAR(after.Step, 1.25 * 4.0 / 47.0, 1e-9);
  EXPECT_DOUBLE_EQ(after.ResolutionScale, 0.875);
  EXPECT_NE(after.FirstLightPosition, before.FirstLightPosition);
  EXPECT_FALSE(after.LogHistogram);
  // f: the function's ends sit on the field's range.
  EXPECT_DOUBLE_EQ(after.TransferFunction.Opacity.front()[0], after.EditorRange[0]);
  EXPECT_DOUBLE_EQ(after.TransferFunction.Opacity.back()[0], after.EditorRange[1]);
  // The saved scene carries them.
  const Scene scene = session.View->CurrentScene();
  const nlohmann::json saved = session.View->CurrentSceneJson();
  EXPECT_DOUBLE_EQ(saved["render"]["step"].get<double>(), after.Step);
  EXPECT_DOUBLE_EQ(saved["render"]["resolution_scale"].get<double>(), 0.875);
  EXPECT_EQ(saved["lights"][0]["position"][0].get<double>(), double(scene.Lights[0].Position.x));
  // It reads back as a valid scene.
  EXPECT_NO_THROW(SceneFromDocument(saved, "saved", ""));
  // No EXR below resolution scale 1: the PNG is written and the message says why.
  session.View->PressKey("s", 's');
  EXPECT_TRUE(Exists(directory + "/cloudvis-screenshot-001.png"));
  EXPECT_FALSE(Exists(directory + "/cloudvis-screenshot-001.exr"));
}

TEST(Interaction, CommandLinePlaySavesTheSceneOnExit)
{
  const std::string directory = FreshDirectory("command-line");
  const std::string saved = directory + "/end.json";
  const support::CommandResult run = support::RunCloudvis({ "view",
    "--set",
    "field.dimensions=32",
    "--size",
    "320x240",
    "--output-dir",
    directory,
    "--play",
    Recordings + "/keys-lighting.log",
    "--save-scene-on-exit",
    saved });
  ASSERT_EQ(run.Status, 0) << run.Err;
  EXPECT_NE(run.Out.find("wrote " + saved), std::string::npos);
  const nlohmann::json scene = ReadJson(saved);
  EXPECT_EQ(scene["render"]["lighting"], "derivative");
  EXPECT_EQ(scene["render"]["size"], nlohmann::json({ 320, 180 }));
  EXPECT_TRUE(Exists(directory + "/cloudvis-view-001.json"));
}

TEST(Interaction, RecordedSessionsReplayToTheSameState)
{
  // --record writes what the interactor saw; replaying that file into a fresh viewer must leave
  // it in the same state: the lighting model cycled by a key and the camera turned by a drag.
  const std::string directory = FreshDirectory("record");
  const std::string recording = directory + "/session.log";
  ViewerState recorded;
  nlohmann::json recordedScene;
  {
    ViewerOptions options;
    options.WindowSize = { { 480, 400 } };
    options.OutputDirectory = directory;
    options.RecordFile = recording;
    std::ostringstream messages;
    options.Messages = &messages;
    const Scene scene = SmallScene();
    Viewer view(scene, ProduceField(scene), options);
    view.PlayString("# StreamVersion 1.1\n"
                    "KeyPressEvent 240 250 0 109 1 m\n"
                    "MouseMoveEvent 200 200 0 0 0 0\n"
                    "LeftButtonPressEvent 200 200 0 0 0 0\n"
                    "MouseMoveEvent 230 210 0 0 0 0\n"
                    "MouseMoveEvent 260 220 0 0 0 0\n"
                    "LeftButtonReleaseEvent 260 220 0 0 0 0\n");
    recorded = view.State();
    recordedScene = view.CurrentSceneJson();
  } // the viewer stops recording and closes the file
  const std::string text = support::ReadText(recording);
  ASSERT_NE(text.find("KeyPressEvent"), std::string::npos) << text;
  ASSERT_NE(text.find("LeftButtonPressEvent"), std::string::npos) << text;
  EXPECT_EQ(recorded.Lighting, LightingModel::Derivative);

  Session replay(FreshDirectory("record-replay"));
  replay.View->PlayFile(recording);
  EXPECT_EQ(replay.View->State().Lighting, recorded.Lighting);
  const nlohmann::json replayedScene = replay.View->CurrentSceneJson();
  const nlohmann::json defaultCamera =
    Session(FreshDirectory("record-none")).View->CurrentSceneJson()["camera"];
  EXPECT_NE(recordedScene["camera"]["position"], defaultCamera["position"])
    << "the drag turned the camera";
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(replayedScene["camera"]["position"][c].get<double>(),
      recordedScene["camera"]["position"][c].get<double>(),
      1e-6)
      << c;
  }
}

// The key and mouse lists of docs/viewer.md are the viewer's tables (`cloudvis view --keys` and
// `--mouse` print them): a binding added, removed or described differently in one and not the
// other fails here.
TEST(Interaction, KeyAndMouseTablesMatchTheDocs)
{
  const std::string document =
    support::ReadText(std::string(CLOUDVIS_SOURCE_DIR) + "/docs/viewer.md");
  ASSERT_FALSE(document.empty());
  for (const auto& [name, table] :
    { std::pair<std::string, std::string>{ "keys", ViewerKeysMarkdown() },
      std::pair<std::string, std::string>{ "mouse", ViewerMouseMarkdown() } })
  {
    const std::string begin =
      "<!-- " + name + ": generated by `cloudvis view --" + name + "` -->\n";
    const std::string end = "<!-- end of " + name + " -->";
    const size_t from = document.find(begin);
    const size_t to = document.find(end);
    ASSERT_NE(from, std::string::npos) << "docs/viewer.md lost the marker " << begin;
    ASSERT_NE(to, std::string::npos) << "docs/viewer.md lost the marker " << end;
    EXPECT_EQ(document.substr(from + begin.size(), to - from - begin.size()), table)
      << "docs/viewer.md and the " << name << " table disagree: paste the output of "
      << "`cloudvis view --" << name << "` between the markers";
  }
}

// At every window size the color strip is tall enough to see and grab its points, and both
// charts put a density at the same x.
TEST(Interaction, EditorStripAndAxesAtEverySize)
{
  for (const std::array<int, 2> size : { std::array<int, 2>{ { 320, 240 } },
         std::array<int, 2>{ { 480, 400 } },
         std::array<int, 2>{ { 800, 800 } },
         std::array<int, 2>{ { 1400, 1000 } } })
  {
    Session session(FreshDirectory("editor-size"), SmallScene(), size);
    const ViewerState state = session.View->State();
    const double strip = state.ColorStripPixels[3] - state.ColorStripPixels[1];
    EXPECT_GE(strip, 14.0) << size[0] << "x" << size[1];
    // Density 0 and 1: the first and last points of both functions.
    EXPECT_NEAR(state.OpacityPointPixels.front()[0], state.ColorPointPixels.front()[0], 0.01)
      << size[0] << "x" << size[1];
    EXPECT_NEAR(state.OpacityPointPixels.back()[0], state.ColorPointPixels.back()[0], 0.01)
      << size[0] << "x" << size[1];
    // The color points sit inside the strip.
    EXPECT_GT(state.ColorPointPixels.front()[1], state.ColorStripPixels[1]);
    EXPECT_LT(state.ColorPointPixels.front()[1], state.ColorStripPixels[3]);
  }
}

// Key 4: the 3D view and three slice views, each a quarter of the views' area; the slice views
// show the field (not a blank viewport).
TEST(Interaction, FourViewLayoutShowsTheSlices)
{
  const std::string directory = FreshDirectory("four-views");
  Session session(directory);
  session.View->PressKey("4", '4');
  const ViewerState state = session.View->State();
  EXPECT_TRUE(state.FourViews);
  std::map<std::string, std::array<int, 4>> viewports(
    state.Viewports.begin(), state.Viewports.end());
  for (const char* name : { "3d", "axial", "coronal", "sagittal" })
  {
    ASSERT_EQ(viewports.count(name), 1u) << name;
    EXPECT_EQ(viewports[name][2] - viewports[name][0], 240) << name;
    EXPECT_EQ(viewports[name][3] - viewports[name][1], 150) << name;
  }
  EXPECT_EQ(state.ViewSize[0], 240);
  EXPECT_TRUE(state.ColorBarVisible);
  session.View->SaveWindowImage(directory + "/window.png");
  const Pixels window = ReadPng(directory + "/window.png");
  // The axial view shows its own picture: its corner is its background, (0.08, 0.08, 0.1) in
  // 8-bit levels, and its middle the slice, whose colors (blue-yellow: dark blue for empty
  // space) are all far bluer than that background.
  const auto& axial = viewports["axial"];
  const auto pixel = [&](int x, int y, int c) { return window.Level(x, y, c); };
  EXPECT_NEAR(pixel(axial[0] + 3, axial[1] + 3, 0), 20.4, 1.0);
  EXPECT_NEAR(pixel(axial[0] + 3, axial[1] + 3, 2), 25.5, 1.0);
  int slice = 0, count = 0;
  for (int y = axial[1] + 40; y < axial[3] - 40; ++y)
  {
    for (int x = axial[0] + 80; x < axial[2] - 80; ++x, ++count)
    {
      slice += pixel(x, y, 2) > 45.0 ? 1 : 0;
    }
  }
  EXPECT_GT(double(slice) / count, 0.9) << "the axial view does not show its slice";
  session.View->PressKey("4", '4');
  EXPECT_FALSE(session.View->State().FourViews);
  EXPECT_EQ(session.View->State().ViewSize[0], 480);
}

// A preset, then R (the scene's function), undo and redo between them.
TEST(Interaction, ResetUndoAndRedoTheTransferFunction)
{
  Session session(FreshDirectory("undo"));
  const TransferFunctionSpec scene = session.View->State().TransferFunction;
  session.View->PressKey("p", 'p');
  const TransferFunctionSpec preset = session.View->State().TransferFunction;
  ASSERT_NE(preset.Color, scene.Color) << session.Messages.str();
  session.View->PressKey("R", 'R');
  EXPECT_EQ(session.View->State().TransferFunction.Color, scene.Color);
  session.View->PressKey("z", 26, true);
  EXPECT_EQ(session.View->State().TransferFunction.Color, preset.Color);
  session.View->PressKey("z", 26, true);
  EXPECT_EQ(session.View->State().TransferFunction.Color, scene.Color);
  EXPECT_EQ(session.View->State().UndoDepth, 0);
  session.View->PressKey("y", 25, true);
  EXPECT_EQ(session.View->State().TransferFunction.Color, preset.Color);
  EXPECT_EQ(session.View->State().RedoDepth, 1);
}

// c cycles the slice colors: gray slices are gray; in "transfer function" colors a density has
// its transfer function's color (the default's run from (0.55, 0.58, 0.65) at density 0 to white:
// light, never less blue than red), where blue-yellow is dark blue for empty space.
TEST(Interaction, SliceColorsCycleToTheTransferFunction)
{
  const std::string directory = FreshDirectory("slice-colors");
  Session session(directory);
  session.View->PressKey("4", '4');
  // The share of the axial view's middle whose pixels pass `test`: 0.947 at most, because the
  // crosshair lines cross it.
  const auto share = [&](const std::function<bool(double, double, double)>& test)
  {
    session.View->SaveWindowImage(directory + "/window.png");
    const Pixels window = ReadPng(directory + "/window.png");
    const ViewerState state = session.View->State();
    std::map<std::string, std::array<int, 4>> viewports(
      state.Viewports.begin(), state.Viewports.end());
    const auto& axial = viewports["axial"];
    int passed = 0, count = 0;
    for (int y = axial[1] + 40; y < axial[3] - 40; ++y)
    {
      for (int x = axial[0] + 80; x < axial[2] - 80; ++x, ++count)
      {
        passed += test(window.Level(x, y, 0), window.Level(x, y, 1), window.Level(x, y, 2)) ? 1 : 0;
      }
    }
    return double(passed) / count;
  };
  EXPECT_EQ(session.View->State().SliceColors, "blue-yellow");
  EXPECT_GT(share([](double r, double, double b) { return r < 60.0 && b > r + 20.0; }), 0.5);
  session.View->PressKey("c", 'c');
  EXPECT_EQ(session.View->State().SliceColors, "gray");
  EXPECT_GT(share([](double r, double g, double b)
              { return std::abs(r - g) <= 1.0 && std::abs(g - b) <= 1.0; }),
    0.9);
  session.View->PressKey("c", 'c');
  session.View->PressKey("c", 'c');
  EXPECT_EQ(session.View->State().SliceColors, "transfer function");
  EXPECT_GT(
    share([](double r, double g, double b) { return r >= 130.0 && g >= r && b >= g; }), 0.9);
  session.View->PressKey("c", 'c');
  EXPECT_EQ(session.View->State().SliceColors, "blue-yellow");
}

// The share of a glyph's height that its outer column covers: the leftmost inked column for
// '[' and '(' (`left`), the rightmost for ']' and ')'. A square bracket's stem runs into its
// corners, top to bottom (about 1); a round one's outermost ink is its middle only.
double OuterColumnCover(vtkTextProperty* text, const std::string& glyph, bool left)
{
  vtkNew<vtkImageData> image;
  int size[2] = { 0, 0 };
  if (!vtkTextRenderer::GetInstance()->RenderString(text, vtkStdString(glyph), image, size, 72))
  {
    return -1.0;
  }
  const int* dims = image->GetDimensions();
  const auto inked = [&](int x, int y)
  { return static_cast<unsigned char*>(image->GetScalarPointer(x, y, 0))[3] > 128; };
  int x0 = dims[0], x1 = -1, y0 = dims[1], y1 = -1;
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      if (inked(x, y))
      {
        x0 = std::min(x0, x);
        x1 = std::max(x1, x);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
      }
    }
  }
  if (x1 < 0)
  {
    return -1.0;
  }
  int covered = 0;
  for (int y = y0; y <= y1; ++y)
  {
    // Within a pixel of the outer edge: antialiasing may leave the very edge half covered.
    covered += inked(left ? x0 : x1, y) || inked(left ? x0 + 1 : x1 - 1, y) ? 1 : 0;
  }
  return double(covered) / double(y1 - y0 + 1);
}

// The viewer's texts draw square brackets as square (VTK's embedded Arial, the default font,
// draws them round, so "[0, 4.58]" read as an open interval), rendered by the text renderer that
// draws the viewer's text actors; round brackets stay round, so the measure tells them apart.
TEST(Interaction, ViewerFontDrawsSquareBrackets)
{
  vtkNew<vtkTextProperty> text;
  UseViewerFont(text);
  text->SetFontSize(48);
  EXPECT_GT(OuterColumnCover(text, "[", true), 0.9) << "'[' is not square";
  EXPECT_GT(OuterColumnCover(text, "]", false), 0.9) << "']' is not square";
  EXPECT_LT(OuterColumnCover(text, "(", true), 0.8) << "the measure cannot tell ( from [";
  EXPECT_LT(OuterColumnCover(text, ")", false), 0.8) << "the measure cannot tell ) from ]";
}

} // namespace
} // namespace cloudvis
