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
// The block-allocated mesh cells of itkMeshExtractionCellBlock.h (internal), in the
// SurfaceNets filter's output and on their own.

#include "itkMeshExtractionCellBlock.h"
#include "itkQuadrilateralCell.h"
#include "itkSurfaceNetsImageToMeshFilter.h"
#include "itkTriangleCell.h"
#include "itkMeshExtractionTestHelpers.h"

#include "gtest/gtest.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

using namespace MeshExtractionTest;
namespace ME = itk::MeshExtraction;

namespace
{
using FloatImage = itk::Image<float, 3>;
} // namespace

TEST(SurfaceNetsImageToMeshFilter, MeshCellsShareOneBlockThatGoesWithTheLastCell)
{
  using CellType = MeshType::CellType;
  using Triangle = ME::detail::BlockAllocatedCell<itk::TriangleCell<CellType>>;
  using Quad = ME::detail::BlockAllocatedCell<itk::QuadrilateralCell<CellType>>;
  const std::size_t trianglesBefore = Triangle::GetNumberOfBlocks();
  const std::size_t quadsBefore = Quad::GetNumberOfBlocks();
  const Phantom     p = MakePhantom(ME::PhantomShape::Ellipsoid);
  auto              filter = itk::SurfaceNetsImageToMeshFilter<FloatImage, MeshType>::New();
  filter->SetInput(p.image);
  filter->SetInsideIsAboveIsoValue(false);
  filter->Update();
  MeshType::Pointer mesh = filter->GetOutput();
  mesh->DisconnectPipeline();
  filter = nullptr;
  ASSERT_GT(mesh->GetNumberOfCells(), 1000u);
  EXPECT_EQ(Triangle::GetNumberOfBlocks(), trianglesBefore + 1);
  // Ordinary triangle cells to the mesh and its users, and independent copies.
  const CellType * first = mesh->GetCells()->ElementAt(0);
  EXPECT_EQ(first->GetType(), itk::CellGeometryEnum::TRIANGLE_CELL);
  EXPECT_NE(dynamic_cast<const itk::TriangleCell<CellType> *>(first), nullptr);
  CellType::CellAutoPointer copy;
  first->MakeCopy(copy);
  const std::vector<MeshType::PointIdentifier> firstIds(first->PointIdsBegin(), first->PointIdsEnd());
  // A cell replaced by the user is deleted by the mesh as any other; the block stays
  // while any of its cells does.
  CellType::CellAutoPointer replacement;
  replacement.TakeOwnership(new itk::TriangleCell<CellType>);
  replacement->SetPointIds(first->PointIdsBegin());
  CellType * replaced = mesh->GetCells()->ElementAt(1);
  mesh->GetCells()->InsertElement(1, replacement.ReleaseOwnership());
  delete replaced;
  EXPECT_EQ(Triangle::GetNumberOfBlocks(), trianglesBefore + 1);
  mesh = nullptr; // deletes every cell: the block goes with the last
  EXPECT_EQ(Triangle::GetNumberOfBlocks(), trianglesBefore);
  EXPECT_TRUE(std::equal(firstIds.begin(), firstIds.end(), copy->PointIdsBegin()));

  // Made in a block of many or alone, deleted in any order.
  std::vector<CellType *> cells(1000);
  Quad::MakeCells(cells.size(), cells.begin());
  EXPECT_EQ(Quad::GetNumberOfBlocks(), quadsBefore + 1);
  CellType * alone = new Quad;
  EXPECT_EQ(Quad::GetNumberOfBlocks(), quadsBefore + 2);
  std::mt19937 random(7);
  std::shuffle(cells.begin(), cells.end(), random);
  for (std::size_t i = 0; i + 1 < cells.size(); ++i)
  {
    cells[i]->SetPointId(3, i);
    EXPECT_EQ(cells[i]->GetNumberOfPoints(), 4u);
    delete cells[i];
  }
  EXPECT_EQ(Quad::GetNumberOfBlocks(), quadsBefore + 2);
  delete alone;
  EXPECT_EQ(Quad::GetNumberOfBlocks(), quadsBefore + 1);
  delete cells.back();
  EXPECT_EQ(Quad::GetNumberOfBlocks(), quadsBefore);
}

namespace
{
/** A triangle cell whose constructor throws on its `throwAt`-th call, as an
 * allocating constructor (ITK 5.2's) may. */
class ThrowingTriangle : public itk::TriangleCell<MeshType::CellType>
{
public:
  ThrowingTriangle()
  {
    if (++constructed == throwAt)
    {
      throw std::runtime_error("cell constructor failed");
    }
    ++alive;
  }
  ~ThrowingTriangle() override
  {
    --alive;
  }
  static std::atomic<std::size_t> constructed;
  static std::atomic<std::size_t> alive;
  static std::size_t              throwAt;
};
std::atomic<std::size_t> ThrowingTriangle::constructed{ 0 };
std::atomic<std::size_t> ThrowingTriangle::alive{ 0 };
std::size_t              ThrowingTriangle::throwAt = 0;
} // namespace

TEST(SurfaceNetsImageToMeshFilter, CellBlockLeavesNothingWhenAConstructorThrows)
{
  using Cell = ME::detail::BlockAllocatedCell<ThrowingTriangle>;
  const std::size_t                 blocksBefore = Cell::GetNumberOfBlocks();
  std::vector<MeshType::CellType *> cells(50000, nullptr);

  // Each cell in its slot: the addresses rise by one slot a cell.
  ThrowingTriangle::throwAt = 0;
  Cell::MakeCells(cells.size(), cells.begin());
  EXPECT_EQ(ThrowingTriangle::alive.load(), cells.size());
  EXPECT_EQ(Cell::GetNumberOfBlocks(), blocksBefore + 1);
  const auto slot = reinterpret_cast<std::uintptr_t>(cells[1]) - reinterpret_cast<std::uintptr_t>(cells[0]);
  for (std::size_t i = 1; i < cells.size(); ++i)
  {
    ASSERT_EQ(reinterpret_cast<std::uintptr_t>(cells[i]) - reinterpret_cast<std::uintptr_t>(cells[i - 1]), slot);
  }
  for (auto *& cell : cells)
  {
    delete cell;
    cell = nullptr;
  }
  EXPECT_EQ(ThrowingTriangle::alive.load(), 0u);
  EXPECT_EQ(Cell::GetNumberOfBlocks(), blocksBefore);

  // A constructor that throws part-way (the 20,000th of 50,000): the exception reaches
  // the caller, and no cell, block or address is left.
  ThrowingTriangle::constructed = 0;
  ThrowingTriangle::throwAt = 20000;
  EXPECT_THROW(Cell::MakeCells(cells.size(), cells.begin()), std::runtime_error);
  EXPECT_EQ(ThrowingTriangle::constructed.load(), ThrowingTriangle::throwAt);
  EXPECT_EQ(ThrowingTriangle::alive.load(), 0u);
  EXPECT_EQ(Cell::GetNumberOfBlocks(), blocksBefore);
  EXPECT_TRUE(std::all_of(cells.begin(), cells.end(), [](const MeshType::CellType * c) { return c == nullptr; }));
  ThrowingTriangle::throwAt = 0;
}
