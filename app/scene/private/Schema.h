// The building blocks of the scene schema (SceneSchema.cxx holds the schema itself). A key of a
// scene file is one Key<S> entry: its name, its ValueType (number, integer, names, arrays...,
// with its range or names), the member of S its value lands in, and its help text. From that one
// entry:
//   - Check() tests a JSON value against the ValueType and reports what is wrong in the one
//     message shape "<source>: <dotted key>: <problem>" (Context::Fail);
//   - Assign() / ToJson() move the value between JSON and the member, whatever its C++ type
//     (double, float, glm::vec3, an enumeration...), so reading and writing a scene
//     (SceneJson.cxx) use the same entry;
//   - the reference tables of docs/scene-format.md show the key's type, its default (the member
//     of a default-constructed S) and what is allowed (SceneReference.cxx).
// Everything here is generic; nothing names a scene key.
#ifndef cloudvis_Schema_h
#define cloudvis_Schema_h

#include "Words.h" // Join, which the schema's messages use throughout

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace cloudvis
{
namespace schema
{
using json = nlohmann::json;

// Where the document came from, for messages and relative paths.
struct Context
{
  std::string Source;
  std::string BaseDirectory;
  // Dotted keys set on the command line, each with the option that set it; the last one to
  // set a key is the one whose value is checked.
  std::vector<std::pair<std::string, std::string>> OverriddenKeys;

  // Throws InputError "<source>: <key>: <problem>", adding "(set with --option)" when the key
  // or one of its parents was set on the command line.
  [[noreturn]] void Fail(const std::string& key, const std::string& problem) const;
};

// "number 3", "string \"six\"": a value's JSON type and (shortened) text, for messages.
std::string Describe(const json& value);
// Up to 10 significant digits, no trailing zeros: 0.25, 1e+06, 4294967295.
std::string FormatNumber(double value);

// An allowed interval of a number, and its description for messages and docs.
struct Range
{
  double Min = -std::numeric_limits<double>::max();
  double Max = std::numeric_limits<double>::max();
  bool MinOpen = false; // true: Min itself is excluded
  bool MaxOpen = false; // true: Max itself is excluded

  bool Contains(double v) const;
  // "[0, 1]", "(0, 1000000]", "> 0", ">= 0", or "any finite number" / "any" (forDocs).
  std::string Text(bool forDocs = false) const;
};
inline constexpr Range AnyNumber{};
inline constexpr Range NonNegative{ 0.0 };                                        // >= 0
inline constexpr Range Positive{ 0.0, std::numeric_limits<double>::max(), true }; // > 0
inline constexpr Range UnitInterval{ 0.0, 1.0 };                                  // [0, 1]

// One name of an enumeration: its text in scene files, the value it stands for (the
// enumerator, as an integer), and what it means (for the docs; may be empty).
struct Name
{
  std::string Text;
  int Value = 0;
  std::string Help;
};

// The names of an enumeration E, in the order scene files list them.
template<typename E>
std::vector<Name> NamesOf(std::initializer_list<std::pair<const char*, E>> names)
{
  std::vector<Name> result;
  for (const auto& entry : names)
  {
    result.push_back({ entry.first, static_cast<int>(entry.second), "" });
  }
  return result;
}
std::vector<std::string> TextsOf(const std::vector<Name>& names);
// The name of `value` (empty when there is none).
std::string NameOf(const std::vector<Name>& names, int value);

// What a key's value may be.
struct ValueType
{
  enum Kind
  {
    Number,   // a finite number in Allowed
    Integer,  // an integer (6 or 6.0, never 6.5) in [Min, Max], and one of OneOf when given
    Boolean,  // true or false
    Text,     // a string; Expected says what it should be in messages
    Choice,   // one of Names
    Numbers,  // an array of Count numbers, each in Allowed
    Integers, // an array of Count integers, each in [Min, Max]; OneFillsAll: or one integer
    Points,   // a non-empty list of points [density, v1, ...] of Count numbers each: v in
              // Allowed, densities strictly increasing (a transfer function's control points)
    Custom,   // read and written by the key's own functions; TypeText describes it
  };
  Kind Type = Custom;
  Range Allowed;
  long long Min = 0;
  long long Max = 0;
  std::vector<long long> OneOf;
  size_t Count = 0;
  bool OneFillsAll = false;
  std::string Form; // what the array's numbers are: "[width, height]", "[density, opacity]"
  std::vector<Name> Names;
  std::string Expected;     // Text: "a string", "a preset name or the path of a .json file"
  bool NonEmpty = false;    // Text: the empty string is refused
  bool IsPath = false;      // Text: a path, relative to the scene file's folder unless absolute
  bool StrictNames = false; // Choice: every refusal reads "expected "a" or "b", got ..."
  // A check beyond the kind's, on the value as written (a path before it is resolved), run once
  // the kind's own checks pass: returns the problem, or empty.
  using ValueCheck = std::string (*)(const json& value);
  ValueCheck Refuse = nullptr;
  // A value an earlier version of the format gave this key, refused before the kind's own checks
  // with words that say what to write now: returns that, or empty for any other value.
  ValueCheck Outdated = nullptr;

  // For the docs only.
  std::string Unit;        // "degrees", "world units": added to the type column
  std::string TypeText;    // the type column, where the kind's own words do not fit
  std::string DefaultText; // the default column, where the default is not a value
  bool Required = false;   // the key must be given (typed objects: a light's position)

  ValueType In(std::string unit) const;
  ValueType Described(std::string typeText) const;
  ValueType DefaultIs(std::string defaultText) const;
  ValueType Mandatory() const;
  ValueType CheckedBy(ValueCheck refuse) const;
  ValueType RefusesOutdated(ValueCheck outdated) const;
};

ValueType NumberIn(const Range& allowed);
ValueType IntegerIn(long long min, long long max);
ValueType IntegerOneOf(std::vector<long long> values);
ValueType Boolean();
ValueType Text(std::string expected = "a string");
ValueType NonEmptyText(std::string expected);
ValueType Path(std::string expected); // non-empty, resolved against the scene file's folder
ValueType ChoiceOf(std::vector<Name> names);
ValueType NumbersIn(size_t count, const Range& allowed, std::string form = "");
ValueType IntegersIn(size_t count, long long min, long long max, std::string form = "");
// An array of `count` integers, or one integer that stands for all of them.
ValueType IntegerOrIntegersIn(size_t count, long long min, long long max, std::string form);
ValueType PointsIn(size_t count, const Range& allowed, std::string form);
ValueType CustomValue(std::string typeText);

// Fails through `c` naming `key` when the string `text` holds a NUL character: JSON allows
// "\u0000", but a path or a name holding one is cut short there by every system call (and was
// read as its first part). Every Text value is checked, and so is each custom key that takes a
// path (field.cloud.coverage_map).
void RefuseNul(const Context& c, const std::string& key, const std::string& text);

// Checks `value` against `type` (its Outdated first, its Refuse last) and returns it in the form
// members are assigned from: a choice as its integer value, one integer that fills an array as the
// array, a path resolved against the context's base directory. Fails through `c` naming `key`.
json Check(const Context& c, const ValueType& type, const json& value, const std::string& key);

// The value as a scene file writes it: a choice by its name, numbers as they are.
json Present(const ValueType& type, const json& value);

// The docs' words for a type: its type column ("3 numbers, degrees") and the allowed values
// ("each in [0, 1]"; empty where the help says it all).
std::string TypeWords(const ValueType& type);
std::string AllowedWords(const ValueType& type);
// A value as the docs show it: `[0.5, -0.1, -0.5]`, `"value"`.
std::string ShowValue(const json& value);

// ---- JSON <-> member, by the member's C++ type ----------------------------------------------
// Assign takes a value Check returned; ToJson gives what Check would return for it.

inline void Assign(const json& v, double& m)
{
  m = v.get<double>();
}
inline void Assign(const json& v, float& m)
{
  m = float(v.get<double>());
}
inline void Assign(const json& v, int& m)
{
  m = int(v.get<long long>());
}
inline void Assign(const json& v, std::uint32_t& m)
{
  m = std::uint32_t(v.get<long long>());
}
inline void Assign(const json& v, std::uint64_t& m)
{
  m = std::uint64_t(v.get<long long>());
}
inline void Assign(const json& v, bool& m)
{
  m = v.is_boolean() ? v.get<bool>() : v.get<int>() != 0;
}
inline void Assign(const json& v, std::string& m)
{
  m = v.get<std::string>();
}
void Assign(const json& v, glm::vec3& m);
void Assign(const json& v, glm::dvec3& m);
template<typename E, typename = std::enable_if_t<std::is_enum<E>::value>>
void Assign(const json& v, E& m)
{
  m = static_cast<E>(v.get<int>());
}
template<typename T, size_t N>
void Assign(const json& v, std::array<T, N>& m)
{
  for (size_t i = 0; i < N; ++i)
  {
    Assign(v[i], m[i]);
  }
}
template<typename T>
void Assign(const json& v, std::vector<T>& m)
{
  m.assign(v.size(), T{});
  for (size_t i = 0; i < v.size(); ++i)
  {
    Assign(v[i], m[i]);
  }
}
template<typename T>
void Assign(const json& v, std::optional<T>& m)
{
  T value{};
  Assign(v, value);
  m = value;
}

inline json ToJson(double m)
{
  return m;
}
inline json ToJson(float m)
{
  return double(m);
}
inline json ToJson(int m)
{
  return m;
}
inline json ToJson(std::uint32_t m)
{
  return m;
}
inline json ToJson(std::uint64_t m)
{
  return m;
}
inline json ToJson(bool m)
{
  return m;
}
inline json ToJson(const std::string& m)
{
  return m;
}
json ToJson(const glm::vec3& m);
json ToJson(const glm::dvec3& m);
template<typename E, typename = std::enable_if_t<std::is_enum<E>::value>>
json ToJson(E m)
{
  return static_cast<int>(m);
}
template<typename T, size_t N>
json ToJson(const std::array<T, N>& m);
template<typename T>
json ToJson(const std::vector<T>& m);
// A container of members as a JSON array (the overloads above, declared first so that an array
// of arrays finds them).
template<typename Container>
json ToJsonArray(const Container& members)
{
  json a = json::array();
  for (const auto& x : members)
  {
    a.push_back(ToJson(x));
  }
  return a;
}
template<typename T, size_t N>
json ToJson(const std::array<T, N>& m)
{
  return ToJsonArray(m);
}
template<typename T>
json ToJson(const std::vector<T>& m)
{
  return ToJsonArray(m);
}
template<typename T>
json ToJson(const std::optional<T>& m)
{
  return m ? ToJson(*m) : json();
}

// ---- keys ----------------------------------------------------------------------------------

// A key of an object of the scene, whose value lands in an S.
template<typename S>
struct Key
{
  using Reader = std::function<void(const Context&, const json&, const std::string& key, S&)>;
  using Writer = std::function<json(const S&)>; // null: nothing to write
  // After the value is stored: a check that needs the stored value (it may also normalize it).
  // Returns the problem, or empty.
  using Then = std::string (*)(S&);

  std::string Name;
  ValueType Type;
  std::string Help;
  Reader Read;
  Writer Write;
  // Typed objects (shapes, lights, backgrounds): a bit per value of the object's "type" that
  // uses the key.
  unsigned UsedBy = ~0u;
  // A key whose value is an object of keys (a section, camera.orbit): the type of a dotted key
  // inside it (null when there is none).
  std::function<const ValueType*(const std::string& dotted)> Inner;

  // A key stored in a member of S. `member` is a pointer to a member of S, or a function that
  // returns a reference to the member (Nested, for a member of a member).
  template<typename Member>
  Key(std::string name,
    ValueType type,
    Member member,
    std::string help,
    unsigned usedBy = ~0u,
    Then then = nullptr)
    : Name(std::move(name))
    , Type(std::move(type))
    , Help(std::move(help))
    , UsedBy(usedBy)
  {
    const ValueType& t = this->Type; // copied into the lambdas below: a Key may be copied
    this->Read = [member, then, t](const Context& c, const json& v, const std::string& key, S& s)
    {
      Assign(Check(c, t, v, key), std::invoke(member, s));
      const std::string problem = then ? then(s) : std::string();
      if (!problem.empty())
      {
        c.Fail(key, problem);
      }
    };
    this->Write = [member, t](const S& s)
    { return Present(t, ToJson(std::invoke(member, const_cast<S&>(s)))); };
  }

  // A key with its own reader and writer (a section, a sub-object, a list).
  Key(std::string name,
    ValueType type,
    Reader read,
    Writer write,
    std::string help,
    std::function<const ValueType*(const std::string&)> inner = {})
    : Name(std::move(name))
    , Type(std::move(type))
    , Help(std::move(help))
    , Read(std::move(read))
    , Write(std::move(write))
    , Inner(std::move(inner))
  {
  }
};

template<typename S>
using Keys = std::vector<Key<S>>;

// A member of a member, as a Key's `member`: Nested(&FieldSpec::Description,
// &FieldDescription::Model) is f.Description.Model.
template<typename S, typename M1, typename M2>
auto Nested(M1 S::*outer, M2 M1::*inner)
{
  return [outer, inner](S& s) -> M2& { return (s.*outer).*inner; };
}
template<typename S, typename M1, typename M2, typename M3>
auto Nested(M1 S::*outer, M2 M1::*middle, M3 M2::*inner)
{
  return [outer, middle, inner](S& s) -> M3& { return ((s.*outer).*middle).*inner; };
}

template<typename S>
std::vector<std::string> KeyNames(const Keys<S>& keys, unsigned type = ~0u)
{
  std::vector<std::string> names;
  for (const Key<S>& key : keys)
  {
    if (key.UsedBy & type)
    {
      names.push_back(key.Name);
    }
  }
  return names;
}

template<typename S>
const Key<S>* FindKey(const Keys<S>& keys, const std::string& name)
{
  for (const Key<S>& key : keys)
  {
    if (key.Name == name)
    {
      return &key;
    }
  }
  return nullptr;
}

// The type of a dotted key ("march.g1") among `keys` and the objects inside them, or null.
template<typename S>
const ValueType* FindType(const Keys<S>& keys, const std::string& dotted)
{
  const auto dot = dotted.find('.');
  const Key<S>* key = FindKey(keys, dotted.substr(0, dot));
  if (!key || dot == std::string::npos)
  {
    return key ? &key->Type : nullptr;
  }
  return key->Inner ? key->Inner(dotted.substr(dot + 1)) : nullptr;
}

// The type of dotted keys inside the object `keys()` describes (Key::Inner).
template<typename S>
std::function<const ValueType*(const std::string&)> Inside(const Keys<S>& (*keys)())
{
  return [keys](const std::string& dotted) { return FindType(keys(), dotted); };
}

// Reads every member of an object through `keys`, refusing keys the table lacks.
template<typename S>
void ReadObject(const Context& c,
  const json& object,
  const std::string& key,
  const Keys<S>& keys,
  S& target)
{
  if (!object.is_object())
  {
    c.Fail(key, "expected an object, got " + Describe(object));
  }
  for (const auto& member : object.items())
  {
    const std::string memberKey = key.empty() ? member.key() : key + "." + member.key();
    const Key<S>* entry = FindKey(keys, member.key());
    if (!entry)
    {
      c.Fail(memberKey, "unknown key; allowed keys: " + Join(KeyNames(keys)));
    }
    entry->Read(c, member.value(), memberKey, target);
  }
}

// The object `keys` write for `source` (the keys used by `type` only), leaving out null values.
template<typename S>
json WriteObject(const Keys<S>& keys, const S& source, unsigned type = ~0u)
{
  json object = json::object();
  for (const Key<S>& key : keys)
  {
    if ((key.UsedBy & type) && key.Write)
    {
      json value = key.Write(source);
      if (!value.is_null())
      {
        object[key.Name] = std::move(value);
      }
    }
  }
  return object;
}

} // namespace schema
} // namespace cloudvis

#endif
