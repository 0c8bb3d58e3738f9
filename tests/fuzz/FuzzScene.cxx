// Fuzz target: a scene file's bytes through LoadScene, the entry point of every command that
// takes a scene (read, parse JSON, validate every section), then the procedural field's own
// checks (ValidateProceduralField: geometry, shapes, noise range) that run before generation.
// Contract: any input is either accepted or refused with an InputError; anything else (another
// exception, a crash, undefined behaviour, a leak) is a bug.
#include "FuzzInput.h"

#include "Errors.h"
#include "Scene.h"
#include "SceneField.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string& path = cloudvis::fuzz::WriteInputFile("input.json", data, size);
  try
  {
    const cloudvis::Scene scene = cloudvis::LoadScene(path, {});
    if (!scene.Field.FromFile())
    {
      (void)cloudvis::ValidateProceduralField(scene.Field);
    }
  }
  catch (const cloudvis::InputError&)
  {
    // refused with a message: the expected outcome for most inputs
  }
  return 0;
}
