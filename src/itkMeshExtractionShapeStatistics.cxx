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
#include "itkMeshExtractionShapeStatistics.h"
#include "itkMacro.h"
#include "itkMeshExtractionWholeFile.h"
#include "itk_H5Cpp.h"
#include "itk_eigen.h"
#include ITK_EIGEN(Dense)
#include ITK_EIGEN(SVD)

#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <new>

namespace itk
{
namespace MeshExtraction
{
namespace detail
{
Vec3
SimilarityParameters::Apply(const Vec3 & p) const
{
  Vec3 out;
  for (unsigned int r = 0; r < 3; ++r)
  {
    out[r] = scale * (rotation[r][0] * p[0] + rotation[r][1] * p[1] + rotation[r][2] * p[2]) + translation[r];
  }
  return out;
}

SimilarityParameters
SimilarityParameters::Inverse() const
{
  SimilarityParameters inverse;
  inverse.scale = 1.0 / scale;
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      inverse.rotation[r][c] = rotation[c][r];
    }
  }
  // p = s R q + t  =>  q = (1/s) R^T (p - t)
  Vec3 back = MakeVec3(0, 0, 0);
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      back[r] -= inverse.rotation[r][c] * translation[c];
    }
  }
  inverse.translation = back * inverse.scale;
  return inverse;
}

SimilarityParameters
Compose(const SimilarityParameters & outer, const SimilarityParameters & inner)
{
  // s_o R_o (s_i R_i p + t_i) + t_o
  SimilarityParameters out;
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      out.rotation[r][c] = 0.0;
      for (unsigned int k = 0; k < 3; ++k)
      {
        out.rotation[r][c] += outer.rotation[r][k] * inner.rotation[k][c];
      }
    }
  }
  out.scale = outer.scale * inner.scale;
  out.translation = outer.Apply(inner.translation);
  return out;
}

namespace
{
Vec3
Mean(const Shape & shape)
{
  Vec3 sum = MakeVec3(0, 0, 0);
  for (const Vec3 & p : shape)
  {
    sum += p;
  }
  return sum * (1.0 / static_cast<double>(shape.size()));
}

double
CentroidSize(const Shape & shape)
{
  const Vec3 c = Mean(shape);
  double     sum = 0.0;
  for (const Vec3 & p : shape)
  {
    sum += SquaredNorm(p - c);
  }
  return std::sqrt(sum);
}

double
RMSDistance(const Shape & a, const Shape & b)
{
  double sum = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    sum += SquaredNorm(a[k] - b[k]);
  }
  return std::sqrt(sum / static_cast<double>(a.size()));
}
} // namespace

SimilarityParameters
AlignShape(const Shape & from, const Shape & to, bool withScale)
{
  const Vec3      mf = Mean(from);
  const Vec3      mt = Mean(to);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double          variance = 0.0;
  for (std::size_t k = 0; k < from.size(); ++k)
  {
    const Vec3 f = from[k] - mf;
    const Vec3 t = to[k] - mt;
    variance += SquaredNorm(f);
    for (unsigned int r = 0; r < 3; ++r)
    {
      for (unsigned int c = 0; c < 3; ++c)
      {
        covariance(r, c) += t[r] * f[c];
      }
    }
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(covariance, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d       d(1.0, 1.0, (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0);
  const Eigen::Matrix3d R = svd.matrixU() * d.asDiagonal() * svd.matrixV().transpose();
  SimilarityParameters  result;
  for (unsigned int r = 0; r < 3; ++r)
  {
    for (unsigned int c = 0; c < 3; ++c)
    {
      result.rotation[r][c] = R(r, c);
    }
  }
  result.scale = withScale && variance > 0.0 ? svd.singularValues().dot(d) / variance : 1.0;
  result.translation = MakeVec3(0, 0, 0);
  result.translation = mt - result.Apply(mf);
  return result;
}

Shape
ApplySimilarity(const SimilarityParameters & t, const Shape & shape)
{
  Shape out(shape.size());
  for (std::size_t k = 0; k < shape.size(); ++k)
  {
    out[k] = t.Apply(shape[k]);
  }
  return out;
}

std::vector<Shape>
GeneralizedProcrustes(const std::vector<Shape> &          shapes,
                      bool                                withScale,
                      std::vector<SimilarityParameters> * transforms,
                      double                              tolerance,
                      unsigned int                        maximumIterations)
{
  if (shapes.empty())
  {
    return {};
  }
  double size = 0.0;
  for (const Shape & s : shapes)
  {
    size += CentroidSize(s);
  }
  size /= static_cast<double>(shapes.size());
  // The first shape, centred (and scaled to the average size), starts the mean.
  auto normalise = [withScale, size](const Shape & s) {
    SimilarityParameters t;
    t.scale = withScale ? size / CentroidSize(s) : 1.0;
    t.translation = MakeVec3(0, 0, 0);
    t.translation = t.Apply(Mean(s)) * -1.0;
    return ApplySimilarity(t, s);
  };
  Shape                             mean = normalise(shapes.front());
  std::vector<SimilarityParameters> toMean(shapes.size());
  std::vector<Shape>                aligned(shapes.size());
  for (unsigned int iteration = 0; iteration < maximumIterations; ++iteration)
  {
    Shape sum(mean.size(), MakeVec3(0, 0, 0));
    for (std::size_t i = 0; i < shapes.size(); ++i)
    {
      toMean[i] = AlignShape(shapes[i], mean, withScale);
      aligned[i] = ApplySimilarity(toMean[i], shapes[i]);
      for (std::size_t k = 0; k < sum.size(); ++k)
      {
        sum[k] += aligned[i][k];
      }
    }
    for (Vec3 & p : sum)
    {
      p *= 1.0 / static_cast<double>(shapes.size());
    }
    // The new mean in the old one's frame (rigidly), centred, at the average size.
    Shape        next = normalise(ApplySimilarity(AlignShape(sum, mean, false), sum));
    const double change = RMSDistance(next, mean);
    mean = next;
    if (change < tolerance)
    {
      break;
    }
  }
  for (std::size_t i = 0; i < shapes.size(); ++i)
  {
    toMean[i] = AlignShape(shapes[i], mean, withScale);
    aligned[i] = ApplySimilarity(toMean[i], shapes[i]);
  }
  if (transforms != nullptr)
  {
    *transforms = toMean;
  }
  return aligned;
}

Shape
PrincipalComponentModel::Synthesize(const std::vector<double> & b) const
{
  if (b.size() > basis.size())
  {
    itkGenericExceptionMacro(<< "The model has " << basis.size() << " modes; " << b.size() << " coefficients given.");
  }
  std::vector<double> x = mean;
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    for (std::size_t k = 0; k < x.size(); ++k)
    {
      x[k] += b[i] * basis[i][k];
    }
  }
  Shape shape(x.size() / 3);
  for (std::size_t k = 0; k < shape.size(); ++k)
  {
    shape[k] = MakeVec3(x[3 * k], x[3 * k + 1], x[3 * k + 2]);
  }
  return shape;
}

std::vector<double>
PrincipalComponentModel::Project(const Shape & shape) const
{
  if (3 * shape.size() != mean.size())
  {
    itkGenericExceptionMacro(<< "The shape has " << shape.size() << " points; the model has " << mean.size() / 3
                             << ": only a shape on the model's topology can be projected.");
  }
  std::vector<double> b(basis.size(), 0.0);
  for (std::size_t i = 0; i < basis.size(); ++i)
  {
    for (std::size_t k = 0; k < shape.size(); ++k)
    {
      for (unsigned int d = 0; d < 3; ++d)
      {
        b[i] += basis[i][3 * k + d] * (shape[k][d] - mean[3 * k + d]);
      }
    }
  }
  return b;
}

PrincipalComponentModel
BuildPrincipalComponents(const std::vector<Shape> & shapes, double varianceFraction)
{
  const std::size_t m = shapes.size();
  if (m < 2)
  {
    itkGenericExceptionMacro(<< "A shape model needs at least two shapes, got " << m << '.');
  }
  const std::size_t n = shapes.front().size();
  for (const Shape & s : shapes)
  {
    if (s.size() != n)
    {
      itkGenericExceptionMacro(<< "The shapes are not in correspondence: " << n << " and " << s.size() << " points.");
    }
  }
  if (!(varianceFraction > 0.0 && varianceFraction <= 1.0))
  {
    itkGenericExceptionMacro(<< "The variance fraction must be in (0, 1], got " << varianceFraction << '.');
  }
  PrincipalComponentModel model;
  model.mean.assign(3 * n, 0.0);
  Eigen::MatrixXd data(3 * n, m); // one centred shape per column
  for (std::size_t i = 0; i < m; ++i)
  {
    for (std::size_t k = 0; k < n; ++k)
    {
      for (unsigned int d = 0; d < 3; ++d)
      {
        data(3 * k + d, i) = shapes[i][k][d];
        model.mean[3 * k + d] += shapes[i][k][d] / static_cast<double>(m);
      }
    }
  }
  for (std::size_t i = 0; i < m; ++i)
  {
    for (std::size_t r = 0; r < 3 * n; ++r)
    {
      data(r, i) -= model.mean[r];
    }
  }
#if EIGEN_VERSION_AT_LEAST(3, 4, 90)
  // ITK 6's Eigen takes the computation options as a template argument.
  Eigen::BDCSVD<Eigen::MatrixXd, Eigen::ComputeThinU> svd(data);
#else
  Eigen::BDCSVD<Eigen::MatrixXd> svd(data, Eigen::ComputeThinU);
#endif
  const std::size_t              modes = m - 1; // centring leaves m - 1 directions
  std::vector<double>            variances;
  for (std::size_t k = 0; k < modes; ++k)
  {
    const double s = svd.singularValues()(static_cast<Eigen::Index>(k));
    variances.push_back(s * s / static_cast<double>(m - 1));
    model.totalVariance += variances.back();
  }
  double cumulative = 0.0;
  for (std::size_t k = 0; k < modes; ++k)
  {
    if (model.totalVariance > 0.0 && cumulative >= varianceFraction * model.totalVariance * (1.0 - 1e-12))
    {
      break;
    }
    cumulative += variances[k];
    model.variances.push_back(variances[k]);
    std::vector<double> mode(3 * n);
    for (std::size_t r = 0; r < 3 * n; ++r)
    {
      mode[r] = svd.matrixU()(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k));
    }
    model.basis.push_back(std::move(mode));
  }
  return model;
}

// ---- statismo's HDF5 layout -----------------------------------------------------------

namespace
{
void
WriteFloats(H5::Group &                group,
            const std::string &        name,
            const std::vector<float> & values,
            hsize_t                    rows,
            hsize_t                    columns)
{
  const hsize_t dimensions[2] = { rows, columns };
  H5::DataSpace space(columns == 0 ? 1 : 2, dimensions);
  H5::DataSet   dataset = group.createDataSet(name, H5::PredType::NATIVE_FLOAT, space);
  dataset.write(values.data(), H5::PredType::NATIVE_FLOAT);
}

void
WriteInteger(H5::Group & group, const std::string & name, int value)
{
  H5::DataSet dataset = group.createDataSet(name, H5::PredType::NATIVE_INT, H5::DataSpace(H5S_SCALAR));
  dataset.write(&value, H5::PredType::NATIVE_INT);
}

void
WriteString(H5::Group & group, const std::string & name, const std::string & value)
{
  H5::StrType type(H5::PredType::C_S1, value.size() + 1);
  H5::DataSet dataset = group.createDataSet(name, type, H5::DataSpace(H5S_SCALAR));
  dataset.write(value.c_str(), type);
}

void
WriteStringAttribute(H5::Group & group, const std::string & name, const std::string & value)
{
  H5::StrType   type(H5::PredType::C_S1, value.size() + 1);
  H5::Attribute attribute = group.createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
  attribute.write(type, value.c_str());
}

std::string
Now()
{
  const std::time_t now = std::time(nullptr);
  char              text[64];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

void
WriteModelGroup(H5::H5File & file, const PrincipalComponentModel & model)
{
  H5::Group          group = file.createGroup("/model");
  const std::size_t  rows = model.mean.size();
  const std::size_t  k = model.basis.size();
  std::vector<float> mean(model.mean.begin(), model.mean.end());
  WriteFloats(group, "mean", mean, rows, 0);
  std::vector<float> basis(rows * k); // row-major rows x k
  for (std::size_t r = 0; r < rows; ++r)
  {
    for (std::size_t c = 0; c < k; ++c)
    {
      basis[r * k + c] = static_cast<float>(model.basis[c][r]);
    }
  }
  WriteFloats(group, "pcaBasis", basis, rows, k);
  WriteFloats(group, "pcaVariance", std::vector<float>(model.variances.begin(), model.variances.end()), k, 0);
  WriteFloats(group, "noiseVariance", { static_cast<float>(model.noiseVariance) }, 1, 0);
}

void
WriteRepresenter(H5::H5File &                         file,
                 const PrincipalComponentModel &      model,
                 const std::vector<TriangleIndices> & triangles)
{
  H5::Group group = file.createGroup("/representer");
  WriteStringAttribute(group, "name", "itkStandardMeshRepresenter");
  WriteStringAttribute(group, "version", "0.1");
  WriteStringAttribute(group, "datasetType", "POLYGON_MESH");
  const std::size_t  n = model.mean.size() / 3;
  std::vector<float> points(3 * n);
  for (std::size_t k = 0; k < n; ++k)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      points[d * n + k] = static_cast<float>(model.mean[3 * k + d]);
    }
  }
  WriteFloats(group, "points", points, 3, n);
  std::vector<std::uint32_t> cells(3 * triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f)
  {
    for (unsigned int d = 0; d < 3; ++d)
    {
      cells[d * triangles.size() + f] = triangles[f][d];
    }
  }
  const hsize_t dimensions[2] = { 3, triangles.size() };
  H5::DataSet   dataset = group.createDataSet("cells", H5::PredType::NATIVE_UINT32, H5::DataSpace(2, dimensions));
  dataset.write(cells.data(), H5::PredType::NATIVE_UINT32);
}
} // namespace

namespace
{
/** The model's HDF5 file, made in memory (HDF5's core driver without a backing store):
 * HDF5 then never writes to the disk itself, where a failing write (a full disk, a size
 * limit) left a truncated file and a library that crashed at exit. */
std::vector<char>
MakeStatismoFileImage(const PrincipalComponentModel &      model,
                      const std::vector<TriangleIndices> & triangles,
                      const std::string &                  builderInfo)
{
  H5::FileAccPropList access;
  if (H5Pset_fapl_core(access.getId(), 1 << 20, false) < 0)
  {
    throw H5::FileIException("H5Pset_fapl_core", "cannot use HDF5's in-memory driver");
  }
  H5::H5File file("statismo-model-in-memory.h5", H5F_ACC_TRUNC, H5::FileCreatPropList::DEFAULT, access);
  {
    WriteModelGroup(file, model);
    WriteRepresenter(file, model, triangles);
    H5::Group info = file.createGroup("/modelinfo");
    WriteString(info, "build-time", Now());
    H5::Group builder = file.createGroup("/modelinfo/modelBuilder-0");
    WriteString(builder, "buildTime", Now());
    WriteString(builder, "builderName", "itk::LandmarkFreeShapeModelEstimator (MeshExtraction)");
    H5::Group parameters = file.createGroup("/modelinfo/modelBuilder-0/parameters");
    WriteString(parameters, "description", builderInfo);
    file.createGroup("/modelinfo/modelBuilder-0/dataInfo");
    H5::Group version = file.createGroup("/version");
    WriteInteger(version, "majorVersion", 0);
    WriteInteger(version, "minorVersion", 9);
  }
  file.flush(H5F_SCOPE_GLOBAL);
  const ssize_t     size = H5Fget_file_image(file.getId(), nullptr, 0);
  std::vector<char> image(size > 0 ? static_cast<std::size_t>(size) : 0);
  if (size <= 0 || H5Fget_file_image(file.getId(), image.data(), image.size()) != size)
  {
    throw H5::FileIException("H5Fget_file_image", "cannot take the file's image from memory");
  }
  file.close();
  return image;
}
} // namespace

void
WriteStatismoModel(const std::string &                  fileName,
                   const PrincipalComponentModel &      model,
                   const std::vector<TriangleIndices> & triangles,
                   const std::string &                  builderInfo)
{
  std::vector<char> image;
  try
  {
    H5::Exception::dontPrint();
    image = MakeStatismoFileImage(model, triangles, builderInfo);
  }
  catch (const H5::Exception & e)
  {
    itkGenericExceptionMacro(<< "Cannot write the shape model " << fileName << ": " << e.getDetailMsg());
  }
  std::ofstream out(fileName, std::ios::binary | std::ios::trunc);
  out.write(image.data(), static_cast<std::streamsize>(image.size()));
  out.close();
  if (!out)
  {
    itkGenericExceptionMacro(<< "Cannot write the shape model " << fileName << ": writing its " << image.size()
                             << " bytes failed (a full disk or a size limit?)");
  }
}

namespace
{
/** The number of values of a dataset, refused (naming it) beyond `limit`: the sizes
 * come from the file, and a corrupt one must not ask for any amount of memory. */
hsize_t
CheckedCount(const H5::DataSpace & space, const std::string & path, hsize_t limit, std::vector<hsize_t> & dimensions)
{
  const int rank = space.getSimpleExtentNdims();
  if (rank < 0 || rank > 2)
  {
    itkGenericExceptionMacro(<< path << " has " << rank << " dimensions; the model's datasets have 1 or 2");
  }
  dimensions.assign(static_cast<std::size_t>(rank), 0);
  space.getSimpleExtentDims(dimensions.data());
  hsize_t count = 1;
  for (hsize_t d : dimensions)
  {
    if (d > limit || (d > 0 && count > limit / d))
    {
      itkGenericExceptionMacro(<< path << " claims more values than the file can hold (a corrupt file?)");
    }
    count *= d;
  }
  return count;
}

std::vector<float>
ReadFloats(H5::H5File & file, const std::string & path, std::vector<hsize_t> & dimensions, hsize_t limit)
{
  H5::DataSet        dataset = file.openDataSet(path);
  const hsize_t      count = CheckedCount(dataset.getSpace(), path, limit, dimensions);
  std::vector<float> values(count);
  dataset.read(values.data(), H5::PredType::NATIVE_FLOAT);
  for (hsize_t i = 0; i < count; ++i)
  {
    if (!std::isfinite(values[i]))
    {
      itkGenericExceptionMacro(<< path << " holds " << values[i] << " (value " << i << "): a corrupt file?");
    }
  }
  return values;
}
} // namespace

PrincipalComponentModel
ReadStatismoModel(const std::string & fileName, std::vector<TriangleIndices> & triangles)
{
  PrincipalComponentModel model;
  try
  {
    H5::Exception::dontPrint();
    H5::H5File file(fileName, H5F_ACC_RDONLY);
    // No dataset holds more values than the file has bytes (the module writes them
    // uncompressed; a compressed one of statismo's is allowed a generous ratio).
    const hsize_t        limit = std::max<hsize_t>(1u << 20, 64 * file.getFileSize());
    std::vector<hsize_t> dims;
    const auto           mean = ReadFloats(file, "/model/mean", dims, limit);
    model.mean.assign(mean.begin(), mean.end());
    const auto variances = ReadFloats(file, "/model/pcaVariance", dims, limit);
    model.variances.assign(variances.begin(), variances.end());
    for (const double v : model.variances)
    {
      if (v < 0.0)
      {
        itkGenericExceptionMacro(<< "/model/pcaVariance holds a negative variance " << v << " (a corrupt file?)");
      }
    }
    const auto        basis = ReadFloats(file, "/model/pcaBasis", dims, limit);
    const std::size_t k = dims.size() == 2 ? dims[1] : 0;
    if (dims.size() != 2 || dims[0] != model.mean.size() || k != model.variances.size())
    {
      itkGenericExceptionMacro(<< "pcaBasis is not " << model.mean.size() << " x " << model.variances.size());
    }
    model.basis.assign(k, std::vector<double>(model.mean.size()));
    for (std::size_t r = 0; r < model.mean.size(); ++r)
    {
      for (std::size_t c = 0; c < k; ++c)
      {
        model.basis[c][r] = basis[r * k + c];
      }
    }
    const auto noise = ReadFloats(file, "/model/noiseVariance", dims, limit);
    if (noise.empty())
    {
      itkGenericExceptionMacro(<< "/model/noiseVariance is empty");
    }
    model.noiseVariance = noise[0];
    for (double v : model.variances)
    {
      model.totalVariance += v;
    }
    H5::DataSet cells = file.openDataSet("/representer/cells");
    CheckedCount(cells.getSpace(), "/representer/cells", limit, dims);
    if (dims.size() != 2 || dims[0] != 3)
    {
      itkGenericExceptionMacro(<< "/representer/cells is not 3 x (number of triangles)");
    }
    std::vector<std::uint32_t> values(3 * dims[1]);
    cells.read(values.data(), H5::PredType::NATIVE_UINT32);
    triangles.resize(dims[1]);
    for (std::size_t f = 0; f < triangles.size(); ++f)
    {
      for (unsigned int d = 0; d < 3; ++d)
      {
        triangles[f][d] = values[d * triangles.size() + f];
        if (triangles[f][d] >= model.mean.size() / 3)
        {
          itkGenericExceptionMacro(<< "triangle " << f << " names a point the model does not have");
        }
      }
    }
  }
  catch (const H5::Exception & e)
  {
    itkGenericExceptionMacro(<< "Cannot read the shape model " << fileName << ": " << e.getDetailMsg());
  }
  catch (const itk::ExceptionObject & e)
  {
    itkGenericExceptionMacro(<< "Cannot read the shape model " << fileName << ": " << ExceptionReason(e));
  }
  catch (const std::bad_alloc &)
  {
    itkGenericExceptionMacro(<< "Cannot read the shape model " << fileName
                             << ": its sizes ask for more memory than there is (a corrupt file?)");
  }
  return model;
}
} // namespace detail
} // namespace MeshExtraction
} // namespace itk
