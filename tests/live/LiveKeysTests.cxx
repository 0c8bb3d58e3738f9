// Live tests of the viewer's keys, help and messages as ParaView and 3D Slicer users expect them
// (issue 24): Esc closes and cancels but never quits, q and the window manager's close ask before
// losing unsaved changes, the help lists the mouse too, brackets look like brackets, refinement
// does not wait for a message to fade, a screenshot says it is saving, the editor's tooltip
// leaves with the pointer, and undo covers the camera and the lighting. The real binary on its
// own Xvfb, real X input (LiveSession.h); checks read the state file and the window's pixels.
#include "LiveHelpers.h"
#include "LiveSession.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace cloudvis
{
namespace live
{
namespace
{
using json = nlohmann::json;

const std::string Cloudvis = support::CloudvisBinary();

// The viewer still runs a second after the input: it did not quit.
void ExpectRunning(LiveSession& session, const std::string& after)
{
  EXPECT_EQ(session.WaitForExit(1.0), -1) << "the viewer quit after " << after;
}

// Esc closes the help, cancels typing (the point keeps its values) and, with nothing open, only
// says what it does: the viewer never quits on Esc, even with unsaved changes.
TEST(LiveKeys, EscClosesTheHelpAndCancelsTypingButNeverQuits)
{
  LiveSession session(Cloudvis, Arguments());
  const json start = session.WaitUntilConverged();
  session.Key("h");
  session.WaitFor([](const json& s) { return s["help_visible"].get<bool>(); }, "the help");
  session.Key("Escape");
  session.WaitFor(
    [](const json& s) { return !s["help_visible"].get<bool>(); }, "Esc to close the help");
  ExpectRunning(session, "Esc closed the help");

  SelectInnerOpacityPoint(session, start);
  session.Keys({ "Return", "0", "period", "5" });
  session.WaitFor([](const json& s) { return s["editor"]["typing"].get<bool>(); }, "typing");
  session.Key("Escape");
  const json cancelled = session.WaitFor(
    [](const json& s) { return !s["editor"]["typing"].get<bool>(); }, "Esc to cancel typing");
  EXPECT_EQ(cancelled["transfer_function"], start["transfer_function"]);
  ExpectRunning(session, "Esc cancelled typing");

  session.Key("m"); // an unsaved change
  session.Key("Escape");
  session.WaitFor(
    [](const json& s) { return Said(s, "nothing to close"); }, "Esc with nothing open to say so");
  ExpectRunning(session, "Esc with nothing open");
}

// With unsaved changes (a camera drag) the first q asks, in the message line, and a second q
// quits; after w saves the scene, one q quits at once.
TEST(LiveKeys, QuitAsksOnceWhenThereAreUnsavedChanges)
{
  LiveSession session(Cloudvis, Arguments());
  const json start = session.WaitUntilConverged();
  EXPECT_FALSE(start["unsaved_changes"].get<bool>());
  const auto center = session.Center("3d");
  session.Drag(1, { { center[0] - 20, center[1] } }, { { center[0] + 20, center[1] } });
  session.WaitFor([](const json& s) { return s["unsaved_changes"].get<bool>(); },
    "the camera drag to be an unsaved change");
  session.Key("q");
  session.WaitFor([](const json& s)
    { return Said(s, "unsaved changes: w saves the scene, q again quits"); },
    "q to ask first");
  ExpectRunning(session, "the first q");
  session.Key("q");
  EXPECT_EQ(session.WaitForExit(), 0) << "the second q did not quit\n" << session.Stderr();
}

TEST(LiveKeys, QuitAtOnceWithoutUnsavedChanges)
{
  LiveSession session(Cloudvis, Arguments());
  session.WaitUntilConverged();
  session.Key("m");
  session.WaitFor(
    [](const json& s) { return s["unsaved_changes"].get<bool>(); }, "m to be an unsaved change");
  session.Key("w");
  session.WaitFor([](const json& s)
    { return s["saved_files"].size() == 1 && !s["unsaved_changes"].get<bool>(); },
    "w to save the scene");
  session.Key("q");
  EXPECT_EQ(session.WaitForExit(10.0), 0) << "q after w did not quit at once\n" << session.Stderr();
}

// The window manager's close button follows q's rule.
TEST(LiveKeys, ClosingTheWindowAsksLikeQ)
{
  LiveSession session(Cloudvis, Arguments());
  session.WaitUntilConverged();
  session.Key("Right"); // the light turns: an unsaved change
  session.WaitFor([](const json& s) { return s["unsaved_changes"].get<bool>(); },
    "the light to be an unsaved change");
  session.Close();
  session.WaitFor([](const json& s) { return Said(s, "unsaved changes"); }, "closing to ask first");
  ExpectRunning(session, "the first close");
  session.Close();
  EXPECT_EQ(session.WaitForExit(), 0) << "the second close did not quit\n" << session.Stderr();
}

// h shows the keys, h again the mouse bindings in 3D, h again those of the slice views and the
// editor, h again nothing; each page fits the views of a 480 x 400 window in a font of at least 8
// points, and each page draws a different text from the one before.
TEST(LiveKeys, HelpPagesShowTheKeysThenTheMouseAndFitTheWindow)
{
  LiveSession session(Cloudvis, Arguments());
  const json start = session.WaitUntilConverged();
  const json view = start["viewports"]["3d"];
  std::vector<support::Image> drawn;
  for (const char* page : { "keys", "mouse-3d", "mouse-2d" })
  {
    session.Key("h");
    const json shown = session.WaitFor([&](const json& s)
      { return s["help_page"] == page && s["frames_rendered"] > start["frames_rendered"]; },
      std::string("the help's ") + page + " page");
    ASSERT_FALSE(shown["help_boxes"].empty()) << page;
    EXPECT_GE(shown["help_font_size"].get<int>(), 8) << page << " page: too small to read";
    // The legends would show through the help's boxes.
    EXPECT_FALSE(shown["legend_visible"].get<bool>()) << page << " page: the legend shows";
    for (const json& box : shown["help_boxes"])
    {
      EXPECT_GE(box[0].get<int>(), view[0].get<int>()) << page << " " << box;
      EXPECT_GE(box[1].get<int>(), view[1].get<int>()) << page << " " << box;
      EXPECT_LE(box[2].get<int>(), view[2].get<int>()) << page << " " << box;
      EXPECT_LE(box[3].get<int>(), view[3].get<int>()) << page << " " << box;
    }
    session.WaitFor([](const json& s) { return s["converged"].get<bool>(); }, "a still picture");
    drawn.push_back(session.Pixels(
      { { view[0].get<int>(), view[1].get<int>(), view[2].get<int>(), view[3].get<int>() } }));
  }
  EXPECT_GT(support::Compare(drawn[0], drawn[1]).MeanLevels(), 2.0)
    << "the 3D mouse page draws what the keys page drew";
  EXPECT_GT(support::Compare(drawn[1], drawn[2]).MeanLevels(), 2.0)
    << "the second mouse page draws what the first drew";
  session.Key("h");
  session.WaitFor([](const json& s)
    { return s["help_page"] == "" && !s["help_visible"].get<bool>() && s["legend_visible"]; },
    "the fourth h to hide the help and bring the legend back");
}

// After a key that redraws the cloud the picture refines to convergence at once, while the key's
// message is still on screen: the message and its fading never hold the refinement back (it
// waited for the message to fade, about 4 s, after every m, arrow, +, - or p).
TEST(LiveKeys, RefinementConvergesWhileTheMessageShows)
{
  LiveSession session(Cloudvis, Arguments());
  session.WaitUntilConverged();
  for (const char* key : { "m", "Right", "plus" })
  {
    const json before = session.State();
    session.Key(key);
    const json converged = session.WaitFor(
      [&](const json& s)
      {
        return s["keys"].size() > before["keys"].size() && s["converged"].get<bool>() &&
          !s["keys"].back()["shown_at"].is_null();
      },
      std::string("the picture after ") + key + " to converge");
    const double handled = converged["keys"].back()["handled_at"].get<double>();
    EXPECT_FALSE(converged["message"].get<std::string>().empty())
      << key << ": converged only once the message had faded, "
      << converged["last_frame_at"].get<double>() - handled << " s after the key";
    EXPECT_LT(converged["last_frame_at"].get<double>() - handled, 0.5 * 4.0)
      << key << ": took half the message's time to converge";
  }
}

// The screenshot files in the session's output folder.
int Screenshots(const LiveSession& session)
{
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(session.WorkDirectory()))
  {
    count += entry.path().filename().string().rfind("cloudvis-screenshot-", 0) == 0 ? 1 : 0;
  }
  return count;
}

// s says "saving" on screen before the capture's work (64 frames here, 2 to 3 s) has written
// anything, and the notice stays on screen while it works; "saved FILE" follows once the files
// exist.
TEST(LiveKeys, ScreenshotSaysSavingBeforeTheWork)
{
  LiveSession session(Cloudvis, Arguments({ "--set", "render.accumulate=64" }));
  const json start = session.WaitUntilConverged();
  const json view = start["viewports"]["3d"];
  // The message line's corner of the 3D view.
  const std::array<int, 4> corner = {
    { view[0].get<int>(), view[3].get<int>() - 24, view[0].get<int>() + 120, view[3].get<int>() }
  };
  const auto quiet = session.Pixels(corner);
  session.Key("s");
  const json notice = session.WaitFor(
    [](const json& s) { return Said(s, "saving") || Said(s, "saved "); }, "the saving notice");
  if (Said(notice, "saving")) // else the work was done before a state could be read
  {
    EXPECT_TRUE(notice["saved_files"].empty()) << "the notice came after the files";
    // A moment into the work (the capture renders frames of its own, without the texts), the
    // notice is still what the window shows. Only while the capture lasts (2 to 3 s on llvmpipe,
    // maybe less than the pause on a GPU): the files not there yet say it did.
    Pause(0.2);
    const auto during = session.Pixels(corner);
    if (Screenshots(session) == 0)
    {
      EXPECT_GT(support::Compare(quiet, during).MeanLevels(), 5.0)
        << "the notice is not on screen while the screenshot is taken";
    }
  }
  const json saved =
    session.WaitFor([](const json& s) { return Said(s, "saved "); }, "the saved message");
  const auto& messages = saved["messages"];
  ASSERT_GE(messages.size(), 2u);
  EXPECT_NE(messages[messages.size() - 2].get<std::string>().find("saving"), std::string::npos)
    << "no saving notice before " << messages.back();
  EXPECT_EQ(Screenshots(session), 2); // PNG and EXR
  EXPECT_EQ(saved["saved_files"].size(), 2u);
}

// Hovering a histogram bar shows the chart's tooltip, in the dragged point's format ("density D:
// VALUE"), and it goes when the pointer leaves the editor (it stayed on screen).
TEST(LiveKeys, EditorTooltipsShareAFormatAndLeaveWithThePointer)
{
  LiveSession session(Cloudvis, Arguments());
  const json start = session.WaitUntilConverged();
  const json points = start["editor"]["opacity_point_pixels"];
  const auto first = Pixel(points[0]), last = Pixel(points[points.size() - 1]);
  // Over the histogram's middle bins, just above opacity 0, away from the curve and its points.
  const int x = (first[0] + last[0]) / 2 - 60, y = first[1] + 6;
  session.Move(x, y);
  session.Move(x + 2, y + 2);
  const json hovered = session.WaitFor([](const json& s)
    { return !s["editor"]["hover_tooltip"].get<std::string>().empty(); },
    "the histogram's tooltip");
  const std::string hover = hovered["editor"]["hover_tooltip"];
  EXPECT_EQ(hover.rfind("density ", 0), 0u) << hover;
  EXPECT_NE(hover.find(" voxels"), std::string::npos) << hover;
  session.Move(session.Center("3d")[0], session.Center("3d")[1]);
  session.WaitFor([](const json& s) { return s["editor"]["hover_tooltip"] == ""; },
    "the tooltip to go when the pointer leaves the editor");

  // The dragged point's tooltip, read while the button is held.
  const auto point = Pixel(points[points.size() - 2]);
  session.Move(point[0], point[1]);
  session.Press(1);
  session.Move(point[0] + 4, point[1] + 4);
  const json dragging = session.WaitFor([](const json& s)
    { return !s["editor"]["drag_tooltip"].get<std::string>().empty(); },
    "the drag tooltip");
  session.Release(1);
  const std::string drag = dragging["editor"]["drag_tooltip"];
  EXPECT_EQ(drag.rfind("density ", 0), 0u) << drag;
  EXPECT_NE(drag.find(": opacity "), std::string::npos) << drag;
}

void ExpectSameCamera(const json& a, const json& b, const std::string& what)
{
  for (const char* key : { "position", "focal_point", "view_up" })
  {
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(a["camera"][key][c].get<double>(), b["camera"][key][c].get<double>(), 1e-9)
        << what << ": camera " << key << "[" << c << "]";
    }
  }
}

// One history for everything, as ParaView's undo stack: a camera drag, a burst of wheel notches,
// the lighting model, the light, a slice shown and moved, and the transfer function are a step
// each, Ctrl+z takes
// them back in the reverse order (saying what it undid) and Ctrl+y redoes.
TEST(LiveKeys, UndoCoversTheCameraLightingSlicesAndTheFunction)
{
  LiveSession session(Cloudvis, Arguments());
  const json start = session.WaitUntilConverged();
  const auto center = session.Center("3d");
  const auto depth = [](const json& s) { return s["editor"]["undo_depth"].get<int>(); };
  const auto stepped = [&](int steps, const std::string& what)
  {
    return session.WaitFor([&](const json& s)
      { return depth(s) == steps && s["converged"].get<bool>(); },
      what + " to be undo step " + std::to_string(steps));
  };
  session.Drag(1, { { center[0] - 30, center[1] } }, { { center[0] + 30, center[1] + 10 } });
  const json turned = stepped(1, "the camera drag");
  for (int i = 0; i < 3; ++i)
  {
    session.Wheel(center[0], center[1], true);
  }
  const json zoomed = stepped(2, "three wheel notches");
  EXPECT_NE(zoomed["camera"]["position"], turned["camera"]["position"])
    << "the wheel moved nothing";
  session.Key("m");
  stepped(3, "m");
  session.Key("Right");
  stepped(4, "the light's turn");
  session.Key("z");
  const json sliced = stepped(5, "the slice across z");
  // A middle drag on the slice (it faces the camera) moves it: a step of its own.
  session.Drag(2, { { center[0] + 60, center[1] + 40 } }, { { center[0] + 60, center[1] + 80 } });
  const json moved = stepped(6, "the slice's move");
  ASSERT_NE(moved["slices"]["index"][2], sliced["slices"]["index"][2]);
  session.Key("f");
  const json edited = stepped(7, "the fit of the transfer function");
  ASSERT_NE(edited["transfer_function"], start["transfer_function"]);

  const auto undo = [&](int left, const std::string& what)
  {
    session.Key("z", true);
    const json s = session.WaitFor(
      [&](const json& t) { return depth(t) == left; }, "Ctrl+z to undo the " + what);
    EXPECT_TRUE(Said(s, "undone: " + what)) << s["messages"].back();
    return s;
  };
  EXPECT_EQ(undo(6, "transfer function")["transfer_function"], start["transfer_function"]);
  EXPECT_EQ(undo(5, "slices")["slices"]["index"][2], sliced["slices"]["index"][2]);
  EXPECT_FALSE(undo(4, "slices")["slices"]["visible"][2].get<bool>());
  EXPECT_EQ(undo(3, "lighting")["first_light_position"], start["first_light_position"]);
  EXPECT_EQ(undo(2, "lighting")["lighting"], start["lighting"]);
  ExpectSameCamera(undo(1, "camera"), turned, "the wheel burst undone");
  const json back = undo(0, "camera");
  ExpectSameCamera(back, start, "the drag undone");
  EXPECT_EQ(back["editor"]["redo_depth"].get<int>(), 7);
  session.Key("y", true);
  const json redone =
    session.WaitFor([&](const json& s) { return depth(s) == 1; }, "Ctrl+y to redo the drag");
  ExpectSameCamera(redone, turned, "the drag redone");
}

} // namespace
} // namespace live
} // namespace cloudvis
