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
#ifndef MeshExtractionShapeModelCLI_h
#define MeshExtractionShapeModelCLI_h

// What the two files of `meshextraction shape-model` share: MeshExtractionShapeModelCommand.cxx
// (build, the steps, sample, project) and MeshExtractionShapeModelEvaluation.cxx (evaluate).

#include "MeshExtractionCLI.h"

#include "itkLandmarkFreeShapeModelEstimator.h"
#include "itkMeshExtractionShapeModelBuilder.h"

#include <string>
#include <vector>

namespace MeshExtractionCLI
{
using ShapeModelEstimator = itk::LandmarkFreeShapeModelEstimator<IOMeshType>;

/** The builder's settings of the shape-model options: --correspondence, --thesis,
 * --variance-fraction, --passes. */
ME::detail::ShapeModelSettings
ShapeModelSettingsOf(const Arguments & args);

/** The estimator set as ShapeModelSettingsOf(args) says. */
void
ConfigureShapeModelEstimator(ShapeModelEstimator & estimator, const Arguments & args);

/** meshextraction shape-model evaluate (MeshExtractionShapeModelEvaluation.cxx): the
 * model of `inputs` (mesh files, or one folder: its *.ply but ref_*) and its figures
 * (compactness, eigenvector stability, leave-one-out generalisation, specificity, fit,
 * landmark transfer where every mesh has a landmark file of its name). Options as
 * shape-model build's, and --modes (default 3) for the figures. */
int
EvaluateShapeModel(const Arguments & args, const std::vector<std::string> & inputs);
} // namespace MeshExtractionCLI

#endif
