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
#include "itkThreeLandmarkIncrementalTransformInitializer.h"
#include "itkAffineTransform.h"
#include "itkEuler3DTransform.h"
#include "itkImageRegionIteratorWithIndex.h"
#include "itkLandmarkBasedTransformInitializer.h"
#include "itkResampleImageFilter.h"
#include "itkSimilarity3DTransform.h"
#include "itkTranslationTransform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace
{
using Initializer = itk::ThreeLandmarkIncrementalTransformInitializer<>;
using Point = Initializer::LandmarkPointType;
using Landmarks = Initializer::LandmarkPointContainer;
using Vector = itk::Vector<double, 3>;
using Rigid = itk::VersorRigid3DTransform<double>;

Point
RandomPoint(std::mt19937_64 & random, double extent)
{
  std::uniform_real_distribution<double> u(-extent, extent);
  Point                                  p;
  for (unsigned int d = 0; d < 3; ++d)
  {
    p[d] = u(random);
  }
  return p;
}

/** Three landmarks that are far from degenerate: C at least 10 % of the extent off AB. */
Landmarks
RandomTriple(std::mt19937_64 & random)
{
  for (;;)
  {
    Landmarks    l{ RandomPoint(random, 100.0), RandomPoint(random, 100.0), RandomPoint(random, 100.0) };
    const Vector ab = l[1] - l[0];
    const Vector ac = l[2] - l[0];
    if (ab.GetNorm() > 20.0 && itk::CrossProduct(ab, ac).GetNorm() / ab.GetNorm() > 10.0)
    {
      return l;
    }
  }
}

Rigid::Pointer
RandomRigid(std::mt19937_64 & random)
{
  std::normal_distribution<double> n;
  Vector                           axis;
  for (unsigned int d = 0; d < 3; ++d)
  {
    axis[d] = n(random);
  }
  itk::Versor<double> versor;
  versor.Set(axis / axis.GetNorm(), std::uniform_real_distribution<double>(-itk::Math::pi, itk::Math::pi)(random));
  auto rigid = Rigid::New();
  rigid->SetCenter(RandomPoint(random, 50.0));
  rigid->SetRotation(versor);
  Rigid::OutputVectorType t;
  for (unsigned int d = 0; d < 3; ++d)
  {
    t[d] = 200.0 * (std::uniform_real_distribution<double>(-1, 1)(random));
  }
  rigid->SetTranslation(t);
  return rigid;
}

template <typename TTransform>
Landmarks
Map(const TTransform * transform, const Landmarks & in)
{
  Landmarks out;
  for (const auto & p : in)
  {
    out.push_back(transform->TransformPoint(p));
  }
  return out;
}

template <typename TTransform = Rigid>
typename TTransform::Pointer
Match(const Landmarks &                            fixed,
      const Landmarks &                            moving,
      itk::MeshExtractionEnums::LandmarkDistension distension = itk::MeshExtractionEnums::LandmarkDistension::None)
{
  auto initializer = itk::ThreeLandmarkIncrementalTransformInitializer<TTransform>::New();
  auto transform = TTransform::New();
  initializer->SetTransform(transform);
  initializer->SetFixedLandmarks(fixed);
  initializer->SetMovingLandmarks(moving);
  initializer->SetDistension(distension);
  initializer->InitializeTransform();
  return transform;
}

std::string
ErrorOf(const Landmarks & fixed, const Landmarks & moving)
{
  try
  {
    Match(fixed, moving);
  }
  catch (const itk::ExceptionObject & e)
  {
    return e.GetDescription();
  }
  return "no exception";
}

/** |T(p) - q| over a grid of points around the landmarks. */
template <typename TA, typename TB>
double
LargestDifference(const TA * a, const TB * b)
{
  double largest = 0.0;
  for (double x = -100; x <= 100; x += 50)
  {
    for (double y = -100; y <= 100; y += 50)
    {
      for (double z = -100; z <= 100; z += 50)
      {
        Point p;
        p[0] = x;
        p[1] = y;
        p[2] = z;
        largest = std::max(largest, a->TransformPoint(p).EuclideanDistanceTo(b->TransformPoint(p)));
      }
    }
  }
  return largest;
}
} // namespace

TEST(ThreeLandmarkIncrementalTransformInitializer, RecoversRandomRigidTransformsFromExactLandmarks)
{
  std::mt19937_64 random(1);
  for (int trial = 0; trial < 200; ++trial)
  {
    const auto      truth = RandomRigid(random);
    const Landmarks fixed = RandomTriple(random);
    const auto      found = Match(fixed, Map(truth.GetPointer(), fixed));
    EXPECT_LT(LargestDifference(found.GetPointer(), truth.GetPointer()), 1e-9) << "trial " << trial;
  }
}

TEST(ThreeLandmarkIncrementalTransformInitializer, InvariantsHoldForUnrelatedLandmarks)
{
  std::mt19937_64 random(2);
  for (int trial = 0; trial < 500; ++trial)
  {
    const Landmarks f = RandomTriple(random);
    const Landmarks m = RandomTriple(random);
    const auto      t = Match(f, m);
    // A on A.
    EXPECT_LT(t->TransformPoint(f[0]).EuclideanDistanceTo(m[0]), 1e-9);
    // B on the ray from A through B.
    const Vector axis = (m[1] - m[0]) / (m[1] - m[0]).GetNorm();
    const Vector b = t->TransformPoint(f[1]) - m[0];
    EXPECT_LT(itk::CrossProduct(b, axis).GetNorm(), 1e-9);
    EXPECT_GT(b * axis, 0.0);
    EXPECT_NEAR(b.GetNorm(), (f[1] - f[0]).GetNorm(), 1e-9); // rigid: |AB| kept
    // C in the half-plane of C.
    const Vector c = itk::MeshExtraction::detail::PerpendicularPart(t->TransformPoint(f[2]) - m[0], axis);
    const Vector target = itk::MeshExtraction::detail::PerpendicularPart(m[2] - m[0], axis);
    EXPECT_LT(itk::CrossProduct(c, target).GetNorm() / target.GetNorm(), 1e-9);
    EXPECT_GT(c * target, 0.0);
  }
}

TEST(ThreeLandmarkIncrementalTransformInitializer, TheThesisMoveOfMovingOntoFixedIsTheInverse)
{
  // The thesis: T'(p) = A_f + R2 R1 (p - A_m), R1 turning A_mB_m onto A_fB_f, R2 about
  // A_fB_f turning C. Built here by hand, with the module's rotation helpers.
  std::mt19937_64 random(3);
  for (int trial = 0; trial < 100; ++trial)
  {
    const Landmarks f = RandomTriple(random);
    const Landmarks m = RandomTriple(random);
    const Vector    uf = (f[1] - f[0]) / (f[1] - f[0]).GetNorm();
    const Vector    um = (m[1] - m[0]) / (m[1] - m[0]).GetNorm();
    const auto      R1 = itk::MeshExtraction::detail::ShortestArcRotation(um, uf);
    const Vector    v = itk::MeshExtraction::detail::PerpendicularPart(R1 * (m[2] - m[0]), uf);
    const Vector    w = itk::MeshExtraction::detail::PerpendicularPart(f[2] - f[0], uf);
    const auto R2 = itk::MeshExtraction::detail::AxisAngleRotation(uf, std::atan2(uf * itk::CrossProduct(v, w), v * w));
    auto       thesis = itk::AffineTransform<double, 3>::New();
    thesis->SetCenter(m[0]);
    thesis->SetMatrix(R2 * R1);
    thesis->SetTranslation(f[0] - m[0]);

    const auto ours = Match(f, m);
    auto       inverse = Rigid::New();
    ASSERT_TRUE(ours->GetInverse(inverse));
    EXPECT_LT(LargestDifference(inverse.GetPointer(), thesis.GetPointer()), 1e-9) << "trial " << trial;
  }
}

TEST(ThreeLandmarkIncrementalTransformInitializer, MapsAsLandmarkBasedTransformInitializerAndResampling)
{
  // ITK's convention: the transform maps fixed points to moving points. With exact
  // landmarks the least-squares fit of ITK's initializer is the same transform.
  std::mt19937_64 random(4);
  const auto      truth = RandomRigid(random);
  const Landmarks fixed = RandomTriple(random);
  const Landmarks moving = Map(truth.GetPointer(), fixed);
  const auto      ours = Match(fixed, moving);

  using Image = itk::Image<float, 3>;
  auto itkRigid = Rigid::New();
  auto leastSquares = itk::LandmarkBasedTransformInitializer<Rigid, Image, Image>::New();
  leastSquares->SetTransform(itkRigid);
  leastSquares->SetFixedLandmarks(fixed);
  leastSquares->SetMovingLandmarks(moving);
  leastSquares->InitializeTransform();
  EXPECT_LT(LargestDifference(ours.GetPointer(), itkRigid.GetPointer()), 1e-6);

  // Resampling the moving image through the transform onto the fixed grid puts a
  // bright spot made at T(p) in the moving image back at p.
  auto makeImage = [](const Point & origin) {
    auto            image = Image::New();
    Image::SizeType size;
    size.Fill(40);
    image->SetRegions(size);
    image->SetOrigin(origin);
    image->Allocate(true);
    return image;
  };
  Point spot = fixed[0];
  Point fixedOrigin = spot;
  for (unsigned int d = 0; d < 3; ++d)
  {
    fixedOrigin[d] -= 20.0;
  }
  const Point movingSpot = ours->TransformPoint(spot);
  Point       movingOrigin = movingSpot;
  for (unsigned int d = 0; d < 3; ++d)
  {
    movingOrigin[d] -= 20.0;
  }
  auto moving_image = makeImage(movingOrigin);
  for (itk::ImageRegionIteratorWithIndex<Image> it(moving_image, moving_image->GetBufferedRegion()); !it.IsAtEnd();
       ++it)
  {
    Point p;
    moving_image->TransformIndexToPhysicalPoint(it.GetIndex(), p);
    it.Set(static_cast<float>(std::exp(-p.SquaredEuclideanDistanceTo(movingSpot) / 18.0)));
  }
  auto fixed_image = makeImage(fixedOrigin);
  auto resample = itk::ResampleImageFilter<Image, Image>::New();
  resample->SetInput(moving_image);
  resample->SetTransform(ours);
  resample->UseReferenceImageOn();
  resample->SetReferenceImage(fixed_image);
  resample->Update();
  double                 sum = 0.0;
  itk::Vector<double, 3> weighted;
  weighted.Fill(0.0);
  for (itk::ImageRegionIteratorWithIndex<Image> it(resample->GetOutput(), resample->GetOutput()->GetBufferedRegion());
       !it.IsAtEnd();
       ++it)
  {
    Point p;
    fixed_image->TransformIndexToPhysicalPoint(it.GetIndex(), p);
    sum += it.Get();
    weighted += (p - spot) * static_cast<double>(it.Get());
  }
  ASSERT_GT(sum, 1.0);
  EXPECT_LT((weighted / sum).GetNorm(), 0.05); // the spot's centroid is back at p
}

TEST(ThreeLandmarkIncrementalTransformInitializer, DistensionRecoversKnownScalings)
{
  std::mt19937_64 random(5);
  for (int trial = 0; trial < 50; ++trial)
  {
    const Landmarks f = RandomTriple(random);
    const auto      rigid = RandomRigid(random);
    // Moving = A' + R S (p - A), S scaling by 1.3 along AB and 0.8 toward C.
    const Vector u = (f[1] - f[0]) / (f[1] - f[0]).GetNorm();
    Vector       e2 = itk::MeshExtraction::detail::PerpendicularPart(f[2] - f[0], u);
    e2 /= e2.GetNorm();
    const Vector              e3 = itk::CrossProduct(u, e2);
    itk::Matrix<double, 3, 3> S;
    S.Fill(0.0);
    const double scales[3] = { 1.3, 0.8, 1.0 };
    const Vector frame[3] = { u, e2, e3 };
    for (unsigned int k = 0; k < 3; ++k)
    {
      for (unsigned int r = 0; r < 3; ++r)
      {
        for (unsigned int c = 0; c < 3; ++c)
        {
          S[r][c] += scales[k] * frame[k][r] * frame[k][c];
        }
      }
    }
    auto truth = itk::AffineTransform<double, 3>::New();
    truth->SetCenter(f[0]);
    truth->SetMatrix(rigid->GetMatrix() * S);
    truth->SetTranslation(rigid->TransformPoint(f[0]) - f[0]);
    const Landmarks m = Map(truth.GetPointer(), f);

    auto initializer = itk::ThreeLandmarkIncrementalTransformInitializer<itk::AffineTransform<double, 3>>::New();
    auto found = itk::AffineTransform<double, 3>::New();
    initializer->SetTransform(found);
    initializer->SetFixedLandmarks(f);
    initializer->SetMovingLandmarks(m);
    initializer->SetDistension(itk::MeshExtractionEnums::LandmarkDistension::AlongAxes);
    initializer->InitializeTransform();
    EXPECT_NEAR(initializer->GetScales()[0], 1.3, 1e-9);
    EXPECT_NEAR(initializer->GetScales()[1], 0.8, 1e-9);
    EXPECT_NEAR(initializer->GetScales()[2], 1.0, 1e-12);
    EXPECT_LT(LargestDifference(found.GetPointer(), truth.GetPointer()), 1e-9);
    for (double residual : initializer->GetLandmarkResiduals())
    {
      EXPECT_LT(residual, 1e-9);
    }
  }
  // One isotropic factor: a similarity is recovered exactly.
  using Similarity = itk::Similarity3DTransform<double>;
  for (int trial = 0; trial < 50; ++trial)
  {
    const Landmarks f = RandomTriple(random);
    const auto      rigid = RandomRigid(random);
    auto            truth = Similarity::New();
    truth->SetCenter(rigid->GetCenter());
    truth->SetRotation(rigid->GetVersor());
    truth->SetTranslation(rigid->GetTranslation());
    truth->SetScale(0.7 + 0.1 * trial / 10.0);
    const auto found =
      Match<Similarity>(f, Map(truth.GetPointer(), f), itk::MeshExtractionEnums::LandmarkDistension::Isotropic);
    EXPECT_LT(LargestDifference(found.GetPointer(), truth.GetPointer()), 1e-9);
  }
}

TEST(ThreeLandmarkIncrementalTransformInitializer, KeepsTheCertainLandmarksWhereLeastSquaresSpreadsTheError)
{
  // Only C is uncertain: the incremental match keeps A exactly and B on its ray, while
  // the least-squares fit moves both.
  std::mt19937_64                  random(6);
  std::normal_distribution<double> noise(0.0, 5.0);
  for (int trial = 0; trial < 20; ++trial)
  {
    const auto      truth = RandomRigid(random);
    const Landmarks f = RandomTriple(random);
    Landmarks       m = Map(truth.GetPointer(), f);
    for (unsigned int d = 0; d < 3; ++d)
    {
      m[2][d] += noise(random);
    }
    const auto ours = Match(f, m);
    using Image = itk::Image<float, 3>;
    auto lsq = Rigid::New();
    auto leastSquares = itk::LandmarkBasedTransformInitializer<Rigid, Image, Image>::New();
    leastSquares->SetTransform(lsq);
    leastSquares->SetFixedLandmarks(f);
    leastSquares->SetMovingLandmarks(m);
    leastSquares->InitializeTransform();
    EXPECT_LT(ours->TransformPoint(f[0]).EuclideanDistanceTo(m[0]), 1e-9);
    EXPECT_LT(ours->TransformPoint(f[1]).EuclideanDistanceTo(m[1]), 1e-9);
    EXPECT_GT(lsq->TransformPoint(f[0]).EuclideanDistanceTo(m[0]), 1e-3);
  }
}

TEST(ThreeLandmarkIncrementalTransformInitializer, RefusesDegenerateInputWithAMessage)
{
  Point a, b, c, n;
  a.Fill(0.0);
  b.Fill(0.0);
  b[0] = 10.0;
  c.Fill(0.0);
  c[1] = 5.0;
  n.Fill(0.0);
  n[2] = std::nan("");
  const Landmarks good{ a, b, c };
  EXPECT_NE(ErrorOf({ a, b }, good).find("Three fixed landmarks (A, B, C) are needed, got 2"), std::string::npos);
  EXPECT_NE(ErrorOf(good, { a, b, c, c }).find("Three moving landmarks (A, B, C) are needed, got 4"),
            std::string::npos);
  EXPECT_NE(ErrorOf({ a, a, c }, good).find("are at the same place: they define no axis"), std::string::npos);
  Point onAxis = b;
  onAxis[0] = 25.0;
  EXPECT_NE(ErrorOf(good, { a, b, onAxis }).find("lies on the line through A"), std::string::npos);
  EXPECT_NE(ErrorOf({ a, b, n }, good).find("landmark C has a coordinate that is not finite"), std::string::npos);

  auto initializer = Initializer::New();
  initializer->SetFixedLandmarks(good);
  initializer->SetMovingLandmarks(good);
  EXPECT_THROW(initializer->InitializeTransform(), itk::ExceptionObject); // no transform
  initializer->SetTransform(Rigid::New());
  initializer->SetDistension(itk::MeshExtractionEnums::LandmarkDistension::Isotropic);
  try
  {
    initializer->InitializeTransform();
    ADD_FAILURE() << "a rigid transform cannot scale";
  }
  catch (const itk::ExceptionObject & e)
  {
    EXPECT_NE(std::string(e.GetDescription()).find("needs a Similarity3DTransform or an AffineTransform"),
              std::string::npos);
  }
  // Euler3DTransform works through its matrix.
  std::mt19937_64 random(7);
  const auto      truth = RandomRigid(random);
  const Landmarks f = RandomTriple(random);
  const auto      euler = Match<itk::Euler3DTransform<double>>(f, Map(truth.GetPointer(), f));
  EXPECT_LT(LargestDifference(euler.GetPointer(), truth.GetPointer()), 1e-9);
}

TEST(ThreeLandmarkIncrementalTransformInitializer, TakesAnyTransformThroughTheBaseClass)
{
  // As the Python wrapping has it: the initializer of itk::Transform<double, 3, 3>,
  // given a concrete transform at run time.
  using Base = itk::Transform<double, 3, 3>;
  using BaseInitializer = itk::ThreeLandmarkIncrementalTransformInitializer<Base>;
  std::mt19937_64 random(8);
  const auto      truth = RandomRigid(random);
  const Landmarks f = RandomTriple(random);
  const Landmarks m = Map(truth.GetPointer(), f);
  auto            initializer = BaseInitializer::New();
  auto            rigid = Rigid::New();
  initializer->SetTransform(rigid);
  initializer->SetFixedLandmarks(f);
  initializer->SetMovingLandmarks(m);
  initializer->InitializeTransform();
  EXPECT_LT(LargestDifference(rigid.GetPointer(), truth.GetPointer()), 1e-9);

  auto affine = itk::AffineTransform<double, 3>::New();
  initializer->SetTransform(affine);
  initializer->SetDistension(itk::MeshExtractionEnums::LandmarkDistension::AlongAxes);
  initializer->InitializeTransform();
  EXPECT_LT(LargestDifference(affine.GetPointer(), truth.GetPointer()), 1e-9);

  // A transform without a matrix cannot hold the match.
  initializer->SetTransform(itk::TranslationTransform<double, 3>::New());
  initializer->SetDistension(itk::MeshExtractionEnums::LandmarkDistension::None);
  try
  {
    initializer->InitializeTransform();
    ADD_FAILURE() << "a translation cannot rotate";
  }
  catch (const itk::ExceptionObject & e)
  {
    EXPECT_NE(std::string(e.GetDescription()).find("TranslationTransform cannot hold the match"), std::string::npos);
  }
}
