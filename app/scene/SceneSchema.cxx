// The scene schema: each key of a scene file is one entry below, with its name, its type and
// range (the filters' own limits where a filter checks the parameter), the member it fills and
// its help text; its default is that member's value in a default-constructed Scene. A new key is
// a new entry. This file is the declarative table alone: what is more than a list of keys (a
// field from a file or not, a shape list, a transfer-function preset, the typed objects whose
// "type" decides which keys they take) is read and written by SceneSchemaReaders.cxx, whose
// functions the entries name.
#include "SceneSchemaReaders.h"

#include "FieldIO.h"
#include "SceneField.h"

#include "CloudMarchUniforms.h" // FloatLimit, MaxSamplesPerRay
#include "CloudTransferTable.h" // MaxTransferDensity, MinUnitDistance

#include <cmath>
#include <limits>

namespace cloudvis
{
namespace schema
{
const std::vector<Name>& ShapeTypes()
{
  static const std::vector<Name> names = NamesOf<ShapeType>({ { "sphere", ShapeType::Sphere },
    { "box", ShapeType::Box },
    { "torus", ShapeType::Torus },
    { "cross", ShapeType::Cross },
    { "capsule", ShapeType::Capsule } });
  return names;
}

const std::vector<Name>& BackgroundTypes()
{
  static const std::vector<Name> names = {
    { "solid", int(BackgroundType::Solid), "one color" },
    { "gradient",
      int(BackgroundType::Gradient),
      "a vertical gradient, `bottom` at the bottom edge, `top` at the top (VTK's gradient "
      "background)" },
    { "sky", int(BackgroundType::Sky), "the article's sky, below" },
  };
  return names;
}

// As the flag vtkLight and cloudvis::Light call Positional.
const std::vector<Name>& LightTypes()
{
  static const std::vector<Name> names = {
    { "directional",
      0,
      "parallel light from `position` toward `focal_point`, the same everywhere" },
    { "point", 1, "light from `position` in all directions" },
  };
  return names;
}

namespace
{

// The lighting models by the one table of their names (CloudLightingParameters.h).
const std::vector<Name>& LightingModels()
{
  static const std::vector<Name> names = NamesOfTable(LightingModelTable());
  return names;
}
} // namespace

const Keys<FieldSpec>& FieldKeys()
{
  static const Keys<FieldSpec> keys = []
  {
    Keys<FieldSpec> all = FieldFileKeys();
    all.insert(all.end(), GeneratedFieldKeys().begin(), GeneratedFieldKeys().end());
    all.insert(all.end(), FieldUnitKeys().begin(), FieldUnitKeys().end());
    return all;
  }();
  return keys;
}

// Keys of both kinds of field: what its values and world units mean (FieldUnits.h). Each is
// optional: absent, the file's declaration applies, else the default.
const Keys<FieldSpec>& FieldUnitKeys()
{
  using F = FieldSpec;
  using U = FieldUnits;
  static const Keys<F> keys = {
    { "quantity",
      ChoiceOf({ { "density",
                   int(FieldQuantity::Density),
                   "dimensionless; the transfer function says what it looks like" },
                 { "lwc", int(FieldQuantity::Lwc), "liquid water content in g/m^3" } })
        .DefaultIs("the file's, else `density`"),
      Nested(&F::Units, &U::Quantity),
      "what the values are: `info` reports the statistics in its units, and "
      "`transfer_function.extinction` `\"droplets\"` derives the extinction from it" },
    { "length_unit",
      ChoiceOf({ { "none", int(LengthUnit::None), "world units only" },
                 { "m", int(LengthUnit::Metre), "metres" },
                 { "km", int(LengthUnit::Kilometre), "kilometres" } })
        .DefaultIs("the file's, else `none`"),
      Nested(&F::Units, &U::Length),
      "how long one world unit (of `bounds`, a file's spacing and origin) is" },
    { "up",
      ChoiceOf({ { "x", 0, "" }, { "y", 1, "" }, { "z", 2, "" } })
        .DefaultIs("the file's, else `y`"),
      Nested(&F::Units, &U::Up),
      "the vertical axis of the lattice, for `info`'s cloud fraction per height, base, top and "
      "liquid water path; cloudvis's generated fields have y up, and the default camera and lights "
      "turn to "
      "the field's up" },
    { "effective_radius",
      NumberIn(Range{ 1e-3, 1e6 }).In("micrometres").DefaultIs("the file's, else `10`"),
      Nested(&F::Units, &U::EffectiveRadius),
      "the droplets' effective radius r_e of an lwc field: extinction = 3 lwc / (2 rho_w r_e); "
      "also the droplets' phase's unless `render.march.effective_radius` is given" },
    { "droplet_number",
      NumberIn(Range{ DropletNumberMin, DropletNumberMax })
        .In("droplets per cm^3")
        .DefaultIs("the file's, else none"),
      Nested(&F::Units, &U::DropletNumber),
      "the droplets' number concentration N of an lwc field: their effective radius grows with "
      "the liquid water, r_e = (3 lwc / (4 pi rho_w k N))^(1/3) with k = 0.8 (Martin et al. "
      "1994), so the extinction grows as lwc^(2/3); the droplets' phase takes r_e at the cloud's "
      "mean lwc. Refused with `effective_radius`" },
  };
  return keys;
}

const Keys<FieldSpec>& FieldFileKeys()
{
  using F = FieldSpec;
  using R = FieldReadOptions;
  static const Keys<F> keys = {
    { "file",
      Path("the path of a field file (" + FieldFileExtensions() + ", a non-empty string)")
        .DefaultIs("none"),
      &F::File,
      "path of a field file: " + FieldFormatsInWords() +
        " ([data.md](data.md)); the extension in any case (`.VTI`), or any name with `format`; a "
        "relative path is relative to the folder of the scene file (to the current directory for "
        "the default scene). A `*` in the file name opens a numbered series (`run/les_*.nc`: "
        "`les_0001.nc`, `les_0002.nc`, ...) as one field with a time step per file" },
    NameKey<F>("format",
      ChoiceOf(FieldFormatNames()).DefaultIs("by the extension"),
      Nested(&F::Read, &R::Format),
      "the file's format, whatever its extension"),
    { "array",
      NonEmptyText("the name of a grid, variable or point array (a non-empty string)")
        .DefaultIs("the format's default"),
      Nested(&F::Read, &R::Array),
      "the OpenVDB grid, NetCDF variable or `.vti`/`.pvti` point array to read; refused for a "
      "format that holds one array" },
    { "time_step",
      IntegerIn(0, std::numeric_limits<int>::max()).DefaultIs("`0`, the first"),
      Nested(&F::Read, &R::TimeStep),
      "the time step of a NetCDF file, or the file of a series, from 0; refused for a format "
      "that holds one time step" },
    { "missing",
      ChoiceOf(
        { { "refuse",
            int(MissingValueRule::Refuse),
            "a file with missing values is refused, with their count and marking" },
          { "empty", int(MissingValueRule::Empty), "missing values are read as density 0" } })
        .DefaultIs("`refuse`"),
      Nested(&F::Read, &R::Missing),
      "what the values a NetCDF file marks as missing (`_FillValue`, `missing_value`, "
      "`valid_min`, `valid_max`, `valid_range`) become: cloudvis does not guess what a missing "
      "density is, so the file is refused unless this says to read them as empty space; `info` "
      "then reports their count. NetCDF only: refused for a format that marks no values as "
      "missing" },
    { "series_gaps",
      ChoiceOf({ { "refuse",
                   int(SeriesGapRule::Refuse),
                   "a number missing from the series' progression is refused, naming the file" },
                 { "skip",
                   int(SeriesGapRule::Skip),
                   "the files there are are read as consecutive steps, and `info` names the "
                   "missing ones" } })
        .DefaultIs("`refuse`"),
      Nested(&F::Read, &R::SeriesGaps),
      "what a gap in a file series (`les_0003.nc` missing between `les_0002.nc` and "
      "`les_0004.nc`) becomes; refused for a field.file that is not a series" },
    { "air_density",
      CustomValue("`\"auto\"`, `\"standard\"`, a number (kg/m^3) or `\"variable:NAME\"`")
        .DefaultIs("`\"auto\"`"),
      [](const Context& c, const json& v, const std::string& k, F& f)
      {
        AirDensitySource& a = f.Read.AirDensity;
        const std::string prefix = "variable:";
        if (v.is_number() && v.get<double>() >= AirDensityMin && v.get<double>() <= AirDensityMax)
        {
          a = { AirDensitySource::Kind::Number, v.get<double>(), "" };
          return;
        }
        const std::string text = v.is_string() ? v.get<std::string>() : "";
        if (text == "auto" || text == "standard")
        {
          a = { text == "auto" ? AirDensitySource::Kind::Auto : AirDensitySource::Kind::Standard,
            0.0,
            "" };
          return;
        }
        if (text.size() > prefix.size() && text.compare(0, prefix.size(), prefix) == 0)
        {
          RefuseNul(c, k, text);
          a = { AirDensitySource::Kind::Variable, 0.0, text.substr(prefix.size()) };
          return;
        }
        c.Fail(k,
          "expected \"auto\", \"standard\", a number of kg/m^3 in [" + ShowValue(AirDensityMin) +
            ", " + ShowValue(AirDensityMax) + "] or \"variable:NAME\", got " + Describe(v));
      },
      [](const F& f) -> json
      {
        const AirDensitySource& a = f.Read.AirDensity;
        switch (a.From)
        {
          case AirDensitySource::Kind::Auto:
            break;
          case AirDensitySource::Kind::Standard:
            return "standard";
          case AirDensitySource::Kind::Number:
            return a.KilogramsPerCubicMetre;
          case AirDensitySource::Kind::Variable:
            return "variable:" + a.Variable;
        }
        return json();
      },
      "where the air's density comes from when a NetCDF variable holds a mixing ratio (`kg/kg`, "
      "`g/kg`): times the density it becomes a liquid water content in g/m^3. `\"auto\"` takes "
      "the file's air density variable (standard_name `air_density`, or a name such as `rho`, "
      "`rhof`, `rhobf`, `rhoref`; 3-D or a profile along the vertical), else its pressure and "
      "temperature (ideal gas, with the virtual temperature where it holds the humidity), else "
      "the ICAO standard atmosphere at the heights of the vertical axis; `\"standard\"` the "
      "standard atmosphere; a number, one density everywhere; `\"variable:NAME\"` the file's "
      "variable NAME. `info` names the source and the densities used "
      "([data.md](data.md#mixing-ratios-and-the-airs-density)); NetCDF only" },
    { "max_voxels",
      IntegerIn(1, 1LL << 62),
      Nested(&F::Read, &R::MaximumVoxels),
      "the most voxels the field may have once read (1024^3, a 4 GiB float field, by default); "
      "a file that needs more is refused, with its size, before anything is allocated. Also "
      "taken by a generated field, as the most `dimensions` `\"auto\"` may choose (at least "
      "8)" },
    { "raw",
      CustomValue("object").DefaultIs("none"),
      [](const Context& c, const json& v, const std::string& k, F& f)
      { ReadObject(c, v, k, RawKeys(), f.Read.Raw); },
      [](const F& f)
      { return f.Read.Raw.Dimensions[0] > 0 ? WriteObject(RawKeys(), f.Read.Raw) : json(); },
      "a raw file's layout ([below](#loading-a-field)); required for a raw file, refused for any "
      "other format",
      Inside(RawKeys) },
  };
  return keys;
}

const Keys<RawLayout>& RawKeys()
{
  using R = RawLayout;
  const auto types = []
  {
    std::vector<Name> names;
    for (const std::string& type : RawTypeNames())
    {
      names.push_back({ type, int(names.size()), "" });
    }
    return ChoiceOf(names);
  };
  const auto byteOrder = []
  {
    ValueType t = ChoiceOf({ { "little", 0, "" }, { "big", 1, "" } });
    t.StrictNames = true;
    return t;
  };
  static const Keys<R> keys = {
    { "dimensions",
      Dimensions().Mandatory(),
      &R::Dimensions,
      "voxels along x, y and z (one integer for a cube)" },
    NameKey<R>("type", types(), &R::Type, "the type of every voxel"),
    { "byte_order", byteOrder(), &R::BigEndian, "of every voxel of more than one byte" },
    { "spacing", NumbersIn(3, Positive).In("world units"), &R::Spacing, "" },
    { "origin",
      NumbersIn(3, AnyNumber).In("world units"),
      &R::Origin,
      "the position of the first voxel" },
    { "header_bytes",
      IntegerIn(0, 1LL << 62),
      &R::HeaderBytes,
      "bytes before the first voxel, skipped" },
  };
  return keys;
}

const Keys<FieldSpec>& GeneratedFieldKeys()
{
  using F = FieldSpec;
  using D = FieldDescription;
  using N = noise::FbmParameters;
  static const Keys<F> keys = {
    { "dimensions",
      CustomValue("integer, or 3 integers `[nx, ny, nz]`, or `\"auto\"`")
        .DefaultIs("`[128, 128, 128]`"),
      [](const Context& c, const json& v, const std::string& k, F& f)
      {
        if (v.is_string())
        {
          if (v.get<std::string>() != "auto")
          {
            c.Fail(
              k, "expected \"auto\", an integer or 3 integers [nx, ny, nz], got " + Describe(v));
          }
          f.AutoDimensions = CameraDetail{};
          return;
        }
        f.AutoDimensions.reset();
        Assign(Check(c, Dimensions(), v, k), f.Dimensions);
      },
      // The dimensions "auto" chose, when it did: a resolved scene generates the same lattice.
      [](const F& f) { return ToJson(f.Dimensions); },
      "each in [1, 2147483647]; the field (4 bytes per voxel) must fit in the memory available "
      "when it is generated whole; generated in pieces (`generate -o FIELD.pvti`), each piece "
      "must. `\"auto\"` chooses them from the camera: one isotropic spacing no wider than a "
      "pixel's footprint on the nearest cloud the camera sees, within `max_voxels` "
      "([Detail matched to the camera](#detail-matched-to-the-camera))" },
    { "bounds",
      NumbersIn(6, AnyNumber, "[xmin, xmax, ymin, ymax, zmin, zmax]"),
      &F::Bounds,
      "min < max on each axis",
      ~0u,
      [](F& f) -> std::string
      {
        for (int a = 0; a < 3; ++a)
        {
          if (!(f.Bounds[2 * a] < f.Bounds[2 * a + 1]))
          {
            return std::string("bounds along ") + "xyz"[a] + " must increase (min < max), got [" +
              FormatNumber(f.Bounds[2 * a]) + ", " + FormatNumber(f.Bounds[2 * a + 1]) + "]";
          }
        }
        return "";
      } },
    { "density_model",
      ChoiceOf(NamesOf<DensityModel>({ { "sdf_plus_fbm", DensityModel::SdfPlusFbm },
        { "fbm_falloff", DensityModel::FbmFalloff },
        { "constant", DensityModel::Constant },
        { "cloud", DensityModel::Cloud } })),
      Nested(&F::Description, &D::Model),
      "see [Density models](#density-models)" },
    { "density_scale",
      NumberIn(NonNegative),
      Nested(&F::Description, &D::DensityScale),
      "multiplies the density" },
    { "falloff_width",
      NumberIn(Positive),
      Nested(&F::Description, &D::FalloffWidth),
      "used by `fbm_falloff`" },
    { "shape",
      CustomValue("string, object, or array of strings/objects")
        .DefaultIs("`\"sphere\"` (radius 1)"),
      ReadShapes,
      WriteShapes,
      "see [Shapes](#shapes)" },
    { "blend",
      ChoiceOf(NamesOf<ShapeBlend>(
        { { "union", ShapeBlend::Union }, { "smooth_union", ShapeBlend::SmoothUnion } })),
      Nested(&F::Description, &D::Blend),
      "how a list of shapes is combined" },
    { "blend_radius",
      NumberIn(NonNegative),
      Nested(&F::Description, &D::BlendRadius),
      "used by `smooth_union`" },
    { "noise",
      ChoiceOf(NamesOf<noise::NoiseType>({ { "none", noise::NoiseType::None },
        { "white", noise::NoiseType::White },
        { "value", noise::NoiseType::Value },
        { "perlin", noise::NoiseType::Perlin },
        { "worley", noise::NoiseType::Worley },
        { "inverted_worley", noise::NoiseType::InvertedWorley },
        { "perlin_worley", noise::NoiseType::PerlinWorley } })),
      Nested(&F::Description, &D::Noise, &N::Type),
      "see [Noise and fBm](#noise-and-fbm)" },
    { "octaves",
      IntegerIn(1, noise::MaxOctaves),
      Nested(&F::Description, &D::Noise, &N::Octaves),
      "" },
    { "frequency",
      NumberIn(Range{ 0.0, noise::MaxFrequency, true }),
      Nested(&F::Description, &D::Noise, &N::Frequency),
      "" },
    { "lacunarity",
      NumberIn(Positive),
      Nested(&F::Description, &D::Noise, &N::Lacunarity),
      "with `lacunarity_increment`, every octave's factor must stay > 0" },
    { "lacunarity_increment",
      NumberIn(AnyNumber),
      Nested(&F::Description, &D::Noise, &N::LacunarityIncrement),
      "" },
    { "gain", NumberIn(NonNegative), Nested(&F::Description, &D::Noise, &N::Gain), "" },
    { "amplitude", NumberIn(NonNegative), Nested(&F::Description, &D::Noise, &N::Amplitude), "" },
    { "seed",
      IntegerIn(0, std::numeric_limits<std::uint32_t>::max()),
      Nested(&F::Description, &D::Noise, &N::Seed),
      "" },
    { "noise_period",
      IntegerIn(0, noise::MaxPeriod),
      Nested(&F::Description, &D::Noise, &N::Period),
      "lattice cells of the first octave after which the noise repeats (0: never); needs a "
      "whole-number `lacunarity` and `lacunarity_increment` 0; see [Noise and "
      "fBm](#noise-and-fbm)" },
    { "wind",
      NumbersIn(3, AnyNumber),
      Nested(&F::Description, &D::Wind),
      "world units per second" },
    { "cloud",
      CustomValue("object").DefaultIs("the defaults of [field.cloud](#fieldcloud)"),
      [](const Context& c, const json& v, const std::string& k, F& f)
      { ReadObject(c, v, k, CloudKeys(), f); },
      [](const F& f)
      { return f.Description.Model == DensityModel::Cloud ? WriteObject(CloudKeys(), f) : json(); },
      "the layer, cloud type, coverage and noises of the `cloud` density model; see "
      "[Cloud layers](#cloud-layers)",
      Inside(CloudKeys) },
    { "time", NumberIn(AnyNumber), &F::Time, "seconds" },
  };
  return keys;
}

const Keys<FieldSpec>& CloudKeys()
{
  using F = FieldSpec;
  using D = FieldDescription;
  using L = CloudLayer;
  static const Keys<F> keys = {
    { "type",
      ChoiceOf({ { "stratus", int(CloudType::Stratus), "a thin flat sheet" },
        { "stratocumulus", int(CloudType::Stratocumulus), "a deck of rolls and lumps" },
        { "cumulus", int(CloudType::Cumulus), "a flat base under a rounded, billowing top" },
        { "cumulonimbus", int(CloudType::Cumulonimbus), "a tower to the top, with `anvil`" },
        { "altocumulus",
          int(CloudType::Altocumulus),
          "a thin sheet of rounded cloudlets on a cellular lattice `shape_scale` / 4 across" },
        { "congestus",
          int(CloudType::Congestus),
          "a towering cumulus: a flat base under a tall tower that narrows over its top third" } }),
      Nested(&F::Description, &D::Layer, &L::Type),
      "the height profile" },
    { "base",
      NumberIn(AnyNumber).In("world units"),
      Nested(&F::Description, &D::Layer, &L::Base),
      "the altitude (y) of the cloud base; below `top`" },
    { "top",
      NumberIn(AnyNumber).In("world units"),
      Nested(&F::Description, &D::Layer, &L::Top),
      "the altitude (y) of the cloud tops" },
    { "coverage",
      NumberIn(UnitInterval),
      Nested(&F::Description, &D::Layer, &L::Coverage),
      "how much of the sky the weather map fills (a threshold on it), or the shapes' strength" },
    { "coverage_map",
      CustomValue("`\"shapes\"`, `\"noise\"` or the path of a 2-D image or field file")
        .DefaultIs("`\"shapes\"`"),
      [](const Context& c, const json& v, const std::string& k, F& f)
      {
        if (!v.is_string() || v.get<std::string>().empty())
        {
          c.Fail(k, "expected \"shapes\", \"noise\" or a file path, got " + Describe(v));
        }
        const std::string text = v.get<std::string>();
        RefuseNul(c, k, text);
        f.CoverageMapFile.clear();
        f.Description.Layer.Map.reset(); // a map read before is another file's
        if (text == "shapes" || text == "noise")
        {
          f.Description.Layer.Source =
            text == "shapes" ? CoverageSource::Shapes : CoverageSource::Noise;
          return;
        }
        f.Description.Layer.Source = CoverageSource::Map;
        f.CoverageMapFile =
          text[0] != '/' && !c.BaseDirectory.empty() ? c.BaseDirectory + "/" + text : text;
      },
      [](const F& f) -> json
      {
        switch (f.Description.Layer.Source)
        {
          case CoverageSource::Shapes:
            return "shapes";
          case CoverageSource::Noise:
            return "noise";
          case CoverageSource::Map:
            break;
        }
        return f.CoverageMapFile;
      },
      "`shapes`: the field's shapes, softened over `falloff_width`, are one cloud; `noise`: a "
      "procedural weather map of many clouds (`map_scale`, `map_octaves`, `map_gain`); a path "
      "(relative to the scene file's folder): a 2-D image (PNG, JPEG, TIFF, BMP, PNM: its first "
      "channel) or a 2-D field file of at most 16384 x 16384 points, stretched over the field's x "
      "and z bounds; integers are divided by their type's maximum in every format (8-bit 255 and "
      "16-bit 65535 are full coverage), floating-point values are taken as they are" },
    { "map_scale",
      NumberIn(Positive).In("world units"),
      Nested(&F::Description, &D::Layer, &L::MapScale),
      "the size of the weather map's largest features" },
    { "map_octaves",
      IntegerIn(1, noise::MaxOctaves),
      Nested(&F::Description, &D::Layer, &L::MapOctaves),
      "" },
    { "map_gain",
      NumberIn(UnitInterval),
      Nested(&F::Description, &D::Layer, &L::MapGain),
      "amplitude factor between the map's octaves: higher, rougher cloud edges seen from above "
      "(the area-perimeter dimension of the map's clouds: about 1.27 at 0.6, 1.34 at 0.7, 1.41 at "
      "0.8)" },
    { "shape_scale",
      NumberIn(Positive).In("world units"),
      Nested(&F::Description, &D::Layer, &L::ShapeScale),
      "the length over which the shape noise (the cloud's masses) repeats" },
    { "detail_scale",
      NumberIn(Positive).In("world units"),
      Nested(&F::Description, &D::Layer, &L::DetailScale),
      "the length over which the detail noise (the billows) repeats" },
    { "erosion",
      NumberIn(UnitInterval),
      Nested(&F::Description, &D::Layer, &L::Erosion),
      "how deep the detail noise eats into the edges" },
    { "curl",
      NumberIn(UnitInterval),
      Nested(&F::Description, &D::Layer, &L::Curl),
      "curl-noise turbulence of the detail, strongest at the base" },
    { "breakup",
      NumberIn(UnitInterval),
      Nested(&F::Description, &D::Layer, &L::Breakup),
      "how far a 3-D noise moves the weather map above the base (`noise` or a map): the clouds' "
      "sides break up instead of rising straight as the map's outlines; see "
      "[Cloud layers](#cloud-layers)" },
    { "anvil",
      NumberIn(UnitInterval),
      Nested(&F::Description, &D::Layer, &L::Anvil),
      "the cumulonimbus's anvil, 0 (none) to 1: it overhangs the tower by `anvil` x a tenth of "
      "the layer's depth all round, and streams `anvil` x `anvil_reach` downwind; see "
      "[Cumulonimbus](#cumulonimbus)" },
    { "anvil_direction",
      NumbersIn(2, AnyNumber, "[x, z]"),
      Nested(&F::Description, &D::Layer, &L::AnvilDirection),
      "the direction of the upper wind the anvil streams along (any length but 0)" },
    { "anvil_reach",
      NumberIn(NonNegative).In("world units"),
      Nested(&F::Description, &D::Layer, &L::AnvilReach),
      "how far the anvil streams downwind of the tower; needs the shapes' coverage" },
    { "overshoot",
      NumberIn(NonNegative).In("world units"),
      Nested(&F::Description, &D::Layer, &L::Overshoot),
      "the height of the overshooting dome above `top` on the tower's axis (0: none); `top` plus "
      "it must stay inside the field; needs the shapes' coverage" },
    { "rain",
      NumberIn(UnitInterval),
      Nested(&F::Description, &D::Layer, &L::Rain),
      "the rain shaft under the tower's base, from it to the field's floor: its density in its "
      "streaks as a fraction of `density_scale` (0: none); needs the shapes' coverage; see "
      "[Cumulonimbus](#cumulonimbus)" },
    { "shear",
      NumbersIn(2, AnyNumber, "[x, z]"),
      Nested(&F::Description, &D::Layer, &L::Shear),
      "horizontal displacement per unit of height above the base: the cloud leans" },
  };
  return keys;
}

const Keys<Shape>& ShapeKeys()
{
  static const Keys<Shape> keys = {
    { "type", ChoiceOf(ShapeTypes()).Mandatory(), &Shape::Type, "" },
    { "center", NumbersIn(3, AnyNumber), &Shape::Center, "" },
    { "rotation",
      NumbersIn(3, AnyNumber).In("degrees"),
      &Shape::RotationDegrees,
      "applied about x, then y, then z" },
    { "scale", NumberIn(Positive), &Shape::Scale, "" },
    { "radius",
      NumberIn(NonNegative),
      &Shape::Radius,
      "",
      Bit(ShapeType::Sphere) | Bit(ShapeType::Capsule) },
    { "half_size", NumbersIn(3, NonNegative), &Shape::HalfSize, "", Bit(ShapeType::Box) },
    { "major_radius",
      NumberIn(NonNegative),
      &Shape::MajorRadius,
      "centre of the tube to the axis (the torus lies around y)",
      Bit(ShapeType::Torus) },
    { "minor_radius",
      NumberIn(NonNegative),
      &Shape::MinorRadius,
      "radius of the tube",
      Bit(ShapeType::Torus) },
    { "arm_width",
      NumberIn(NonNegative),
      &Shape::ArmWidth,
      "half-width of the three bars",
      Bit(ShapeType::Cross) },
    { "arm_length",
      NumberIn(NonNegative),
      &Shape::ArmLength,
      "half-length of the three bars",
      Bit(ShapeType::Cross) },
    { "end_a",
      NumbersIn(3, AnyNumber),
      &Shape::EndA,
      "different from `end_b`",
      Bit(ShapeType::Capsule) },
    { "end_b", NumbersIn(3, AnyNumber), &Shape::EndB, "", Bit(ShapeType::Capsule) },
  };
  return keys;
}

const Keys<TransferFunctionSpec>& TransferFunctionKeys()
{
  using T = TransferFunctionSpec;
  const std::string densities = "densities within +-" + FormatNumber(MaxTransferDensity) +
    " (float's range), spanning at most that";
  static const Keys<T> keys = {
    { "opacity",
      PointsIn(2, UnitInterval, "[density, opacity]").CheckedBy(DensitiesWithinFloat),
      &T::Opacity,
      densities },
    { "color",
      PointsIn(4, UnitInterval, "[density, r, g, b]").CheckedBy(DensitiesWithinFloat),
      &T::Color,
      densities },
    { "unit_distance",
      NumberIn(Range{ MinUnitDistance() }).In("world units"),
      &T::UnitDistance,
      "the distance over which `opacity` applies; the bound keeps the extinction of opacity 1, "
      "-ln(1e-4) / `unit_distance`, within float range" },
    { "extinction",
      ChoiceOf(
        { { "opacity", int(T::ExtinctionRule::Opacity), "from `opacity` per `unit_distance`" },
          { "droplets",
            int(T::ExtinctionRule::Droplets),
            "the extinction of cloud droplets, 3 lwc / (2 rho_w r_e) per metre (rho_w = 10^6 "
            "g/m^3, r_e = `field.effective_radius`, else the field file's), converted to world "
            "units; needs `field.quantity` `\"lwc\"` and `field.length_unit` `\"m\"` or "
            "`\"km\"`, from the scene or the field file; `opacity` and `unit_distance` are "
            "then unused" } }),
      &T::Extinction,
      "where the extinction comes from; `color` gives the albedo either way" },
    { "lwc_max",
      NumberIn(Positive).In("g/m^3"),
      &T::LwcMax,
      "with `extinction` `\"droplets\"`: the largest liquid water content the table resolves; "
      "denser voxels get its extinction" },
    PresetReference("preset",
      NonEmptyText("a preset name or the path of a .json file").DefaultIs("none"),
      "a shipped preset's name, or the path of a preset file (relative to the scene file's "
      "folder); [below](#transfer-function-presets)"),
    PresetReference("preset_name",
      NonEmptyText("the Name of a preset in the ParaView file")
        .DefaultIs("the file's first preset"),
      "with a ParaView file holding several presets: the `Name` of the one to use; an error with "
      "anything else"),
  };
  return keys;
}

const Keys<CameraSpec>& CameraKeys()
{
  using C = CameraSpec;
  static const Keys<C> keys = {
    { "position",
      NumbersIn(3, AnyNumber)
        .DefaultIs("`focal_point + (0, 0, d)`: looking along -z; for a field whose up is z, "
                   "`focal_point + (0, -d, 0)` (looking across it, along +y), for x up as for y"),
      &C::Position,
      "not equal to `focal_point`" },
    { "focal_point",
      NumbersIn(3, AnyNumber).DefaultIs("the centre of the field's bounds"),
      &C::FocalPoint,
      "" },
    { "view_up",
      NumbersIn(3, AnyNumber)
        .DefaultIs(
          "`[0, 1, 0]`; the field's up axis (`field.up`, or the file's) when it is x or z"),
      &C::ViewUp,
      "not zero, not parallel to the view direction",
      ~0u,
      [](C& camera) -> std::string
      {
        const std::array<double, 3>& u = camera.ViewUp;
        return u[0] * u[0] + u[1] * u[1] + u[2] * u[2] == 0.0
          ? "the view-up vector must not be zero"
          : "";
      } },
    { "view_angle",
      NumberIn(Range{ 0.0, 180.0, true, true }).In("degrees"),
      &C::ViewAngle,
      "the vertical angle of view" },
    { "orbit",
      CustomValue("object `{\"azimuth\", \"elevation\", \"distance\"}`").DefaultIs("none"),
      [](const Context& c, const json& v, const std::string& k, C& camera)
      {
        OrbitSpec orbit;
        ReadObject(c, v, k, OrbitKeys(), orbit);
        camera.Orbit = orbit;
      },
      [](const C& camera)
      { return camera.Orbit ? WriteObject(OrbitKeys(), *camera.Orbit) : json(); },
      "places the camera on a sphere around `focal_point`; cannot be combined with `position`",
      Inside(OrbitKeys) },
  };
  return keys;
}

const Keys<OrbitSpec>& OrbitKeys()
{
  using O = OrbitSpec;
  static const Keys<O> keys = {
    { "azimuth",
      NumberIn(AnyNumber).In("degrees"),
      &O::Azimuth,
      "about the y axis, from +z toward +x" },
    { "elevation", NumberIn(Range{ -90.0, 90.0, true, true }).In("degrees"), &O::Elevation, "" },
    { "distance",
      NumberIn(Positive).In("world units").DefaultIs("`d` above: the field fits the view"),
      &O::Distance,
      "" },
  };
  return keys;
}

const Keys<Scene>& BackgroundKeys()
{
  const auto solid = Bit(BackgroundType::Solid), gradient = Bit(BackgroundType::Gradient),
             sky = Bit(BackgroundType::Sky);
  static const Keys<Scene> keys = {
    { "type",
      ChoiceOf(BackgroundTypes()).Mandatory(),
      Nested(&Scene::BackgroundStyle, &BackgroundSpec::Type),
      "" },
    { "color", NumbersIn(3, UnitInterval).Mandatory(), &Scene::Background, "", solid },
    { "top",
      NumbersIn(3, UnitInterval).Mandatory(),
      Nested(&Scene::BackgroundStyle, &BackgroundSpec::Top),
      "",
      gradient },
    { "bottom", NumbersIn(3, UnitInterval).Mandatory(), &Scene::Background, "", gradient },
    { "sun",
      NumbersIn(3, AnyNumber),
      Nested(&Scene::BackgroundStyle, &BackgroundSpec::Sun),
      "a direction toward the sun, any length but not zero",
      sky,
      NormalizeSun },
  };
  return keys;
}

const Keys<RenderSpec>& RenderKeys()
{
  using R = RenderSpec;
  static const Keys<R> keys = {
    { "lighting",
      ChoiceOf(LightingModels()),
      Nested(&R::Lighting, &LightingParameters::Model),
      "see [lighting.md](lighting.md). `--lighting` overrides it." },
    { "step",
      NumberIn(NonNegative).In("world units"),
      &R::Step,
      "between samples along a ray; `0` means automatic: one voxel (the smallest spacing of the "
      "field). A ray takes at most " +
        std::to_string(MaxSamplesPerRay) +
        " samples: a step needing more along the field's longest diagonal is refused once the "
        "field is known, with the smallest step it allows" },
    { "jitter",
      Boolean(),
      &R::Jitter,
      "offset each ray's start by blue noise, turning banding into fine noise that accumulation "
      "averages away" },
    { "resolution_scale",
      NumberIn(Range{ 0.25, 1.0 }),
      &R::ResolutionScale,
      "the march runs at this fraction of the image's width and height and is upsampled "
      "(Catmull-Rom)" },
    { "gpu_memory",
      NumberIn(Range{ 16.0, 16777216.0 })
        .In("MiB")
        .DefaultIs("what the GPU's driver reports free (no limit where it reports nothing)"),
      &R::GpuMemoryMiB,
      "the GPU memory the renderer may take (the mapper's MaximumGPUMemory); a field whose "
      "textures do not fit is averaged over "
      "2 x 2 x 2 voxels (and again, up to 16 x 16 x 16) until they do, which the render and the "
      "viewer say and the image's metadata records (`cloudvis.coarsened`)" },
    { "accumulate",
      IntegerIn(1, 65536),
      &R::Accumulate,
      "frames averaged into a still (with `jitter: false` one frame is rendered: every frame "
      "would be the same)" },
    { "spp",
      IntegerIn(2, 1 << 24),
      &R::SamplesPerPixel,
      "`pathtrace`: paths averaged per pixel of a still (its noise falls as 1 / sqrt(spp)); "
      "`--spp` overrides it" },
    { "skip_empty_space",
      Boolean(),
      &R::SkipEmptySpace,
      "leap over empty bricks; changes the speed, never the image" },
    { "size",
      IntegersIn(2, 16, 16384, "[width, height]").In("pixels"),
      &R::Size,
      "`--size WxH` overrides it" },
    { "png_bits",
      IntegerOneOf({ 8, 16 }),
      &R::PngBits,
      "bits per PNG channel ([export.md](export.md)); `--png-bits` overrides it" },
    { "exr_type",
      []
      {
        ValueType t = ChoiceOf({ { "half", 1, "" }, { "float", 0, "" } });
        t.StrictNames = true;
        return t;
      }(),
      &R::ExrHalf,
      "pixel type of every EXR channel; `--exr-half` sets `\"half\"`" },
    { "exposure",
      CustomValue("number (EV) or `\"auto\"`").DefaultIs("`0`"),
      [](const Context& c, const json& v, const std::string& k, R& r)
      {
        if (v.is_string() && v.get<std::string>() == "auto")
        {
          r.AutoExposure = true;
          r.ExposureEV = 0.0;
          return;
        }
        if (!v.is_number() || !std::isfinite(v.get<double>()) ||
          std::abs(v.get<double>()) > MaxExposureEV)
        {
          c.Fail(k,
            "expected \"auto\" or a number of EV in [-" + ShowValue(MaxExposureEV) + ", " +
              ShowValue(MaxExposureEV) + "], got " + Describe(v));
        }
        r.AutoExposure = false;
        r.ExposureEV = v.get<double>();
      },
      [](const R& r) -> json
      {
        if (r.AutoExposure)
        {
          return "auto";
        }
        return r.ExposureEV;
      },
      "the cloud's radiance is multiplied by 2^EV before the display curve; `\"auto\"` chooses "
      "EV so that the " +
        ShowValue(100.0 * AutoExposurePercentile) +
        "th percentile of the cloud's luminance (pixels at least " +
        ShowValue(AutoExposureMinimumAlpha) + " opaque) lands at " + ShowValue(AutoExposureTarget) +
        " ([export.md](export.md#exposure-and-the-display-curve)); PNG, `compare` and the "
        "viewer; EXR stays linear and records it; `--exposure` overrides it" },
    { "display",
      []
      {
        ValueType t = ChoiceOf(NamesOf<DisplayCurve>(
          { { "linear", DisplayCurve::Linear }, { "filmic", DisplayCurve::Filmic } }));
        t.StrictNames = true;
        return t;
      }(),
      &R::Display,
      "the curve from exposed radiance to display values: `linear` (clamped at 1) or `filmic` "
      "(an ACES-like tone curve with sRGB's encoding, which rolls highlights off instead of "
      "clipping them)" },
    { "reprojection",
      Boolean(),
      &R::Reprojection,
      "`cloudvis view`: while the camera moves, blend the last image, reprojected to the new "
      "view, into each reduced-resolution frame where it still holds ([viewer.md](viewer.md)); "
      "stills and exports are unchanged" },
    LightingObject("derivative",
      DerivativeKeys,
      "the derivative model's parameters ([below](#renderderivative-and-rendermarch))"),
    LightingObject("march",
      MarchKeys,
      "the light march's parameters ([below](#renderderivative-and-rendermarch))"),
  };
  return keys;
}

// The ranges are the filters' (LightingLimits, ValidateLightingParameters in CloudLighting.h),
// which also checks the whole after these keys.
const Keys<LightingParameters>& DerivativeKeys()
{
  using P = LightingParameters;
  static const Keys<P> keys = {
    { "distance",
      NumberIn(NonNegative).In("world units"),
      &P::DerivativeDistance,
      "the finite-difference distance `h` toward each light; `0` means automatic: 4 voxels (the "
      "smallest spacing)" },
  };
  return keys;
}

const Keys<LightingParameters>& MarchKeys()
{
  using P = LightingParameters;
  using L = LightingLimits;
  const Range g{ -1.0, 1.0, true, true };
  static const Keys<P> keys = {
    { "light_steps",
      IntegerIn(L::MinLightSteps, L::MaxLightSteps),
      &P::LightSteps,
      "segments of the march toward each light, spanning the way to the volume's exit (or a point "
      "light)" },
    { "light_step",
      NumberIn(NonNegative).In("world units"),
      &P::LightStep,
      "shortest first segment (a short way takes fewer segments); `0` means automatic: 2 voxels" },
    { "light_step_growth",
      NumberIn(Range{ L::MinLightStepGrowth, L::MaxLightStepGrowth }),
      &P::LightStepGrowth,
      "each segment is this much longer than the one before (1: uniform)" },
    { "transmittance",
      ChoiceOf(NamesOf<LightTransmittance>(
        { { "volumes", LightTransmittance::Volumes }, { "nested", LightTransmittance::Nested } })),
      &P::Transmittance,
      "where the optical depth toward each light comes from: `\"volumes\"`, per-light volumes at "
      "half the field's resolution computed when the field, transfer function or lights change "
      "(fast), or `\"nested\"`, the march above at every sample (the quality setting); see "
      "[lighting.md](lighting.md#light-volumes)" },
    { "g1",
      NumberIn(g),
      &P::PhaseG1,
      "Henyey-Greenstein eccentricity of the forward lobe (> 0 scatters forward)" },
    { "g2", NumberIn(g), &P::PhaseG2, "eccentricity of the second (backward) lobe" },
    { "lobe_weight",
      NumberIn(UnitInterval),
      &P::PhaseLobeWeight,
      "weight of the first lobe (1: one lobe)" },
    { "phase",
      []
      {
        ValueType t = ChoiceOf(NamesOf<PhaseModel>(
          { { "two_lobe", PhaseModel::TwoLobe }, { "droplets", PhaseModel::Droplets } }));
        t.StrictNames = true;
        return t;
      }(),
      &P::Phase,
      "the phase function of the march and the path tracer: `two_lobe`, Henyey-Greenstein with "
      "`g1`, `g2` and `lobe_weight`, or "
      "`droplets`, the Mie phase of liquid water droplets computed by cloudvis for "
      "`effective_radius` and `effective_variance` at 680, 550 and 440 nm, with its forward "
      "peak, cloudbow and glory ([lighting.md](lighting.md#droplet-optics))" },
    { "effective_radius",
      NumberIn(Range{ DropletEffectiveRadiusMinUm, DropletEffectiveRadiusMaxUm })
        .In("micrometres")
        .DefaultIs("the field's r_e (`field.effective_radius`, else the file's, else `10`)"),
      &P::DropletEffectiveRadius,
      "`phase: \"droplets\"`: the droplets' effective radius r_e (the ratio of the third to the "
      "second moment of their radii); without it the phase takes the field's, one r_e for "
      "extinction and phase, refused when beyond this range" },
    { "effective_variance",
      NumberIn(Range{ DropletEffectiveVarianceMin, DropletEffectiveVarianceMax }),
      &P::DropletEffectiveVariance,
      "`phase: \"droplets\"`: the effective variance v_e of their modified gamma size "
      "distribution (Hansen and Travis 1974)" },
    { "multiple_scattering",
      ChoiceOf(NamesOfTable(MultipleScatteringModelTable())).RefusesOutdated(OctaveCountMoved),
      &P::MultipleScattering,
      "how the march adds the light scattered more than once to single scattering "
      "([lighting.md](lighting.md#the-multiple-scattering-volume-the-default)). Until issue 21 "
      "this key held the number of octaves, now `octaves`: a number here is refused, saying so" },
    { "octaves",
      IntegerIn(0, L::MaxMultipleScatteringOctaves),
      &P::MultipleScatteringOctaves,
      "with `multiple_scattering: \"octaves\"`: octaves of approximate multiple scattering added "
      "to single scattering (0: none)" },
    { "scattering_falloff",
      NumberIn(UnitInterval),
      &P::ScatteringFalloff,
      "`a`: each octave scatters `a` times less" },
    { "extinction_falloff",
      NumberIn(UnitInterval),
      &P::ExtinctionFalloff,
      "`b`: each octave sees `b` times less extinction toward the light" },
    { "eccentricity_falloff",
      NumberIn(UnitInterval),
      &P::EccentricityFalloff,
      "`c`: each octave's phase is `c` times less eccentric" },
    { "powder",
      NumberIn(UnitInterval),
      &P::PowderStrength,
      "the \"powder\" darkening of thin, lit regions. **Not physical**: it removes light single "
      "scattering says is there; an artistic, labelled choice" },
  };
  return keys;
}

const Keys<Light>& LightKeys()
{
  static const Keys<Light> keys = {
    { "type", ChoiceOf(LightTypes()).Mandatory(), &Light::Positional, "" },
    { "position",
      NumbersIn(3, AnyNumber).Mandatory(),
      &Light::Position,
      "for a directional light, not equal to `focal_point`" },
    { "focal_point",
      NumbersIn(3, AnyNumber),
      &Light::FocalPoint,
      "directional lights only (on a point light it is an error)",
      Directional },
    { "color", NumbersIn(3, UnitInterval), &Light::Color, "" },
    { "intensity",
      NumberIn(Range{ 0.0, FloatLimit, false, true }),
      &Light::Intensity,
      "multiplies `color`; the renderers also refuse a light bright enough to overflow float "
      "arithmetic in the light it scatters (with `render.march`'s phase function)" },
    { "attenuation",
      NumbersIn(3, NonNegative, "[a0, a1, a2]"),
      &Light::Attenuation,
      "point lights only; not all 0; the light falls off as `1 / (a0 + a1 r + a2 r^2)` at "
      "distance `r` (the default is the inverse square)",
      Point,
      [](Light& l) -> std::string
      {
        return l.Attenuation == glm::vec3(0.0f)
          ? "the attenuation [a0, a1, a2] must not be all zero (the falloff is 1 / (a0 + a1 r + "
            "a2 r^2))"
          : "";
      } },
  };
  return keys;
}

const Keys<LightingParameters>& AmbientKeys()
{
  using P = LightingParameters;
  static const Keys<P> keys = {
    { "color", NumbersIn(3, UnitInterval), &P::AmbientColor, "" },
    { "strength", NumberIn(NonNegative), &P::AmbientStrength, "multiplies `color`" },
  };
  return keys;
}

const Keys<Scene>& SceneSections()
{
  static const Keys<Scene> keys = {
    { "description",
      Text().DefaultIs("none"),
      &Scene::Description,
      "free text, shown nowhere yet; say what the scene is for" },
    { "field",
      CustomValue("object").DefaultIs("the default scene's field"),
      ReadField,
      WriteField,
      "the density field ([below](#the-field-section))",
      Inside(FieldKeys) },
    { "transfer_function",
      CustomValue("object").DefaultIs("below"),
      ReadTransferFunction,
      [](const Scene& s) { return WriteObject(TransferFunctionKeys(), s.TransferFunction); },
      "what density looks like: opacity and color ([below](#the-transfer_function-section))",
      Inside(TransferFunctionKeys) },
    { "camera",
      CustomValue("object").DefaultIs("framing the field"),
      ReadCamera,
      [](const Scene& s) { return WriteObject(CameraKeys(), s.Camera); },
      "where the view is from ([below](#the-camera-section))",
      Inside(CameraKeys) },
    { "background",
      CustomValue("`[r, g, b]` (each in [0, 1]) or an object with a `type`"),
      ReadBackground,
      WriteBackground,
      "what is behind the cloud: a color, a gradient or the article's sky "
      "([below](#the-background-section))",
      Inside(BackgroundKeys) },
    Section(
      "render", &Scene::Render, RenderKeys, "how the image is made ([below](#the-render-section))"),
    { "lights",
      CustomValue("list of objects").DefaultIs("one white sun"),
      ReadLights,
      WriteLights,
      "the light sources of the `derivative` and `march` models "
      "([below](#the-lights-section))" },
    Section("ambient",
      Nested(&Scene::Render, &RenderSpec::Lighting),
      AmbientKeys,
      "isotropic, unshadowed light those models add ([below](#the-ambient-section))"),
    ViewSection(),
  };
  return keys;
}

} // namespace schema
} // namespace cloudvis
