// The generic checks and words of the scene schema: every message about a value, and every
// description of a type in the docs, is written here once, for all keys of that type.
#include "Schema.h"

#include "Errors.h"
#include "Scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace cloudvis
{
namespace schema
{

void Context::Fail(const std::string& key, const std::string& problem) const
{
  std::string note;
  for (const auto& overridden : this->OverriddenKeys)
  {
    const std::string& k = overridden.first;
    if (key == k || key.rfind(k + ".", 0) == 0 || key.rfind(k + "[", 0) == 0)
    {
      note = " (set with " + overridden.second + ")";
    }
  }
  throw InputError(this->Source + ": " + key + ": " + problem + note);
}

std::string Describe(const json& value)
{
  // A string from --set may hold any bytes, and dump() throws on invalid UTF-8.
  const std::string text = WithValidUtf8(value).dump();
  return std::string(value.type_name()) + " " +
    (text.size() > 40 ? text.substr(0, 37) + "..." : text);
}

std::string FormatNumber(double value)
{
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

// ---- ranges --------------------------------------------------------------------------------

bool Range::Contains(double v) const
{
  return (this->MinOpen ? v > this->Min : v >= this->Min) &&
    (this->MaxOpen ? v < this->Max : v <= this->Max);
}

std::string Range::Text(bool forDocs) const
{
  const bool bounded = this->Max < std::numeric_limits<double>::max();
  const bool floored = this->Min > -std::numeric_limits<double>::max();
  if (floored && bounded)
  {
    return std::string(this->MinOpen ? "(" : "[") + FormatNumber(this->Min) + ", " +
      FormatNumber(this->Max) + (this->MaxOpen ? ")" : "]");
  }
  if (floored)
  {
    return std::string(this->MinOpen ? "> " : ">= ") + FormatNumber(this->Min);
  }
  return forDocs ? "any" : "any finite number";
}

// ---- names ---------------------------------------------------------------------------------

std::vector<std::string> TextsOf(const std::vector<Name>& names)
{
  std::vector<std::string> texts;
  for (const Name& name : names)
  {
    texts.push_back(name.Text);
  }
  return texts;
}

std::string NameOf(const std::vector<Name>& names, int value)
{
  for (const Name& name : names)
  {
    if (name.Value == value)
    {
      return name.Text;
    }
  }
  return "";
}

namespace
{
std::vector<std::string> Quoted(const std::vector<std::string>& texts)
{
  std::vector<std::string> quoted;
  for (const std::string& text : texts)
  {
    quoted.push_back("\"" + text + "\"");
  }
  return quoted;
}
}

// ---- value types ---------------------------------------------------------------------------

ValueType ValueType::In(std::string unit) const
{
  ValueType t = *this;
  t.Unit = std::move(unit);
  return t;
}

ValueType ValueType::Described(std::string typeText) const
{
  ValueType t = *this;
  t.TypeText = std::move(typeText);
  return t;
}

ValueType ValueType::DefaultIs(std::string defaultText) const
{
  ValueType t = *this;
  t.DefaultText = std::move(defaultText);
  return t;
}

ValueType ValueType::Mandatory() const
{
  ValueType t = *this;
  t.Required = true;
  return t;
}

ValueType ValueType::CheckedBy(ValueCheck refuse) const
{
  ValueType t = *this;
  t.Refuse = refuse;
  return t;
}

ValueType ValueType::RefusesOutdated(ValueCheck outdated) const
{
  ValueType t = *this;
  t.Outdated = outdated;
  return t;
}

ValueType NumberIn(const Range& allowed)
{
  ValueType t;
  t.Type = ValueType::Number;
  t.Allowed = allowed;
  return t;
}

ValueType IntegerIn(long long min, long long max)
{
  ValueType t;
  t.Type = ValueType::Integer;
  t.Min = min;
  t.Max = max;
  return t;
}

ValueType IntegerOneOf(std::vector<long long> values)
{
  ValueType t = IntegerIn(values.front(), values.back());
  t.OneOf = std::move(values);
  return t;
}

ValueType Boolean()
{
  ValueType t;
  t.Type = ValueType::Boolean;
  return t;
}

ValueType Text(std::string expected)
{
  ValueType t;
  t.Type = ValueType::Text;
  t.Expected = std::move(expected);
  return t;
}

ValueType NonEmptyText(std::string expected)
{
  ValueType t = Text(std::move(expected));
  t.NonEmpty = true;
  return t;
}

ValueType Path(std::string expected)
{
  ValueType t = NonEmptyText(std::move(expected));
  t.IsPath = true;
  return t;
}

ValueType ChoiceOf(std::vector<Name> names)
{
  ValueType t;
  t.Type = ValueType::Choice;
  t.Names = std::move(names);
  return t;
}

ValueType NumbersIn(size_t count, const Range& allowed, std::string form)
{
  ValueType t;
  t.Type = ValueType::Numbers;
  t.Count = count;
  t.Allowed = allowed;
  t.Form = std::move(form);
  return t;
}

ValueType IntegersIn(size_t count, long long min, long long max, std::string form)
{
  ValueType t;
  t.Type = ValueType::Integers;
  t.Count = count;
  t.Min = min;
  t.Max = max;
  t.Form = std::move(form);
  return t;
}

ValueType IntegerOrIntegersIn(size_t count, long long min, long long max, std::string form)
{
  ValueType t = IntegersIn(count, min, max, std::move(form));
  t.OneFillsAll = true;
  return t;
}

ValueType PointsIn(size_t count, const Range& allowed, std::string form)
{
  ValueType t = NumbersIn(count, allowed, std::move(form));
  t.Type = ValueType::Points;
  return t;
}

ValueType CustomValue(std::string typeText)
{
  ValueType t;
  t.TypeText = std::move(typeText);
  return t;
}

// ---- checking ------------------------------------------------------------------------------

namespace
{

double CheckNumber(const Context& c, const json& v, const std::string& key, const Range& range)
{
  if (!v.is_number())
  {
    c.Fail(key, "expected a number, got " + Describe(v));
  }
  const double value = v.get<double>();
  if (!std::isfinite(value))
  {
    c.Fail(key, "expected a finite number, got " + FormatNumber(value));
  }
  if (!range.Contains(value))
  {
    c.Fail(key, "value " + FormatNumber(value) + " is out of range: allowed " + range.Text());
  }
  return value;
}

// Integers may be written as 6 or 6.0, never 6.5.
long long CheckInteger(const Context& c, const json& v, const std::string& key, const ValueType& t)
{
  const std::string allowed =
    "an integer in [" + std::to_string(t.Min) + ", " + std::to_string(t.Max) + "]";
  if (!v.is_number())
  {
    c.Fail(key, "expected " + allowed + ", got " + Describe(v));
  }
  if (v.is_number_unsigned() &&
    v.get<unsigned long long>() > static_cast<unsigned long long>(t.Max))
  {
    c.Fail(key, "value " + v.dump() + " is out of range: allowed " + allowed);
  }
  const double asDouble = v.get<double>();
  if (v.is_number_float() && (!std::isfinite(asDouble) || asDouble != std::floor(asDouble)))
  {
    c.Fail(key, "expected " + allowed + ", got " + v.dump());
  }
  if (asDouble < double(t.Min) || asDouble > double(t.Max))
  {
    c.Fail(key, "value " + v.dump() + " is out of range: allowed " + allowed);
  }
  const long long value =
    v.is_number_float() ? static_cast<long long>(asDouble) : v.get<long long>();
  if (!t.OneOf.empty() && std::find(t.OneOf.begin(), t.OneOf.end(), value) == t.OneOf.end())
  {
    std::vector<std::string> choices;
    for (long long choice : t.OneOf)
    {
      choices.push_back(std::to_string(choice));
    }
    c.Fail(key, "expected " + Join(choices, " or ") + ", got " + v.dump());
  }
  return value;
}

std::string IndexKey(const std::string& key, size_t i)
{
  return key + "[" + std::to_string(i) + "]";
}

int CheckChoice(const Context& c, const json& v, const std::string& key, const ValueType& t)
{
  const std::vector<std::string> texts = TextsOf(t.Names);
  if (v.is_string())
  {
    for (const Name& name : t.Names)
    {
      if (v.get<std::string>() == name.Text)
      {
        return name.Value;
      }
    }
  }
  if (t.StrictNames)
  {
    c.Fail(key, "expected " + Join(Quoted(texts), " or ") + ", got " + Describe(v));
  }
  if (!v.is_string())
  {
    c.Fail(key, "expected a string (one of " + Join(texts) + "), got " + Describe(v));
  }
  c.Fail(key, "unknown name \"" + v.get<std::string>() + "\"; allowed: " + Join(texts));
}

json CheckPoints(const Context& c, const json& v, const std::string& key, const ValueType& t)
{
  if (!v.is_array())
  {
    c.Fail(key, "expected a list of " + t.Form + " points, got " + Describe(v));
  }
  if (v.empty())
  {
    c.Fail(key, "the list is empty; give at least one " + t.Form + " point");
  }
  json points = json::array();
  for (size_t i = 0; i < v.size(); ++i)
  {
    const std::string pointKey = IndexKey(key, i);
    if (!v[i].is_array() || v[i].size() != t.Count)
    {
      c.Fail(pointKey, "expected a point " + t.Form + ", got " + Describe(v[i]));
    }
    json point = json::array({ CheckNumber(c, v[i][0], IndexKey(pointKey, 0), AnyNumber) });
    for (size_t j = 1; j < t.Count; ++j)
    {
      point.push_back(CheckNumber(c, v[i][j], IndexKey(pointKey, j), t.Allowed));
    }
    if (!points.empty() && !(point[0].get<double>() > points.back()[0].get<double>()))
    {
      c.Fail(IndexKey(pointKey, 0),
        "densities must increase strictly from point to point: " + FormatNumber(point[0]) +
          " follows " + FormatNumber(points.back()[0]));
    }
    points.push_back(point);
  }
  return points;
}

json CheckKind(const Context& c, const ValueType& t, const json& v, const std::string& key)
{
  switch (t.Type)
  {
    case ValueType::Number:
      return CheckNumber(c, v, key, t.Allowed);
    case ValueType::Integer:
      return CheckInteger(c, v, key, t);
    case ValueType::Boolean:
      if (!v.is_boolean())
      {
        c.Fail(key, "expected true or false, got " + Describe(v));
      }
      return v;
    case ValueType::Text:
    {
      if (!v.is_string() || (t.NonEmpty && v.get<std::string>().empty()))
      {
        c.Fail(key, "expected " + t.Expected + ", got " + Describe(v));
      }
      const std::string text = v.get<std::string>();
      RefuseNul(c, key, text);
      const bool relative = t.IsPath && text[0] != '/' && !c.BaseDirectory.empty();
      return relative ? c.BaseDirectory + "/" + text : text;
    }
    case ValueType::Choice:
      return CheckChoice(c, v, key, t);
    case ValueType::Numbers:
    {
      if (!v.is_array() || v.size() != t.Count)
      {
        c.Fail(key,
          "expected an array of " + std::to_string(t.Count) + " numbers" +
            (t.Form.empty() ? "" : " " + t.Form) + ", got " + Describe(v));
      }
      json numbers = json::array();
      for (size_t i = 0; i < t.Count; ++i)
      {
        numbers.push_back(CheckNumber(c, v[i], IndexKey(key, i), t.Allowed));
      }
      return numbers;
    }
    case ValueType::Integers:
    {
      if (t.OneFillsAll && v.is_number())
      {
        return json::array_t(t.Count, CheckInteger(c, v, key, t));
      }
      if (!v.is_array() || v.size() != t.Count)
      {
        const std::string count =
          std::to_string(t.Count) + " integers" + (t.Form.empty() ? "" : " " + t.Form);
        c.Fail(key,
          std::string("expected ") + (t.OneFillsAll ? "an integer or " : "") + "an array of " +
            count + ", got " + Describe(v));
      }
      json integers = json::array();
      for (size_t i = 0; i < t.Count; ++i)
      {
        integers.push_back(CheckInteger(c, v[i], IndexKey(key, i), t));
      }
      return integers;
    }
    case ValueType::Points:
      return CheckPoints(c, v, key, t);
    case ValueType::Custom:
      break;
  }
  return v;
}

} // namespace

void RefuseNul(const Context& c, const std::string& key, const std::string& text)
{
  const auto at = text.find('\0');
  if (at != std::string::npos)
  {
    c.Fail(key,
      "the string holds a NUL character (\\u0000) at byte " + std::to_string(at) +
        ", which no path or name can hold: got " + Describe(json(text)));
  }
}

json Check(const Context& c, const ValueType& t, const json& v, const std::string& key)
{
  const std::string outdated = t.Outdated ? t.Outdated(v) : std::string();
  if (!outdated.empty())
  {
    c.Fail(key, outdated);
  }
  json checked = CheckKind(c, t, v, key);
  const std::string problem = t.Refuse ? t.Refuse(v) : std::string();
  if (!problem.empty())
  {
    c.Fail(key, problem);
  }
  return checked;
}

json Present(const ValueType& t, const json& value)
{
  if (t.Type != ValueType::Choice || value.is_null())
  {
    return value;
  }
  return NameOf(t.Names, value.is_boolean() ? int(value.get<bool>()) : value.get<int>());
}

// ---- members -------------------------------------------------------------------------------

void Assign(const json& v, glm::vec3& m)
{
  m = glm::vec3(float(v[0].get<double>()), float(v[1].get<double>()), float(v[2].get<double>()));
}

void Assign(const json& v, glm::dvec3& m)
{
  m = glm::dvec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
}

json ToJson(const glm::vec3& m)
{
  return json::array({ ToJson(m.x), ToJson(m.y), ToJson(m.z) });
}

json ToJson(const glm::dvec3& m)
{
  return json::array({ m.x, m.y, m.z });
}

// ---- words for the docs --------------------------------------------------------------------

namespace
{
std::string WithUnit(const std::string& text, const ValueType& t)
{
  return t.Unit.empty() ? text : text + ", " + t.Unit;
}

// "[density, r, g, b]" -> "r, g, b": the names of a point's values after its density.
std::string PointValues(const std::string& form)
{
  const std::string inside = form.substr(1, form.size() - 2);
  const auto comma = inside.find(", ");
  return comma == std::string::npos ? inside : inside.substr(comma + 2);
}
}

std::string TypeWords(const ValueType& t)
{
  if (!t.TypeText.empty())
  {
    return WithUnit(t.TypeText, t);
  }
  const std::string form = t.Form.empty() ? "" : " `" + t.Form + "`";
  switch (t.Type)
  {
    case ValueType::Number:
      return WithUnit("number", t);
    case ValueType::Integer:
      return WithUnit("integer", t);
    case ValueType::Boolean:
      return "boolean";
    case ValueType::Text:
    case ValueType::Choice:
      return "string";
    case ValueType::Numbers:
      return WithUnit(std::to_string(t.Count) + " numbers" + form, t);
    case ValueType::Integers:
      return WithUnit(
        (t.OneFillsAll ? "integer, or " : "") + std::to_string(t.Count) + " integers" + form, t);
    case ValueType::Points:
      return "list of" + form;
    case ValueType::Custom:
      break;
  }
  return "";
}

std::string AllowedWords(const ValueType& t)
{
  const std::string integers = "[" + std::to_string(t.Min) + ", " + std::to_string(t.Max) + "]";
  switch (t.Type)
  {
    case ValueType::Number:
      return t.Allowed.Text(true);
    case ValueType::Integer:
    {
      if (t.OneFillsAll || t.OneOf.empty())
      {
        return integers;
      }
      std::vector<std::string> choices;
      for (long long choice : t.OneOf)
      {
        choices.push_back(std::to_string(choice));
      }
      return Join(choices, " or ");
    }
    case ValueType::Choice:
    {
      std::vector<std::string> names;
      for (const Name& name : t.Names)
      {
        names.push_back(
          "`\"" + name.Text + "\"`" + (name.Help.empty() ? "" : " (" + name.Help + ")"));
      }
      return names.size() < 2
        ? Join(names)
        : Join(std::vector<std::string>(names.begin(), names.end() - 1)) + " or " + names.back();
    }
    case ValueType::Numbers:
    {
      const std::string range = t.Allowed.Text(true);
      return range == "any"
        ? range
        : "each " + (range[0] == '[' || range[0] == '(' ? "in " + range : range);
    }
    case ValueType::Integers:
      return "each in " + integers;
    case ValueType::Points:
      return "at least one point; " + PointValues(t.Form) + " in " + t.Allowed.Text(true) +
        "; densities strictly increasing";
    case ValueType::Boolean:
    case ValueType::Text:
    case ValueType::Custom:
      break;
  }
  return "";
}

std::string ShowValue(const json& value)
{
  if (value.is_array())
  {
    std::vector<std::string> items;
    for (const json& item : value)
    {
      items.push_back(ShowValue(item));
    }
    return "[" + Join(items) + "]";
  }
  if (!value.is_number() || value.is_number_integer())
  {
    return value.dump(); // integers exactly: 2^30 voxels is 1073741824, not the float 1073741800
  }
  // A float member was written as the double it widens to (0.6f is 0.60000002384185791): show
  // the shortest decimal that reads back as that float.
  const double number = value.get<double>();
  if (double(float(number)) == number)
  {
    for (int digits = 1; digits < 9; ++digits)
    {
      char text[32];
      std::snprintf(text, sizeof(text), "%.*g", digits, number);
      if (float(std::strtod(text, nullptr)) == float(number))
      {
        return FormatNumber(std::strtod(text, nullptr));
      }
    }
  }
  return FormatNumber(number);
}

} // namespace schema
} // namespace cloudvis
