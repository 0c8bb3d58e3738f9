// Fuzz target: command-line overrides. Each line of the input is one --set argument
// (KEY=VALUE), applied in order to the default scene by LoadScene (ApplyOverride,
// ParseOverrideValue, SetDocumentValue), then validated as `cloudvis generate --set ...` would.
// Contract: UsageError (a malformed assignment) or InputError (a bad value), nothing else.
#include "FuzzInput.h"

#include "Errors.h"
#include "Scene.h"
#include "SceneField.h"

#include <algorithm>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  std::vector<std::string> assignments;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::size_t start = 0;
  while (start <= text.size())
  {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    assignments.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  try
  {
    const cloudvis::Scene scene = cloudvis::LoadScene("", assignments);
    if (!scene.Field.FromFile())
    {
      (void)cloudvis::ValidateProceduralField(scene.Field);
    }
  }
  catch (const cloudvis::UsageError&)
  {
  }
  catch (const cloudvis::InputError&)
  {
  }
  return 0;
}
