/*=========================================================================
 *
 *  Copyright NumFOCUS
 *
 *  Licensed under the Apache License, Version 2.0 (the "License");
 *  you may not use this file except in compliance with the License.
 *  You may obtain a copy of the License at
 *
 *         https://www.apache.org/licenses/LICENSE-2.0.txt
 *
 *  Unless required by applicable law or agreed to in writing, software
 *  distributed under the License is distributed on an "AS IS" BASIS,
 *  WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
 *  See the License for the specific language governing permissions and
 *  limitations under the License.
 *
 *=========================================================================*/
#include "itkTorusImplicitSurface.h"
#include "itkImplicitSurfaceTestHelpers.h"

using namespace ImplicitSurfaceTest;

TEST(TorusImplicitSurface, DistanceMatchesClosedFormsOnAxisPlaneAndTube)
{
  auto torus = itk::TorusImplicitSurface::New();
  torus->SetRadii(3, 1);
  EXPECT_NEAR(torus->Evaluate(P(0, 0, 0)), 2.0, 1e-15);                         // centre
  EXPECT_NEAR(torus->Evaluate(P(0, 0, 4)), std::sqrt(9.0 + 16.0) - 1.0, 1e-15); // on the axis
  EXPECT_NEAR(torus->Evaluate(P(3, 0, 0)), -1.0, 1e-15);                        // core circle
  EXPECT_NEAR(torus->Evaluate(P(0, -3, 0.25)), -0.75, 1e-15);                   // inside the tube
  EXPECT_NEAR(torus->Evaluate(P(6, 0, 0)), 2.0, 1e-15);                         // outside, equator
  EXPECT_NEAR(torus->Evaluate(P(0, 3, 2)), 1.0, 1e-15);                         // above the core
  ExpectConsistentAt(*torus, P(0, 0, 0), "torus centre");
  ExpectConsistentAt(*torus, P(3, 0, 0), "torus core circle");
  ExpectConsistentAt(*torus, P(0, 0, 4), "torus axis");
}

TEST(TorusImplicitSurface, TiltedAxisMovesTheDistanceField)
{
  auto local = itk::TorusImplicitSurface::New();
  local->SetRadii(4, 1.5);
  auto             moved = itk::TorusImplicitSurface::New();
  const MatrixType r = Rotation(0.3, 0.8, 0.1);
  const PointType  c = P(1, -1, 2);
  moved->SetCenter(c);
  moved->SetAxis(r * V(0, 0, 7)); // any length
  moved->SetRadii(4, 1.5);
  for (const PointType & q : RandomPoints(P(-6, -6, -3), P(6, 6, 3), 0.0, 500, 51))
  {
    EXPECT_NEAR(moved->Evaluate(Transform(r, c, q)), local->Evaluate(q), 1e-9) << q;
  }
}

TEST(TorusImplicitSurface, MinorRadiusNotBelowMajorRadiusIsRejectedWhenUsed)
{
  auto torus = itk::TorusImplicitSurface::New();
  ExpectThrowsMentioning([&] { torus->SetMinorRadius(0); }, "MinorRadius");
  ExpectThrowsMentioning([&] { torus->SetMajorRadius(-2); }, "MajorRadius");
  ExpectThrowsMentioning([&] { torus->SetAxis(V(0, 0, 0)); }, "Axis");
  // Changing both radii one at a time may pass through an invalid state...
  torus->SetMinorRadius(5);
  EXPECT_FALSE(torus->AreParametersValid());
  ExpectThrowsMentioning([&] { torus->Evaluate(P(0, 0, 0)); }, "MinorRadius");
  ExpectThrowsMentioning([&] { torus->VerifyParameters(); }, "MajorRadius");
  // ... and is accepted once the combination is valid.
  torus->SetMajorRadius(10);
  EXPECT_TRUE(torus->AreParametersValid());
  EXPECT_NEAR(torus->Evaluate(P(0, 0, 0)), 5.0, 1e-15);
  ExpectThrowsMentioning(
    [&] {
      torus->SetRadii(2, 2);
      torus->Evaluate(P(0, 0, 0));
    },
    "MinorRadius");
}
