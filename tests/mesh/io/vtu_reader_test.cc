#include "mesh/io/vtu_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_replace.h"
#include "mesh/io/base64.h"
#include "support/status_message.h"

namespace kerf::mesh {
namespace {

using ::testing::ElementsAre;

std::string Vtu(const std::string& root_attributes, const std::string& points,
                const std::string& connectivity, const std::string& offsets,
                const std::string& types, const std::string& format = "ascii",
                const std::string& number_of_points = "5") {
  return absl::StrCat(
      "<?xml version=\"1.0\"?>\n<!-- written by hand -->\n<VTKFile type=\"UnstructuredGrid\" ",
      root_attributes, ">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"", number_of_points,
      "\" NumberOfCells=\"3\">\n<PointData/>\n<Points>\n<DataArray type=\"Float64\" "
      "NumberOfComponents=\"3\" format=\"",
      format, "\">", points,
      "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" "
      "format=\"",
      format, "\">", connectivity,
      "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"", format, "\">", offsets,
      "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"", format, "\">", types,
      "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
}

const std::string kAsciiPoints = "0 0 0 1 0 0 0 1 0 0 0 1 1 1 1";

template <typename T>
std::string Binary(const std::vector<T>& values, bool header64, bool separate_header) {
  const std::uint64_t count = values.size() * sizeof(T);
  std::string header(header64 ? 8 : 4, '\0');
  std::memcpy(header.data(), &count, header.size());
  std::string data(count, '\0');
  std::memcpy(data.data(), values.data(), count);
  return separate_header ? internal::Base64Encode(header) + internal::Base64Encode(data)
                         : internal::Base64Encode(header + data);
}

void ExpectTheTwoVtuTets(const absl::StatusOr<TetMeshData>& data) {
  ASSERT_TRUE(data.ok()) << data.status();
  ASSERT_EQ(data->points.size(), 5u);
  EXPECT_EQ(data->points[4], Eigen::Vector3d(1, 1, 1));
  ASSERT_EQ(data->tets.size(), 2u);  // the triangle is skipped
  EXPECT_THAT(data->tets[0], ElementsAre(0, 1, 2, 3));
  EXPECT_THAT(data->tets[1], ElementsAre(1, 2, 3, 4));
}

TEST(ParseVtu, Ascii) {
  ExpectTheTwoVtuTets(
      ParseVtu(Vtu("", kAsciiPoints, "0 1 2 3 1 2 3 4 0 1 2", "4 8 11", "10 10 5"), "a.vtu"));
}

TEST(ParseVtu, BinaryWithEitherHeaderSizeAndEitherHeaderEncoding) {
  const std::vector<double> points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  const std::vector<std::int32_t> connectivity = {0, 1, 2, 3, 1, 2, 3, 4, 0, 1, 2};
  const std::vector<std::int64_t> offsets = {4, 8, 11};
  const std::vector<std::uint8_t> types = {10, 10, 5};
  for (const bool header64 : {false, true}) {
    for (const bool separate : {false, true}) {
      const std::string text =
          Vtu(header64 ? "header_type=\"UInt64\"" : "", Binary(points, header64, separate),
              Binary(connectivity, header64, separate), Binary(offsets, header64, separate),
              Binary(types, header64, separate), "binary");
      ExpectTheTwoVtuTets(ParseVtu(text, "b.vtu"));
    }
  }
}

TEST(ParseVtu, Errors) {
  const std::string good = Vtu("", kAsciiPoints, "0 1 2 3 1 2 3 4 0 1 2", "4 8 11", "10 10 5");
  const std::pair<std::string, std::string> cases[] = {
      {"<VTKFile type=\"PolyData\"></VTKFile>",
       "bad.vtu:1: expected <VTKFile type=\"UnstructuredGrid\">"},
      {"<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid>",
       "bad.vtu:1: expected </UnstructuredGrid>"},
      {absl::StrReplaceAll(good, {{"<VTKFile ", "<VTKFile compressor=\"vtkZLibDataCompressor\" "}}),
       "bad.vtu:3: compressed data (vtkZLibDataCompressor) is not supported: save uncompressed"},
      {absl::StrReplaceAll(good, {{"</Piece>", "</Piece><AppendedData encoding=\"raw\">_"}}),
       "bad.vtu:15: appended data is not supported: save the VTU with inline ascii or binary "
       "arrays"},
      {Vtu("", "0 0 0 1 0 0 0 1 0 0 0 1 1 1 oops", "0", "1", "1"),
       "bad.vtu:8: DataArray (unnamed): expected a finite number, found 'oops'"},
      {Vtu("", kAsciiPoints, "0 1 2 3 1 2 3 9 0 1 2", "4 8 11", "10 10 5"),
       "bad.vtu:11: cell 1 names point 9 of 5"},
      {Vtu("", kAsciiPoints, "0 1 2 3 1 2 3 4 0 1 2", "4 8 11", "10 12 5"),
       "bad.vtu:13: cell 1 has type 12, which is not supported: kerf reads tetrahedra (type 10)"},
      {Vtu("", kAsciiPoints, "0 1 2 3 1 2 3 4 0 1 2", "4 8 11", "10 10 5", "ascii", "6"),
       "bad.vtu:5: NumberOfPoints does not match the 5 points given"},
      {Vtu("", "AAAA", "0", "1", "1", "binary"),
       "bad.vtu:8: DataArray (unnamed): binary data is shorter than its header"},
      {Vtu("", internal::Base64Encode(std::string("\x64\0\0\0", 4) + std::string(8, '\0')), "0",
           "1", "1", "binary"),
       "bad.vtu:8: DataArray (unnamed): header declares 100 bytes of Float64 but 8 bytes follow"},
      {Vtu("", "!!!!", "0", "1", "1", "binary"),
       "bad.vtu:8: DataArray (unnamed): invalid base64 data"},
  };
  for (const auto& [text, message] : cases) {
    EXPECT_EQ(kerf::testing::StatusMessage(ParseVtu(text, "bad.vtu")), message) << text;
  }
}

}  // namespace
}  // namespace kerf::mesh
