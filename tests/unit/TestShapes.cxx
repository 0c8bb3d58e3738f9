// Signed distances at known points for every shape, placement, unions and the morph timeline.
#include "CloudShapes.h"

#include <gtest/gtest.h>

using namespace cloudvis;

TEST(Sdf, SphereBoxTorusCrossCapsuleAtKnownPoints)
{
  EXPECT_FLOAT_EQ(sdf::Sphere(glm::vec3(0.0f), 1.5f), -1.5f);
  EXPECT_FLOAT_EQ(sdf::Sphere(glm::vec3(3.0f, 0.0f, 0.0f), 1.0f), 2.0f);

  const glm::vec3 half(1.0f, 2.0f, 3.0f);
  EXPECT_FLOAT_EQ(sdf::Box(glm::vec3(0.0f), half), -1.0f);
  EXPECT_FLOAT_EQ(sdf::Box(glm::vec3(4.0f, 0.0f, 0.0f), half), 3.0f);
  EXPECT_FLOAT_EQ(sdf::Box(glm::vec3(4.0f, 6.0f, 0.0f), half), 5.0f); // 3-4-5 to the edge

  // Torus around y: the tube's centre line is the circle of radius 1.3 in the xz plane.
  EXPECT_FLOAT_EQ(sdf::Torus(glm::vec3(1.3f, 0.0f, 0.0f), 1.3f, 0.9f), -0.9f);
  EXPECT_FLOAT_EQ(sdf::Torus(glm::vec3(0.0f), 1.3f, 0.9f), 0.4f);
  EXPECT_FLOAT_EQ(sdf::Torus(glm::vec3(0.0f, 0.0f, 3.2f), 1.3f, 0.9f), 1.0f);

  EXPECT_FLOAT_EQ(sdf::Cross(glm::vec3(0.0f), 0.6f, 3.0f), -0.6f);
  EXPECT_FLOAT_EQ(sdf::Cross(glm::vec3(2.0f, 0.0f, 0.0f), 0.6f, 3.0f), -0.6f); // inside an arm
  EXPECT_FLOAT_EQ(sdf::Cross(glm::vec3(2.0f, 2.0f, 0.0f), 0.6f, 3.0f), 1.4f);  // between arms
  EXPECT_FLOAT_EQ(sdf::Cross(glm::vec3(4.0f, 0.0f, 0.0f), 0.6f, 3.0f), 1.0f);  // past an arm's end

  const glm::vec3 a(-2.0f, -1.5f, 0.0f), b(2.0f, 1.5f, 0.0f);
  EXPECT_FLOAT_EQ(sdf::Capsule(glm::vec3(0.0f), a, b, 1.0f), -1.0f);
  EXPECT_FLOAT_EQ(sdf::Capsule(glm::vec3(0.0f, 0.0f, 2.5f), a, b, 1.0f), 1.5f);
  EXPECT_FLOAT_EQ(sdf::Capsule(glm::vec3(5.2f, 3.9f, 0.0f), a, b, 1.0f), 3.0f); // beyond b
}

TEST(Sdf, SmoothMinRoundsTheSeamAndMatchesMinFarFromIt)
{
  EXPECT_FLOAT_EQ(sdf::SmoothMin(1.0f, 3.0f, 0.5f), 1.0f);
  EXPECT_FLOAT_EQ(sdf::SmoothMin(1.0f, 1.0f, 0.5f), 1.0f - 0.125f);
  EXPECT_FLOAT_EQ(sdf::SmoothMin(1.0f, 1.0f, 0.0f), 1.0f);
}

TEST(PlacedShape, TranslationRotationAndScaleMoveTheShape)
{
  Shape box;
  box.Type = ShapeType::Box;
  box.HalfSize = glm::vec3(2.0f, 0.5f, 0.5f);
  box.Center = glm::vec3(1.0f, 1.0f, 1.0f);
  box.RotationDegrees = glm::vec3(0.0f, 0.0f, 90.0f); // long axis now along y
  box.Scale = 2.0f;
  const PlacedShape placed(box);
  EXPECT_NEAR(placed.SignedDistance(glm::vec3(1.0f, 1.0f, 1.0f)), -1.0f, 1e-5f);
  // The long axis reaches 2 * 2 = 4 along y, but only 2 * 0.5 = 1 along x.
  EXPECT_NEAR(placed.SignedDistance(glm::vec3(1.0f, 4.5f, 1.0f)), -0.5f, 1e-5f);
  EXPECT_NEAR(placed.SignedDistance(glm::vec3(3.0f, 1.0f, 1.0f)), 1.0f, 1e-5f);
}

TEST(Morph, SlotsHoldOneShapeAndBlendIntoTheNext)
{
  for (int k = 0; k < 8; ++k)
  {
    const MorphTimeline::Phase start = MorphTimeline::At(3.0 * k);
    EXPECT_EQ(start.From, k % 4);
    EXPECT_EQ(start.Blend, 0.0f);
    // A shape holds until the last 1.2 s of its slot.
    EXPECT_EQ(MorphTimeline::At(3.0 * k + 1.79).Blend, 0.0f);
    const MorphTimeline::Phase mid = MorphTimeline::At(3.0 * k + 2.4);
    EXPECT_EQ(mid.To, (k + 1) % 4);
    EXPECT_NEAR(mid.Blend, 0.5f, 1e-6f);
  }
  EXPECT_EQ(MorphTimeline::At(-3.0).From, 3); // time before 0 wraps around the cycle
}
