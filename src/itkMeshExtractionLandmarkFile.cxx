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
#include "itkMeshExtractionLandmarkFile.h"
#include "itkMacro.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>

namespace itk
{
namespace MeshExtraction
{
const JSONValue *
JSONValue::Find(const std::string & name) const
{
  for (const auto & member : members)
  {
    if (member.first == name)
    {
      return &member.second;
    }
  }
  return nullptr;
}

namespace
{
/** A recursive-descent reader of RFC 8259 JSON; nesting is limited so that a
 * hostile file cannot exhaust the stack. */
class JSONReader
{
public:
  JSONReader(const std::string & text, const std::string & source)
      : m_Text(text)
      , m_Source(source)
  {}

  JSONValue
  Document()
  {
    JSONValue value = this->Value(0);
    this->SkipSpace();
    if (m_Position != m_Text.size())
    {
      this->Fail("unexpected text after the JSON value");
    }
    return value;
  }

private:
  static constexpr unsigned int MaximumDepth = 256;

  [[noreturn]] void
  Fail(const std::string & problem) const
  {
    std::size_t line = 1;
    for (std::size_t i = 0; i < m_Position && i < m_Text.size(); ++i)
    {
      line += m_Text[i] == '\n' ? 1 : 0;
    }
    itkGenericExceptionMacro(<< m_Source << " is not valid JSON: " << problem << " (line " << line << ")");
  }

  void
  SkipSpace()
  {
    while (m_Position < m_Text.size() && (m_Text[m_Position] == ' ' || m_Text[m_Position] == '\t' ||
                                          m_Text[m_Position] == '\n' || m_Text[m_Position] == '\r'))
    {
      ++m_Position;
    }
  }

  bool
  Consume(char c)
  {
    this->SkipSpace();
    if (m_Position < m_Text.size() && m_Text[m_Position] == c)
    {
      ++m_Position;
      return true;
    }
    return false;
  }

  void
  Expect(char c)
  {
    if (!this->Consume(c))
    {
      this->Fail(std::string("expected '") + c + "'");
    }
  }

  bool
  Keyword(const char * word)
  {
    const std::size_t n = std::char_traits<char>::length(word);
    if (m_Text.compare(m_Position, n, word) == 0)
    {
      m_Position += n;
      return true;
    }
    return false;
  }

  JSONValue
  Value(unsigned int depth)
  {
    if (depth > MaximumDepth)
    {
      this->Fail("nested too deeply");
    }
    this->SkipSpace();
    if (m_Position >= m_Text.size())
    {
      this->Fail("unexpected end of text");
    }
    JSONValue  value;
    const char c = m_Text[m_Position];
    if (c == '{')
    {
      this->Object(value, depth);
    }
    else if (c == '[')
    {
      this->Array(value, depth);
    }
    else if (c == '"')
    {
      value.kind = JSONValue::Kind::String;
      value.text = this->String();
    }
    else if (this->Keyword("true") || this->Keyword("false"))
    {
      value.kind = JSONValue::Kind::Boolean;
      value.boolean = c == 't';
    }
    else if (this->Keyword("null"))
    {
      value.kind = JSONValue::Kind::Null;
    }
    else
    {
      value.kind = JSONValue::Kind::Number;
      value.number = this->Number();
    }
    return value;
  }

  void
  Object(JSONValue & value, unsigned int depth)
  {
    value.kind = JSONValue::Kind::Object;
    this->Expect('{');
    if (this->Consume('}'))
    {
      return;
    }
    do
    {
      this->SkipSpace();
      if (m_Position >= m_Text.size() || m_Text[m_Position] != '"')
      {
        this->Fail("expected a member name in quotes");
      }
      std::string name = this->String();
      this->Expect(':');
      value.members.emplace_back(std::move(name), this->Value(depth + 1));
    } while (this->Consume(','));
    this->Expect('}');
  }

  void
  Array(JSONValue & value, unsigned int depth)
  {
    value.kind = JSONValue::Kind::Array;
    this->Expect('[');
    if (this->Consume(']'))
    {
      return;
    }
    do
    {
      value.elements.push_back(this->Value(depth + 1));
    } while (this->Consume(','));
    this->Expect(']');
  }

  double
  Number()
  {
    // The JSON grammar: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?
    const std::size_t start = m_Position;
    auto              digits = [this]() {
      const std::size_t first = m_Position;
      while (m_Position < m_Text.size() && m_Text[m_Position] >= '0' && m_Text[m_Position] <= '9')
      {
        ++m_Position;
      }
      return m_Position > first;
    };
    if (m_Position < m_Text.size() && m_Text[m_Position] == '-')
    {
      ++m_Position;
    }
    if (!digits())
    {
      this->Fail("unexpected character '" + std::string(1, m_Text[start]) + "'");
    }
    if (m_Position < m_Text.size() && m_Text[m_Position] == '.')
    {
      ++m_Position;
      if (!digits())
      {
        this->Fail("a number needs digits after its decimal point");
      }
    }
    if (m_Position < m_Text.size() && (m_Text[m_Position] == 'e' || m_Text[m_Position] == 'E'))
    {
      ++m_Position;
      if (m_Position < m_Text.size() && (m_Text[m_Position] == '+' || m_Text[m_Position] == '-'))
      {
        ++m_Position;
      }
      if (!digits())
      {
        this->Fail("a number needs digits in its exponent");
      }
    }
    std::istringstream in(m_Text.substr(start, m_Position - start));
    in.imbue(std::locale::classic());
    double number = 0.0;
    in >> number;
    return number; // out of range: the stream gives +-max or 0, both finite
  }

  std::string
  String()
  {
    ++m_Position; // the opening quote
    std::string out;
    while (m_Position < m_Text.size())
    {
      const char c = m_Text[m_Position++];
      if (c == '"')
      {
        return out;
      }
      if (static_cast<unsigned char>(c) < 0x20)
      {
        this->Fail("a control character in a string");
      }
      if (c != '\\')
      {
        out += c;
        continue;
      }
      if (m_Position >= m_Text.size())
      {
        break;
      }
      const char e = m_Text[m_Position++];
      switch (e)
      {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u':
          this->Unicode(out);
          break;
        default:
          this->Fail("an unknown escape '\\" + std::string(1, e) + "'");
      }
    }
    this->Fail("a string without its closing quote");
  }

  unsigned int
  Hex4()
  {
    if (m_Position + 4 > m_Text.size())
    {
      this->Fail("a \\u escape needs four hexadecimal digits");
    }
    unsigned int code = 0;
    for (int k = 0; k < 4; ++k)
    {
      const char   h = m_Text[m_Position++];
      unsigned int digit = 0;
      if (h >= '0' && h <= '9')
      {
        digit = static_cast<unsigned int>(h - '0');
      }
      else if (h >= 'a' && h <= 'f')
      {
        digit = static_cast<unsigned int>(h - 'a' + 10);
      }
      else if (h >= 'A' && h <= 'F')
      {
        digit = static_cast<unsigned int>(h - 'A' + 10);
      }
      else
      {
        this->Fail("a \\u escape needs four hexadecimal digits");
      }
      code = code * 16 + digit;
    }
    return code;
  }

  /** A \u escape (and its low surrogate) as UTF-8. */
  void
  Unicode(std::string & out)
  {
    unsigned int code = this->Hex4();
    if (code >= 0xD800 && code <= 0xDBFF && m_Text.compare(m_Position, 2, "\\u") == 0)
    {
      m_Position += 2;
      const unsigned int low = this->Hex4();
      code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
    }
    if (code < 0x80)
    {
      out += static_cast<char>(code);
    }
    else if (code < 0x800)
    {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
    else if (code < 0x10000)
    {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
    else
    {
      out += static_cast<char>(0xF0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  const std::string & m_Text;
  const std::string & m_Source;
  std::size_t         m_Position{ 0 };
};

/** Three finite coordinates from a JSON array, or an exception naming the landmark. */
Point<double, 3>
CoordinatesOf(const JSONValue * array, const std::string & id, const std::string & fileName)
{
  if (array == nullptr || array->kind != JSONValue::Kind::Array || array->elements.size() != 3)
  {
    itkGenericExceptionMacro(<< fileName << ": landmark \"" << id << "\" needs three coordinates [x, y, z].");
  }
  Point<double, 3> p;
  for (unsigned int d = 0; d < 3; ++d)
  {
    const JSONValue & c = array->elements[d];
    if (c.kind != JSONValue::Kind::Number || !std::isfinite(c.number))
    {
      itkGenericExceptionMacro(<< fileName << ": landmark \"" << id << "\" has a coordinate that is not a finite "
                               << "number.");
    }
    // Beyond this, the distances and products the matching computes lose every digit
    // of the landmarks' differences (or overflow).
    if (!(std::abs(c.number) <= 1e9))
    {
      itkGenericExceptionMacro(<< fileName << ": landmark \"" << id << "\" has the coordinate " << c.number
                               << ", beyond +-1e9 mm.");
    }
    p[d] = c.number;
  }
  return p;
}

std::string
TextOf(const JSONValue * value)
{
  if (value == nullptr)
  {
    return "";
  }
  if (value->kind == JSONValue::Kind::String)
  {
    return value->text;
  }
  if (value->kind == JSONValue::Kind::Number)
  {
    std::ostringstream out;
    out << value->number;
    return out.str();
  }
  return "";
}

std::vector<NamedLandmark>
ModuleLandmarks(const JSONValue & document, const std::string & fileName)
{
  std::vector<NamedLandmark> landmarks;
  for (const JSONValue & entry : document.elements)
  {
    const std::string id = TextOf(entry.Find("id"));
    if (entry.kind != JSONValue::Kind::Object || id.empty())
    {
      itkGenericExceptionMacro(<< fileName << ": every entry of the landmark array needs an \"id\" and "
                               << "\"coordinates\".");
    }
    landmarks.push_back({ id, CoordinatesOf(entry.Find("coordinates"), id, fileName) });
  }
  return landmarks;
}

std::vector<NamedLandmark>
SlicerLandmarks(const JSONValue & markups, const std::string & fileName)
{
  std::vector<NamedLandmark> landmarks;
  for (const JSONValue & markup : markups.elements)
  {
    const std::string system = TextOf(markup.Find("coordinateSystem"));
    if (!system.empty() && system != "LPS" && system != "RAS")
    {
      itkGenericExceptionMacro(<< fileName << ": coordinateSystem \"" << system << "\" is neither LPS nor RAS.");
    }
    const JSONValue * points = markup.Find("controlPoints");
    if (points == nullptr || points->kind != JSONValue::Kind::Array)
    {
      continue;
    }
    for (const JSONValue & point : points->elements)
    {
      if (TextOf(point.Find("positionStatus")) == "missing")
      {
        continue;
      }
      std::string id = TextOf(point.Find("label"));
      if (id.empty())
      {
        id = TextOf(point.Find("id"));
      }
      Point<double, 3> p = CoordinatesOf(point.Find("position"), id, fileName);
      if (system != "LPS") // RAS, also where older files do not say
      {
        p[0] = -p[0];
        p[1] = -p[1];
      }
      landmarks.push_back({ id, p });
    }
  }
  return landmarks;
}
} // namespace

JSONValue
ParseJSON(const std::string & text, const std::string & source)
{
  return JSONReader(text, source).Document();
}

std::vector<NamedLandmark>
ReadLandmarkFile(const std::string & fileName)
{
  std::ifstream in(fileName, std::ios::binary);
  if (!in)
  {
    itkGenericExceptionMacro(<< "Cannot read the landmark file " << fileName << " (no such file, or not readable).");
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const JSONValue            document = ParseJSON(buffer.str(), fileName);
  std::vector<NamedLandmark> landmarks;
  if (document.kind == JSONValue::Kind::Array)
  {
    landmarks = ModuleLandmarks(document, fileName);
  }
  else if (const JSONValue * markups = document.Find("markups");
           markups != nullptr && markups->kind == JSONValue::Kind::Array)
  {
    landmarks = SlicerLandmarks(*markups, fileName);
  }
  else
  {
    itkGenericExceptionMacro(<< fileName << " holds no landmarks: expected an array of {\"id\", \"coordinates\"} or "
                             << "a 3D Slicer markups file ({\"markups\": [...]}).");
  }
  std::set<std::string> seen;
  for (const auto & landmark : landmarks)
  {
    if (!seen.insert(landmark.id).second)
    {
      itkGenericExceptionMacro(<< fileName << ": the landmark id \"" << landmark.id << "\" is given twice.");
    }
  }
  return landmarks;
}

void
WriteLandmarkFile(const std::string & fileName, const std::vector<NamedLandmark> & landmarks)
{
  std::ostringstream out;
  out.imbue(std::locale::classic());
  out << std::setprecision(std::numeric_limits<double>::max_digits10) << "[";
  for (std::size_t i = 0; i < landmarks.size(); ++i)
  {
    std::string id;
    for (char c : landmarks[i].id)
    {
      if (c == '"' || c == '\\')
      {
        id += '\\';
      }
      id += c;
    }
    out << (i ? ",\n " : "\n ") << "{\"id\": \"" << id << "\", \"coordinates\": [" << landmarks[i].point[0] << ", "
        << landmarks[i].point[1] << ", " << landmarks[i].point[2] << "]}";
  }
  out << "\n]\n";
  std::ofstream file(fileName, std::ios::binary);
  file << out.str();
  file.close();
  if (!file)
  {
    itkGenericExceptionMacro(<< "Cannot write the landmark file " << fileName << '.');
  }
}

std::vector<Point<double, 3>>
SelectLandmarks(const std::vector<NamedLandmark> & landmarks,
                const std::vector<std::string> &   ids,
                const std::string &                fileName)
{
  std::vector<Point<double, 3>> points;
  std::string                   missing;
  for (const auto & id : ids)
  {
    bool found = false;
    for (const auto & landmark : landmarks)
    {
      if (landmark.id == id)
      {
        points.push_back(landmark.point);
        found = true;
        break;
      }
    }
    if (!found)
    {
      missing += (missing.empty() ? "\"" : ", \"") + id + "\"";
    }
  }
  if (!missing.empty())
  {
    std::string present;
    for (const auto & landmark : landmarks)
    {
      present += (present.empty() ? "\"" : ", \"") + landmark.id + "\"";
    }
    itkGenericExceptionMacro(<< fileName << " has no landmark " << missing << " (it has "
                             << (present.empty() ? std::string("none") : present) << ").");
  }
  return points;
}
} // namespace MeshExtraction
} // namespace itk
