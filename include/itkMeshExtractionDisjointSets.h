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
#ifndef itkMeshExtractionDisjointSets_h
#define itkMeshExtractionDisjointSets_h

#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
/** \brief Disjoint sets of 0 .. n-1 (union-find with path compression). The smaller
 * index of two joined sets becomes the root, so the roots depend on the input only,
 * never on the order of the finds.
 * \ingroup MeshExtraction */
class DisjointSets
{
public:
  explicit DisjointSets(std::size_t n)
      : m_Parent(n)
  {
    std::iota(m_Parent.begin(), m_Parent.end(), 0u);
  }
  std::uint32_t
  Find(std::uint32_t x)
  {
    std::uint32_t root = x;
    while (m_Parent[root] != root)
    {
      root = m_Parent[root];
    }
    while (m_Parent[x] != root)
    {
      const std::uint32_t next = m_Parent[x];
      m_Parent[x] = root;
      x = next;
    }
    return root;
  }
  void
  Join(std::uint32_t a, std::uint32_t b)
  {
    a = this->Find(a);
    b = this->Find(b);
    if (a != b)
    {
      m_Parent[a < b ? b : a] = a < b ? a : b;
    }
  }

private:
  std::vector<std::uint32_t> m_Parent;
};
} // namespace detail
} // namespace MeshExtraction
} // namespace itk

#endif
