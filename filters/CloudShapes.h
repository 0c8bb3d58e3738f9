// Signed distance functions of the shapes clouds are made from, their placement, unions, and
// the morph timeline of the write-ups. Negative inside, positive outside, in world units.
//
// Written with GLM, whose functions mirror GLSL's, so that the shapes could move to the GPU as
// they are (docs/transport.md).
#ifndef CloudShapes_h
#define CloudShapes_h

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <vector>

namespace cloudvis
{
namespace sdf
{

inline float Sphere(glm::vec3 p, float radius)
{
  return glm::length(p) - radius;
}

inline float Box(glm::vec3 p, glm::vec3 halfSize)
{
  const glm::vec3 q = glm::abs(p) - halfSize;
  return glm::length(glm::max(q, 0.0f)) + glm::min(glm::max(q.x, glm::max(q.y, q.z)), 0.0f);
}

// A torus around the y axis: majorRadius to the tube's centre line, minorRadius of the tube.
inline float Torus(glm::vec3 p, float majorRadius, float minorRadius)
{
  const glm::vec2 q(glm::length(glm::vec2(p.x, p.z)) - majorRadius, p.y);
  return glm::length(q) - minorRadius;
}

// Three bars along x, y and z, each of half-width armWidth and half-length armLength.
inline float Cross(glm::vec3 p, float armWidth, float armLength)
{
  const float bx = Box(p, glm::vec3(armLength, armWidth, armWidth));
  const float by = Box(p, glm::vec3(armWidth, armLength, armWidth));
  const float bz = Box(p, glm::vec3(armWidth, armWidth, armLength));
  return glm::min(bx, glm::min(by, bz));
}

inline float Capsule(glm::vec3 p, glm::vec3 a, glm::vec3 b, float radius)
{
  const glm::vec3 pa = p - a, ba = b - a;
  const float h = glm::clamp(glm::dot(pa, ba) / glm::dot(ba, ba), 0.0f, 1.0f);
  return glm::length(pa - ba * h) - radius;
}

// Polynomial smooth minimum: equals min(a, b) where they differ by more than radius and
// rounds the seam in between.
inline float SmoothMin(float a, float b, float radius)
{
  if (radius <= 0.0f)
  {
    return glm::min(a, b);
  }
  const float h = glm::max(radius - glm::abs(a - b), 0.0f) / radius;
  return glm::min(a, b) - h * h * radius * 0.25f;
}

} // namespace sdf

enum class ShapeType
{
  Sphere,
  Box,
  Torus,
  Cross,
  Capsule,
};

// One shape with its placement: p_local = R^-1 (p - Center) / Scale, distance scaled back.
// Only the parameters of its Type are used.
struct Shape
{
  ShapeType Type = ShapeType::Sphere;
  glm::vec3 Center{ 0.0f };
  glm::vec3 RotationDegrees{ 0.0f }; // applied about x, then y, then z
  float Scale = 1.0f;

  float Radius = 1.0f;                   // sphere, capsule
  glm::vec3 HalfSize{ 1.0f };            // box
  float MajorRadius = 1.3f;              // torus
  float MinorRadius = 0.9f;              // torus
  float ArmWidth = 0.6f;                 // cross
  float ArmLength = 3.0f;                // cross
  glm::vec3 EndA{ -2.0f, -1.5f, 0.0f };  // capsule
  glm::vec3 EndB{ 2.0f, 1.5f, 0.0f };    // capsule
};

enum class ShapeBlend
{
  Union,       // min of the distances
  SmoothUnion, // smooth minimum with a blend radius
};

// A shape with its world-to-local transform computed once.
class PlacedShape
{
public:
  explicit PlacedShape(const Shape& shape)
    : Description(shape)
  {
    const glm::vec3 r = glm::radians(shape.RotationDegrees);
    glm::mat4 rotation(1.0f);
    rotation = glm::rotate(rotation, r.z, glm::vec3(0, 0, 1));
    rotation = glm::rotate(rotation, r.y, glm::vec3(0, 1, 0));
    rotation = glm::rotate(rotation, r.x, glm::vec3(1, 0, 0));
    // The inverse of a rotation is its transpose.
    this->WorldToLocal = glm::transpose(glm::mat3(rotation));
    this->Rotated = shape.RotationDegrees != glm::vec3(0.0f);
    this->InverseScale = 1.0f / shape.Scale;
  }

  float SignedDistance(glm::vec3 p) const
  {
    const Shape& s = this->Description;
    // Most shapes are not rotated: skip the matrix on the per-voxel path.
    glm::vec3 q = p - s.Center;
    if (this->Rotated)
    {
      q = this->WorldToLocal * q;
    }
    q *= this->InverseScale;
    float d = 0.0f;
    switch (s.Type)
    {
      case ShapeType::Sphere:
        d = sdf::Sphere(q, s.Radius);
        break;
      case ShapeType::Box:
        d = sdf::Box(q, s.HalfSize);
        break;
      case ShapeType::Torus:
        d = sdf::Torus(q, s.MajorRadius, s.MinorRadius);
        break;
      case ShapeType::Cross:
        d = sdf::Cross(q, s.ArmWidth, s.ArmLength);
        break;
      case ShapeType::Capsule:
        d = sdf::Capsule(q, s.EndA, s.EndB, s.Radius);
        break;
    }
    return d * s.Scale;
  }

private:
  Shape Description;
  glm::mat3 WorldToLocal{ 1.0f };
  bool Rotated = false;
  float InverseScale = 1.0f;
};

// The morph of the write-ups: torus -> cross -> sphere -> capsule -> torus, one shape per 3 s
// slot, each slot ending with a 1.2 s smoothstep blend of the distances into the next shape.
struct MorphTimeline
{
  static constexpr double SlotSeconds = 3.0;
  static constexpr double BlendSeconds = 1.2;
  static constexpr int NumberOfShapes = 4;
  static constexpr double PeriodSeconds = SlotSeconds * NumberOfShapes;

  static std::vector<Shape> Shapes()
  {
    Shape torus;
    torus.Type = ShapeType::Torus;
    torus.MajorRadius = 1.3f;
    torus.MinorRadius = 0.9f;
    torus.RotationDegrees = glm::vec3(90.0f, 0.0f, 0.0f); // ring facing the +z camera
    Shape cross;
    cross.Type = ShapeType::Cross; // the write-ups evaluate it at 2p: scale 0.5
    cross.ArmWidth = 0.6f;
    cross.ArmLength = 3.0f;
    cross.Scale = 0.5f;
    Shape sphere;
    sphere.Type = ShapeType::Sphere;
    sphere.Radius = 1.5f;
    Shape capsule;
    capsule.Type = ShapeType::Capsule;
    capsule.EndA = glm::vec3(-2.0f, -1.5f, 0.0f);
    capsule.EndB = glm::vec3(2.0f, 1.5f, 0.0f);
    capsule.Radius = 1.0f;
    return { torus, cross, sphere, capsule };
  }

  // Which shape a time starts from, and how far the blend into the next one has gone.
  struct Phase
  {
    int From;
    int To;
    float Blend;
  };
  static Phase At(double time)
  {
    const double slot = std::floor(time / SlotSeconds);
    const double inSlot = time - slot * SlotSeconds;
    int from = static_cast<int>(std::fmod(slot, double(NumberOfShapes)));
    from = (from + NumberOfShapes) % NumberOfShapes;
    const float t = glm::clamp(
      static_cast<float>((inSlot - (SlotSeconds - BlendSeconds)) / BlendSeconds), 0.0f, 1.0f);
    return { from, (from + 1) % NumberOfShapes, t * t * (3.0f - 2.0f * t) };
  }
};

} // namespace cloudvis

#endif
