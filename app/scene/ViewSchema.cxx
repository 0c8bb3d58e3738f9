// The "view" section of the scene schema (Scene.h's ViewSpec): what `cloudvis view` restores
// besides the picture (layout, slices, window/level, slice colors, legends). Kept apart from
// SceneSchema.cxx, which holds the sections every command renders.
#include "SceneSchema.h"

#include <algorithm>
#include <cmath>

namespace cloudvis
{

const std::vector<std::string>& SliceColormapNames()
{
  static const std::vector<std::string> names = {
    "blue-yellow", "gray", "viridis", "transfer function"
  };
  return names;
}

namespace schema
{
namespace
{

std::vector<Name> SliceColormaps()
{
  const std::vector<std::string>& texts = SliceColormapNames();
  const char* const help[] = { "dark blue through teal to pale yellow",
    "black to white",
    "matplotlib's viridis",
    "the transfer function's own colors, sampled over the window" };
  std::vector<Name> names;
  for (size_t i = 0; i < texts.size(); ++i)
  {
    names.push_back({ texts[i], int(i), help[i] });
  }
  return names;
}

// [x, y, z]: three booleans (the Boolean kind is one value).
void ReadSlices(const Context& c, const json& v, const std::string& key, ViewSpec& view)
{
  const bool booleans = v.is_array() && v.size() == 3 &&
    std::all_of(v.begin(), v.end(), [](const json& b) { return b.is_boolean(); });
  if (!booleans)
  {
    c.Fail(key,
      "expected [x, y, z], 3 booleans (true: the slice across that axis is shown), got " +
        Describe(v));
  }
  for (size_t i = 0; i < 3; ++i)
  {
    view.Slices[i] = v[i].get<bool>();
  }
}

std::string NonZeroNormal(ObliqueSpec& oblique)
{
  // Its direction must be computable: scaled to its largest component, its length is finite and
  // not zero (a normal of 1e200s would overflow to infinity if squared as it is).
  const auto& n = oblique.Normal;
  const double largest = std::max({ std::abs(n[0]), std::abs(n[1]), std::abs(n[2]) });
  return largest > 0.0 && std::isfinite(largest) ? "" : "the normal must not be zero";
}

std::string PositiveWindow(ViewSpec& view)
{
  return view.WindowLevel ? WindowLevelProblem((*view.WindowLevel)[0], (*view.WindowLevel)[1]) : "";
}

} // namespace

const Keys<ObliqueSpec>& ObliqueKeys()
{
  using O = ObliqueSpec;
  static const Keys<O> keys = {
    { "visible", Boolean(), &O::Visible, "the oblique slice is shown" },
    { "origin",
      NumbersIn(3, AnyNumber).In("world units").DefaultIs("the centre of the field"),
      &O::Origin,
      "a point of the plane" },
    { "normal", NumbersIn(3, AnyNumber), &O::Normal, "not zero", ~0u, NonZeroNormal },
  };
  return keys;
}

const Keys<ViewSpec>& ViewKeys()
{
  using V = ViewSpec;
  static const Keys<V> keys = {
    { "layout",
      ChoiceOf({ { "3d", int(ViewLayout::ThreeD), "the 3D view alone" },
        { "four", int(ViewLayout::Four), "the 3D view and the three slice views" } }),
      &V::Layout,
      "the viewer's layout (`--layout` overrides it)" },
    { "slices",
      CustomValue("3 booleans `[x, y, z]`").DefaultIs("`[false, false, false]`"),
      ReadSlices,
      [](const V& view) { return ToJson(view.Slices); },
      "which of the slices across x, y and z are shown" },
    { "slice_position",
      NumbersIn(3, AnyNumber).In("world units").DefaultIs("the centre of the field"),
      &V::SlicePosition,
      "where the three slices cut, each on the voxel layer nearest to it" },
    { "oblique",
      CustomValue("object `{\"visible\", \"origin\", \"normal\"}`").DefaultIs("hidden"),
      [](const Context& c, const json& v, const std::string& k, V& view)
      { ReadObject(c, v, k, ObliqueKeys(), view.Oblique); },
      [](const V& view) { return WriteObject(ObliqueKeys(), view.Oblique); },
      "the oblique slice",
      Inside(ObliqueKeys) },
    { "window_level",
      NumbersIn(2, AnyNumber, "[window, level]").DefaultIs("the field's range"),
      &V::WindowLevel,
      "the slices' colors span density `level - window/2` to `level + window/2`; window > 0",
      ~0u,
      PositiveWindow },
    { "slice_colors", ChoiceOf(SliceColormaps()), &V::SliceColors, "how the slices color density" },
    { "legends", Boolean(), &V::Legends, "the color legends are shown (key b)" },
  };
  return keys;
}

Key<Scene> ViewSection()
{
  return Key<Scene>(
    "view",
    CustomValue("object").DefaultIs("none"),
    [](const Context& c, const json& v, const std::string& k, Scene& s)
    {
      ViewSpec view;
      ReadObject(c, v, k, ViewKeys(), view);
      s.View = view;
    },
    [](const Scene& s) { return s.View ? WriteObject(ViewKeys(), *s.View) : json(); },
    "how `cloudvis view` shows the scene: layout, slices, window/level, slice colors, legends; "
    "`render` ignores it ([below](#the-view-section))",
    Inside(ViewKeys));
}

} // namespace schema

std::string WindowLevelProblem(double window, double level)
{
  if (!(window > 0.0))
  {
    return "the window (the first number) must be greater than 0";
  }
  if (!std::isfinite(level - 0.5 * window) || !std::isfinite(level + 0.5 * window))
  {
    return "level -+ window / 2 must be finite numbers";
  }
  return "";
}

} // namespace cloudvis
