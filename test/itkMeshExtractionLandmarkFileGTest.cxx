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
#include "itksys/SystemTools.hxx"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace ME = itk::MeshExtraction;

namespace
{
std::string
ParseError(const std::string & text)
{
  try
  {
    ME::ParseJSON(text, "test.json");
  }
  catch (const itk::ExceptionObject & e)
  {
    return e.GetDescription();
  }
  return "no exception";
}

/** A directory of this test's own under the system's temporary directory. */
std::string
Scratch()
{
  const std::string directory = (std::filesystem::temp_directory_path() / "meshextraction-landmark-test").string();
  itksys::SystemTools::MakeDirectory(directory);
  return directory;
}

std::string
WriteText(const std::string & name, const std::string & text)
{
  const std::string path = Scratch() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string
ReadError(const std::string & path)
{
  try
  {
    ME::ReadLandmarkFile(path);
  }
  catch (const itk::ExceptionObject & e)
  {
    return e.GetDescription();
  }
  return "no exception";
}
} // namespace

TEST(LandmarkFile, ParsesJSON)
{
  const ME::JSONValue v = ME::ParseJSON(R"({"a": [1, -2.5e2, true, null, "x\"\u00e9\ud83d\ude00"], "b": {}, "c": []})");
  ASSERT_EQ(v.kind, ME::JSONValue::Kind::Object);
  const ME::JSONValue * a = v.Find("a");
  ASSERT_NE(a, nullptr);
  ASSERT_EQ(a->elements.size(), 5u);
  EXPECT_EQ(a->elements[0].number, 1.0);
  EXPECT_EQ(a->elements[1].number, -250.0);
  EXPECT_TRUE(a->elements[2].boolean);
  EXPECT_EQ(a->elements[3].kind, ME::JSONValue::Kind::Null);
  EXPECT_EQ(a->elements[4].text, "x\"\xc3\xa9\xf0\x9f\x98\x80");
  EXPECT_EQ(v.Find("b")->kind, ME::JSONValue::Kind::Object);
  EXPECT_EQ(v.Find("missing"), nullptr);
}

TEST(LandmarkFile, RefusesInvalidJSONWithTheLine)
{
  EXPECT_NE(ParseError("[1, 2").find("test.json is not valid JSON: expected ']' (line 1)"), std::string::npos);
  EXPECT_NE(ParseError("{\n\"a\": NaN}").find("unexpected character 'N' (line 2)"), std::string::npos);
  EXPECT_NE(ParseError("[1.]").find("digits after its decimal point"), std::string::npos);
  EXPECT_NE(ParseError("\"abc").find("without its closing quote"), std::string::npos);
  EXPECT_NE(ParseError("[1] 2").find("unexpected text after the JSON value"), std::string::npos);
  EXPECT_NE(ParseError(std::string(100000, '[')).find("nested too deeply"), std::string::npos);
  EXPECT_NE(ParseError("").find("unexpected end of text"), std::string::npos);
}

TEST(LandmarkFile, ReadsTheModuleFormatAndSlicerMarkups)
{
  const std::string own = WriteText("landmarks-own.json",
                                    R"([{"id": "A", "coordinates": [1, 2, 3], "uncertainty": {}},
                                        {"id": "B", "coordinates": [4, 5, 6]}])");
  const auto        l = ME::ReadLandmarkFile(own);
  ASSERT_EQ(l.size(), 2u);
  EXPECT_EQ(l[1].id, "B");
  EXPECT_EQ(l[1].point[2], 6.0);

  // Slicer: RAS points become LPS; LPS points stay; missing ones are skipped.
  const std::string slicer = WriteText("landmarks.mrk.json", R"({"@schema": "x", "markups": [
    {"type": "Fiducial", "coordinateSystem": "RAS", "controlPoints": [
      {"id": "1", "label": "A", "position": [1.5, -2, 3]},
      {"id": "2", "label": "B", "position": [0, 0, 0], "positionStatus": "missing"}]},
    {"type": "Fiducial", "coordinateSystem": "LPS", "controlPoints": [
      {"id": "3", "label": "C", "position": [7, 8, 9]}]}]})");
  const auto        s = ME::ReadLandmarkFile(slicer);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].id, "A");
  EXPECT_EQ(s[0].point[0], -1.5);
  EXPECT_EQ(s[0].point[1], 2.0);
  EXPECT_EQ(s[0].point[2], 3.0);
  EXPECT_EQ(s[1].point[0], 7.0);

  const auto picked = ME::SelectLandmarks(s, { "C", "A" }, slicer);
  EXPECT_EQ(picked[0][0], 7.0);

  // Round trip through the writer.
  const std::string written = Scratch() + "/written.json";
  ME::WriteLandmarkFile(written, s);
  const auto back = ME::ReadLandmarkFile(written);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].point, s[0].point);
}

TEST(LandmarkFile, NamesTheFileAndTheProblem)
{
  EXPECT_NE(ReadError("/nonexistent/x.json").find("Cannot read the landmark file /nonexistent/x.json"),
            std::string::npos);
  EXPECT_NE(ReadError(WriteText("bad-count.json", R"([{"id": "A", "coordinates": [1, 2]}])"))
              .find("landmark \"A\" needs three coordinates"),
            std::string::npos);
  EXPECT_NE(ReadError(WriteText("twice.json", R"([{"id": "A", "coordinates": [1, 2, 3]},
                                                  {"id": "A", "coordinates": [1, 2, 3]}])"))
              .find("the landmark id \"A\" is given twice"),
            std::string::npos);
  EXPECT_NE(ReadError(WriteText("neither.json", R"({"points": []})")).find("holds no landmarks"), std::string::npos);
  EXPECT_NE(
    ReadError(WriteText("system.json", R"({"markups": [{"coordinateSystem": "XYZ"}]})")).find("neither LPS nor RAS"),
    std::string::npos);
  const std::vector<ME::NamedLandmark> l{ { "A", {} }, { "B", {} } };
  try
  {
    ME::SelectLandmarks(l, { "A", "C", "D" }, "f.json");
    ADD_FAILURE();
  }
  catch (const itk::ExceptionObject & e)
  {
    EXPECT_NE(std::string(e.GetDescription()).find("f.json has no landmark \"C\", \"D\" (it has \"A\", \"B\")"),
              std::string::npos);
  }
}
