// The .vtp check (Module/IO/VtpFileCheck.cxx) against VTK's own writer and reader: every file
// vtkXMLPolyDataWriter makes (ASCII, inline binary, appended raw and base64; no compression,
// zlib, LZ4, LZMA; 32- and 64-bit headers; verts, lines, strips, polygons, point, cell and field
// data, string and bit arrays) passes and reads back whole; files whose counts, block tables or
// offsets lie are refused with a sentence before the reader sees them.
#include "MeshFileCheck.h"

#include "vtkBitArray.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace
{
std::string TempPath(const std::string& name)
{
  return ::testing::TempDir() + "/catar_vtp_" + name;
}

// A mesh with every kind of cell and data: a sphere's triangles as polygons and as strips, two
// lines, three vertices; a point array, a cell array and a field array.
vtkSmartPointer<vtkPolyData> RichMesh()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(12);
  sphere->SetPhiResolution(8);
  sphere->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(sphere->GetOutput());
  vtkNew<vtkCellArray> strips;
  const vtkIdType strip[5] = { 0, 2, 3, 4, 5 };
  strips->InsertNextCell(5, strip);
  mesh->SetStrips(strips);
  vtkNew<vtkCellArray> lines;
  const vtkIdType line[3] = { 0, 1, 2 };
  lines->InsertNextCell(3, line);
  lines->InsertNextCell(2, line);
  mesh->SetLines(lines);
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < 3; ++i)
  {
    verts->InsertNextCell(1, &i);
  }
  mesh->SetVerts(verts);
  vtkNew<vtkFloatArray> cellValue;
  cellValue->SetName("CellValue");
  for (vtkIdType i = 0; i < mesh->GetNumberOfCells(); ++i)
  {
    cellValue->InsertNextValue(static_cast<float>(i));
  }
  mesh->GetCellData()->AddArray(cellValue);
  vtkNew<vtkFloatArray> second;
  second->DeepCopy(cellValue);
  second->SetName("Second");
  mesh->GetCellData()->AddArray(second);
  vtkNew<vtkIntArray> field;
  field->SetName("Field");
  field->SetNumberOfComponents(2);
  field->InsertNextTuple2(7, 8);
  mesh->GetFieldData()->AddArray(field);
  vtkNew<vtkStringArray> names;
  names->SetName("Names");
  names->InsertNextValue("sphere");
  names->InsertNextValue("");
  names->InsertNextValue("strips and lines");
  mesh->GetFieldData()->AddArray(names);
  vtkNew<vtkStringArray> labels;
  labels->SetName("Labels");
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    labels->InsertNextValue(i % 3 ? "p" : "");
  }
  mesh->GetPointData()->AddArray(labels);
  vtkNew<vtkBitArray> flags;
  flags->SetName("Flags");
  for (vtkIdType i = 0; i < mesh->GetNumberOfCells(); ++i)
  {
    flags->InsertNextValue(static_cast<int>(i % 2));
  }
  mesh->GetCellData()->AddArray(flags);
  return mesh;
}

std::string Slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void Spit(const std::string& path, const std::string& text)
{
  std::ofstream(path, std::ios::binary) << text;
}
} // namespace

TEST(VtpFileCheck, EveryFileVtkWritesPassesAndReadsBack)
{
  const auto mesh = RichMesh();
  int files = 0;
  for (int mode : { vtkXMLWriter::Ascii, vtkXMLWriter::Binary, vtkXMLWriter::Appended })
  {
    for (int encode : { 0, 1 })
    {
      for (int compressor :
        { vtkXMLWriter::NONE, vtkXMLWriter::ZLIB, vtkXMLWriter::LZ4, vtkXMLWriter::LZMA })
      {
        for (int header : { vtkXMLWriter::UInt32, vtkXMLWriter::UInt64 })
        {
          if ((mode != vtkXMLWriter::Appended && encode == 0) ||
            (mode == vtkXMLWriter::Ascii &&
              (compressor != vtkXMLWriter::NONE || header != vtkXMLWriter::UInt32)))
          {
            continue; // the same file as another combination
          }
          const std::string path = TempPath("good.vtp");
          vtkNew<vtkXMLPolyDataWriter> writer;
          writer->SetInputData(mesh);
          writer->SetFileName(path.c_str());
          writer->SetDataMode(mode);
          writer->SetEncodeAppendedData(encode);
          writer->SetCompressorType(compressor);
          writer->SetHeaderType(header);
          writer->SetBlockSize(256); // several blocks an array
          ASSERT_EQ(writer->Write(), 1);
          std::string error;
          EXPECT_TRUE(catar::CheckVtpFile(path, error))
            << "mode " << mode << " encode " << encode << " compressor " << compressor << " header "
            << header << ": " << error;
          EXPECT_TRUE(catar::CheckMeshFile(path, error)) << error;
          vtkNew<vtkXMLPolyDataReader> reader;
          reader->SetFileName(path.c_str());
          reader->Update();
          EXPECT_EQ(reader->GetOutput()->GetNumberOfCells(), mesh->GetNumberOfCells());
          ++files;
        }
      }
    }
  }
  EXPECT_EQ(files, 1 + 8 + 16);
}

TEST(VtpFileCheck, LyingFilesAreRefused)
{
  const auto mesh = RichMesh();
  struct Case
  {
    int mode;
    int compressor;
    std::string from;
    std::string to;
    std::string expected;
  };
  const std::string points = "NumberOfPoints=\"" + std::to_string(mesh->GetNumberOfPoints());
  const std::vector<Case> cases = {
    { vtkXMLWriter::Ascii, vtkXMLWriter::NONE, points, "NumberOfPoints=\"1000000000", "numbers" },
    { vtkXMLWriter::Binary, vtkXMLWriter::NONE, points, "NumberOfPoints=\"1000000000", "values" },
    { vtkXMLWriter::Appended, vtkXMLWriter::ZLIB, points, "NumberOfPoints=\"1000000000", "values" },
    { vtkXMLWriter::Ascii, vtkXMLWriter::NONE, "NumberOfPolys=\"", "NumberOfPolys=\"9", "offsets" },
    { vtkXMLWriter::Ascii, vtkXMLWriter::NONE, "3 6 9", "3 2 9", "offsets must rise" },
    { vtkXMLWriter::Appended, vtkXMLWriter::ZLIB, "offset=\"0\"", "offset=\"99999999\"",
      "past the end" },
    { vtkXMLWriter::Ascii, vtkXMLWriter::NONE, "type=\"Float32\"", "type=\"Float128\"",
      "unknown type" },
    { vtkXMLWriter::Ascii, vtkXMLWriter::NONE, "</PolyData>", "</Poly>", "closed by" },
    { vtkXMLWriter::Ascii, vtkXMLWriter::NONE, "type=\"PolyData\"", "type=\"ImageData\"",
      "not a PolyData file" },
    // A string array that announces more strings than it has bytes.
    { vtkXMLWriter::Binary, vtkXMLWriter::ZLIB, "Name=\"Names\" NumberOfTuples=\"3\"",
      "Name=\"Names\" NumberOfTuples=\"300000000\"", "array 'Names' has" },
    // Two cell arrays of one name: the reader read into the one the data set had dropped.
    { vtkXMLWriter::Ascii, vtkXMLWriter::NONE, "Name=\"Second\"", "Name=\"CellValue\"",
      "<CellData> has two arrays named 'CellValue'" },
    // An empty piece whose array claims 2^32 components: the reader named each one, for minutes.
    { vtkXMLWriter::Appended, vtkXMLWriter::ZLIB, "NumberOfComponents=\"3\"",
      "NumberOfComponents=\"4294967296\"", "NumberOfComponents must be in [1, 1024]" },
  };
  for (const Case& c : cases)
  {
    const std::string path = TempPath("bad.vtp");
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputData(mesh);
    writer->SetFileName(path.c_str());
    writer->SetDataMode(c.mode);
    writer->SetCompressorType(c.compressor);
    writer->SetEncodeAppendedData(0);
    ASSERT_EQ(writer->Write(), 1);
    std::string text = Slurp(path);
    const std::size_t at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    text.replace(at, c.from.size(), c.to);
    Spit(path, text);
    std::string error;
    EXPECT_FALSE(catar::CheckVtpFile(path, error)) << c.from << " -> " << c.to;
    EXPECT_NE(error.find(c.expected), std::string::npos)
      << "error '" << error << "' lacks '" << c.expected << "'";
    EXPECT_NE(error.find(path), std::string::npos) << error;
  }
  // Compressed block tables that lie: a block size of zero, a last block larger than the others,
  // a compressed size past the file; and a file cut short.
  const std::string path = TempPath("table.vtp");
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(mesh);
  writer->SetFileName(path.c_str());
  writer->SetDataMode(vtkXMLWriter::Appended);
  writer->SetEncodeAppendedData(0);
  writer->SetCompressorTypeToZLib();
  ASSERT_EQ(writer->Write(), 1);
  const std::string good = Slurp(path);
  const std::size_t data = good.find('_', good.find("<AppendedData")) + 1;
  for (int word : { 1, 2, 3 })
  {
    std::string bad = good;
    for (int k = 0; k < 4; ++k)
    {
      bad[data + 4 * word + k] = static_cast<char>(word == 1 ? 0 : 0x7f);
    }
    Spit(path, bad);
    std::string error;
    EXPECT_FALSE(catar::CheckVtpFile(path, error)) << "header word " << word;
  }
  Spit(path, good.substr(0, good.size() - 40));
  std::string error;
  EXPECT_FALSE(catar::CheckVtpFile(path, error));
  std::remove(path.c_str());
}
