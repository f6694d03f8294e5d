// SPDX-License-Identifier: BSD-3-Clause
#include "csmFileChecks.h"

#include "vtkCellArray.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"
#include "vtk_jsoncpp.h"
#include "vtksys/SystemTools.hxx"

#include <json/json.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <unistd.h>
#include <vector>

namespace csmScenes
{
namespace
{
using Size = unsigned long long;

Size fileSize(const std::string& path)
{
  return static_cast<Size>(vtksys::SystemTools::FileLength(path));
}

/// Bytes of a PLY scalar type, 0 when unknown.
Size plyTypeSize(const std::string& type)
{
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8")
    return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16")
    return 2;
  if (type == "int" || type == "uint" || type == "float" || type == "int32" || type == "uint32" ||
    type == "float32")
    return 4;
  if (type == "double" || type == "float64")
    return 8;
  return 0;
}

std::string tooShort(const std::string& what, Size count, Size needed, Size size)
{
  std::ostringstream os;
  os << "the header says " << count << " " << what << ", which need at least " << needed
     << " bytes, but the file has " << size;
  return os.str();
}

std::string checkPly(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string line, format;
  struct Element
  {
    std::string Name;
    Size Count = 0;
    Size Bytes = 0; // binary: at least; ASCII: tokens
  };
  std::vector<Element> elements;
  Size header = 0;
  bool ended = false;
  while (header < 65536 && std::getline(in, line))
  {
    header += line.size() + 1;
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format")
      words >> format;
    else if (key == "element")
    {
      Element e;
      words >> e.Name >> e.Count;
      if (!words)
        return "bad 'element' line in the PLY header: " + line;
      elements.push_back(e);
    }
    else if (key == "property" && !elements.empty())
    {
      std::string type, countType, itemType;
      words >> type;
      if (type == "list")
        words >> countType >> itemType;
      const Size bytes = plyTypeSize(type == "list" ? countType : type);
      if (bytes == 0 || (type == "list" && plyTypeSize(itemType) == 0))
        return "unknown property type in the PLY header: " + line;
      elements.back().Bytes += format == "ascii" ? 1 : bytes;
    }
    else if (key == "end_header")
    {
      ended = true;
      break;
    }
  }
  if (!ended || format.empty())
    return "not a PLY file (no format or end_header in its header)";
  const Size size = fileSize(path);
  const Size body = size > header ? size - header : 0;
  Size needed = 0;
  for (const Element& e : elements)
  {
    // ASCII: at least one digit and one separator per value.
    const Size perElement = format == "ascii" ? 2 * e.Bytes : e.Bytes;
    if (perElement > 0 && e.Count > (body - needed) / perElement)
      return tooShort(e.Name + " elements", e.Count, needed + e.Count * perElement, body);
    needed += e.Count * perElement;
  }
  return {};
}

std::string checkLegacyVtk(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  bool binary = false;
  for (int i = 0; i < 1000 && std::getline(in, line); ++i)
  {
    std::istringstream words(line);
    std::string key;
    words >> key;
    key = vtksys::SystemTools::UpperCase(key);
    if (i == 2)
      binary = key == "BINARY";
    if (key == "POINTS")
    {
      double count = -1;
      std::string type;
      words >> count >> type;
      if (!words || !(count >= 0) || count != std::floor(count))
        return "bad POINTS line in the header: " + line;
      const Size size = fileSize(path);
      const Size bytesPerValue =
        binary ? (type == "double" ? 8 : (type == "float" || type == "int" ? 4 : 1)) : 2;
      const double needed = count * 3 * bytesPerValue;
      if (needed > static_cast<double>(size))
        return tooShort("points", static_cast<Size>(count), static_cast<Size>(needed), size);
      return {};
    }
  }
  return {};
}

std::string checkStl(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  char head[84] = {};
  in.read(head, sizeof(head));
  const Size size = fileSize(path);
  if (std::strncmp(head, "solid", 5) == 0)
  {
    // ASCII, unless it is binary with a header that begins with "solid": text has no NULs.
    const std::string start(head, static_cast<size_t>(in.gcount()));
    if (start.find('\0') == std::string::npos)
      return {};
  }
  if (size < 84)
    return "not an STL file: too short for a binary STL header";
  std::uint32_t triangles = 0;
  std::memcpy(&triangles, head + 80, 4); // little endian, as the format says
  // A binary STL is an 84-byte header and 50 bytes a triangle: exactly 84 + 50 n bytes.
  const Size expected = 84 + 50ull * triangles;
  if (triangles > 0 && size == expected)
    return {};
  if (triangles == 0 && size == expected)
    return "the header says 0 triangles: no surface in the file";
  std::ostringstream os;
  os << (size < expected ? "truncated" : "too long") << ": the header says " << triangles
     << " triangles, so a binary STL of " << expected << " bytes (84 + 50 * " << triangles
     << ") was expected, but the file has " << size;
  if (size < expected)
    os << " (" << (size - 84) / 50 << " whole triangles)";
  else
    os << " (" << size - expected << " more)";
  return os.str();
}

std::string checkGltf(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  Json::CharReaderBuilder builder;
  Json::Value root;
  std::string errors;
  if (!Json::parseFromStream(builder, in, &root, &errors))
  {
    std::string oneLine; // "* Line 1, Column 44\n  Missing '}'..." on one line
    std::istringstream lines(errors);
    for (std::string line; std::getline(lines, line) && oneLine.size() < 200;)
      oneLine += (oneLine.empty() ? "" : " ") + line.substr(line.find_first_not_of(" *"));
    return "not valid glTF JSON: " + oneLine;
  }
  if (!root.isObject() || !root["asset"].isObject())
    return "not a glTF file: no \"asset\" object";
  const std::string dir = vtksys::SystemTools::GetFilenamePath(path);
  const Json::Value& buffers = root["buffers"];
  for (Json::ArrayIndex i = 0; buffers.isArray() && i < buffers.size(); ++i)
  {
    const Json::Value& buffer = buffers[i];
    if (!buffer.isObject() || !buffer["uri"].isString())
      continue;
    const std::string uri = buffer["uri"].asString();
    if (uri.compare(0, 5, "data:") == 0)
      continue;
    const std::string file = dir.empty() ? uri : dir + "/" + uri;
    if (!vtksys::SystemTools::FileExists(file, true))
      return "its buffer '" + uri + "' does not exist";
    const Size need = buffer["byteLength"].isNumeric() ? buffer["byteLength"].asLargestUInt() : 0;
    if (fileSize(file) < need)
      return tooShort("bytes in buffer '" + uri + "'", need, need, fileSize(file));
  }
  return {};
}

/// The largest and smallest point index of the cells, against the point count.
std::string checkCells(vtkCellArray* cells, vtkIdType points)
{
  if (!cells || cells->GetNumberOfCells() == 0)
    return {};
  vtkDataArray* ids = cells->GetConnectivityArray();
  if (!ids || ids->GetNumberOfValues() == 0)
    return {};
  double range[2];
  ids->GetRange(range, 0);
  if (range[0] < 0 || range[1] >= static_cast<double>(points))
  {
    std::ostringstream os;
    os << "a cell refers to point " << static_cast<long long>(range[0] < 0 ? range[0] : range[1])
       << " (counting from 0), but there are " << points << " points";
    return os.str();
  }
  return {};
}
} // namespace

std::string CheckFileStructure(const std::string& path, const std::string& extension)
{
  if (extension == ".ply")
    return checkPly(path);
  if (extension == ".vtk")
    return checkLegacyVtk(path);
  if (extension == ".stl")
    return checkStl(path);
  if (extension == ".gltf")
    return checkGltf(path);
  return {};
}

std::string CheckOutputFile(const std::string& path)
{
  if (path.empty())
    return "no file name";
  if (vtksys::SystemTools::FileIsDirectory(path))
    return "'" + path + "' is a directory";
  if (vtksys::SystemTools::FileExists(path))
  {
    // Opened for writing, not truncated (access() answers yes to root for any file).
    const int fd = open(path.c_str(), O_WRONLY | O_APPEND | O_NONBLOCK);
    if (fd < 0)
      return "cannot write '" + path + "': " + std::strerror(errno);
    close(fd);
    return {};
  }
  const std::string folder = vtksys::SystemTools::GetFilenamePath(path);
  const std::string error = CheckOutputFolder(folder.empty() ? "." : folder);
  return error.empty() ? error : "cannot write '" + path + "': " + error;
}

std::string CheckOutputFolder(const std::string& path)
{
  if (!vtksys::SystemTools::FileExists(path))
    return "the folder '" + path + "' does not exist";
  if (!vtksys::SystemTools::FileIsDirectory(path))
    return "'" + path + "' is not a folder";
  // A file made and removed again (access() answers yes to root for any folder, even /proc).
  std::string probe = path + "/.csm-write-check-XXXXXX";
  const int fd = mkstemp(probe.data());
  if (fd < 0)
    return "cannot write in the folder '" + path + "': " + std::strerror(errno);
  close(fd);
  unlink(probe.c_str());
  return {};
}

std::string CheckReaderOutput(vtkDataObject* data)
{
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> it;
    it.TakeReference(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      const std::string error = CheckReaderOutput(it->GetCurrentDataObject());
      if (!error.empty())
        return error;
    }
    return {};
  }
  auto* set = vtkPointSet::SafeDownCast(data);
  if (!set)
    return {};
  vtkPoints* points = set->GetPoints();
  const vtkIdType count = points ? points->GetNumberOfPoints() : 0;
  vtkIdType bad = 0;
  for (vtkIdType i = 0; i < count; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    bad += std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) ? 0 : 1;
  }
  if (bad > 0)
    return std::to_string(bad) + " of " + std::to_string(count) +
      " points have coordinates that are not finite (NaN or infinity)";
  if (auto* poly = vtkPolyData::SafeDownCast(set))
  {
    for (vtkCellArray* cells :
      { poly->GetVerts(), poly->GetLines(), poly->GetPolys(), poly->GetStrips() })
    {
      const std::string error = checkCells(cells, count);
      if (!error.empty())
        return error;
    }
  }
  else if (auto* grid = vtkUnstructuredGrid::SafeDownCast(set))
  {
    return checkCells(grid->GetCells(), count);
  }
  return {};
}

} // namespace csmScenes
