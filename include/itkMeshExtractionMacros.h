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
#ifndef itkMeshExtractionMacros_h
#define itkMeshExtractionMacros_h

#include "itkMacro.h"
#include "itkConfigure.h"

/** \file
 * Source compatibility between ITK 5.2 (Debian bookworm), 5.3, 5.4 and 6.
 *
 * - itkOverrideGetNameOfClassMacro appeared in ITK 5.4; itkTypeMacro is its
 *   deprecated predecessor (a static_assert under ITK_FUTURE_LEGACY_REMOVE on 6).
 * - Mesh traits renamed CoordRepType to CoordinateType in ITK 6; code here uses
 *   `typename TMesh::PointType::ValueType` instead of either name.
 *
 * \ingroup MeshExtraction
 */
#ifndef itkOverrideGetNameOfClassMacro
#  define itkOverrideGetNameOfClassMacro(thisClass) itkTypeMacro(thisClass, Unused)
#endif

#ifndef itkVirtualGetNameOfClassMacro
#  define itkVirtualGetNameOfClassMacro(thisClass) itkTypeMacroNoParent(thisClass)
#endif

/** Put after a lambda's parameter list: inline the lambda into its callers even
 * where the compiler's size limits would not (for the per-node steps of hot loops). */
#if defined(__GNUC__) || defined(__clang__)
#  define MESHEXTRACTION_ALWAYS_INLINE __attribute__((always_inline))
#else
#  define MESHEXTRACTION_ALWAYS_INLINE
#endif

#define MESHEXTRACTION_ITK_VERSION_AT_LEAST(major, minor)                                                              \
  ((ITK_VERSION_MAJOR > (major)) || (ITK_VERSION_MAJOR == (major) && ITK_VERSION_MINOR >= (minor)))

#endif
