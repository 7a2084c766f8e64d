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
// Internal to MeshExtraction (namespace detail): not part of the public API.
#ifndef itkMeshExtractionCellBlock_h
#define itkMeshExtractionCellBlock_h

#include "itkMeshExtractionBuffer.h"

#include <atomic>
#include <cstddef>
#include <new>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \brief An itk::Mesh cell (TCell: TriangleCell or QuadrilateralCell of the mesh's
 * CellType) that lives in one block of memory with the other cells made with it,
 * instead of one heap object per cell.
 *
 * The mesh keeps its default ownership (CellsAllocatedDynamicallyCellByCell): it
 * deletes every cell with `delete`, and this class's operator delete counts the
 * cells of the block down and releases the block with its last cell. So the mesh,
 * its copies and its users treat these cells as any other (a cell may be replaced,
 * deleted or kept alone); only the memory comes from one block, allocated with huge
 * pages where it is large (AllocateLargeBlock), which makes a 222,000-cell output
 * one allocation instead of 222,000. \ingroup MeshExtraction */
template <typename TCell>
class BlockAllocatedCell : public TCell
{
public:
  BlockAllocatedCell() = default;

  /** Makes `count` default-constructed cells in one block and writes their
   * addresses to `cells[0 .. count)`; the block is released with its last cell.
   * If the block cannot be allocated (std::bad_alloc) or a cell constructor throws,
   * the exception is rethrown and none is made (the addresses it wrote are set to null). */
  template <typename TOutputIterator>
  static void
  MakeCells(std::size_t count, TOutputIterator cells)
  {
    if (count == 0)
    {
      return;
    }
    Block *     block = NewBlock(count);
    std::size_t made = 0;
    try
    {
      for (; made < count; ++made)
      {
        cells[made] = ::new (CellStorage(block, made)) BlockAllocatedCell; // may throw (ITK 5.2's cells allocate)
      }
    }
    catch (...)
    {
      // None made after all: the cells made so far go with the block.
      for (std::size_t i = 0; i < made; ++i)
      {
        std::launder(reinterpret_cast<BlockAllocatedCell *>(SlotOf(block, i) + Prefix))->~BlockAllocatedCell();
        cells[i] = nullptr;
      }
      ReleaseBlock(block);
      throw;
    }
  }

  /** A cell made on its own (as `new` would): a block of one. */
  static void *
  operator new(std::size_t size)
  {
    if (size != sizeof(BlockAllocatedCell))
    {
      throw std::bad_alloc();
    }
    return CellStorage(NewBlock(1), 0);
  }

  static void
  operator delete(void * cell) noexcept
  {
    if (cell == nullptr)
    {
      return;
    }
    // The block's address is stored just before the cell, outside its storage.
    Block * block = *reinterpret_cast<Block **>(static_cast<char *>(cell) - Prefix);
    if (block->live.fetch_sub(1, std::memory_order_acq_rel) == 1)
    {
      ReleaseBlock(block);
    }
  }

  /** The blocks of this cell type alive now (each made by MakeCells or `new`,
   * gone with its last cell): for tests and diagnostics. */
  static std::size_t
  GetNumberOfBlocks()
  {
    return LiveBlocks().load();
  }

private:
  static std::atomic<std::size_t> &
  LiveBlocks()
  {
    static std::atomic<std::size_t> live{ 0 };
    return live;
  }

  struct Block
  {
    std::atomic<std::size_t> live;
    std::size_t              bytes;
  };
  static constexpr std::size_t
  Align(std::size_t n, std::size_t a)
  {
    return (n + a - 1) / a * a;
  }
  static constexpr std::size_t CellAlignment = alignof(TCell) > alignof(Block *) ? alignof(TCell) : alignof(Block *);
  static constexpr std::size_t Prefix = Align(sizeof(Block *), CellAlignment);
  static constexpr std::size_t Slot = Align(Prefix + sizeof(TCell), CellAlignment);
  static constexpr std::size_t Header = Align(sizeof(Block), 64);

  static Block *
  NewBlock(std::size_t count)
  {
    static_assert(sizeof(BlockAllocatedCell) == sizeof(TCell), "BlockAllocatedCell adds no data to the cell");
    const std::size_t bytes = Header + count * Slot;
    void *            memory = AllocateLargeBlock(bytes);
    Block *           block = ::new (memory) Block;
    block->live.store(count, std::memory_order_relaxed);
    block->bytes = bytes;
    ++LiveBlocks();
    return block;
  }

  static void
  ReleaseBlock(Block * block) noexcept
  {
    const std::size_t bytes = block->bytes;
    block->~Block();
    ReleaseLargeBlock(block, bytes);
    --LiveBlocks();
  }

  static char *
  SlotOf(Block * block, std::size_t i)
  {
    return reinterpret_cast<char *>(block) + Header + i * Slot;
  }

  /** Slot i's storage for a cell, after writing the block's address just before it
   * (where operator delete finds it). */
  static void *
  CellStorage(Block * block, std::size_t i)
  {
    char * slot = SlotOf(block, i);
    *reinterpret_cast<Block **>(slot) = block;
    return slot + Prefix;
  }
};

} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
