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
#include "itkBoxImplicitSurface.h"
#include "itkImplicitSurfaceTestHelpers.h"

using namespace ImplicitSurfaceTest;

TEST(BoxImplicitSurface, DistanceToFacesEdgesAndCornersMatchesClosedForms)
{
  auto box = itk::BoxImplicitSurface::New();
  box->SetHalfSizes(V(3, 2, 1));
  EXPECT_NEAR(box->Evaluate(P(0, 0, 0)), -1.0, 1e-15);                        // centre: nearest face z
  EXPECT_NEAR(box->Evaluate(P(2.5, 0, 0)), -0.5, 1e-15);                      // nearest face x
  EXPECT_NEAR(box->Evaluate(P(5, 0, 0)), 2.0, 1e-15);                         // outside a face
  EXPECT_NEAR(box->Evaluate(P(4, 3, 0)), std::sqrt(2.0), 1e-15);              // outside an edge
  EXPECT_NEAR(box->Evaluate(P(4, -3, 3)), std::sqrt(1.0 + 1.0 + 4.0), 1e-15); // corner
  ExpectConsistentAt(*box, P(0, 0, 0), "box centre");
  ExpectConsistentAt(*box, P(2.5, 1.5, 0.5), "box inside near a corner");
}

TEST(BoxImplicitSurface, RotationAndTranslationMoveTheDistanceField)
{
  auto local = itk::BoxImplicitSurface::New();
  local->SetHalfSizes(V(3, 2, 0.25));
  auto             moved = itk::BoxImplicitSurface::New();
  const MatrixType r = Rotation(-0.5, 0.2, 0.9);
  const PointType  c = P(10, 0, -3);
  moved->SetHalfSizes(V(3, 2, 0.25));
  moved->SetCenter(c);
  moved->SetRotation(r);
  for (const PointType & q : RandomPoints(P(-4, -3, -1), P(4, 3, 1), 0.0, 500, 61))
  {
    EXPECT_NEAR(moved->Evaluate(Transform(r, c, q)), local->Evaluate(q), 1e-9) << q;
  }
}

TEST(BoxImplicitSurface, NonPositiveHalfSizeThrows)
{
  auto box = itk::BoxImplicitSurface::New();
  ExpectThrowsMentioning([&] { box->SetHalfSizes(V(1, 1, 0)); }, "HalfSizes");
}
