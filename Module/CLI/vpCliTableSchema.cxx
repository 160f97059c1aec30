#include "vpCliTableSchema.h"

#include "vpOutputFile.h"

#include <filesystem>

namespace vp
{
namespace cli
{
namespace
{
bool EndsWith(const std::string& text, const std::string& end)
{
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

TableColumn Typed(const std::string& name)
{
  if (name == "nearest_class" || name == "level_class" || name == "level_cause" || name == "tumour_id" || EndsWith(name, "_level") ||
    EndsWith(name, "_inside") || EndsWith(name, "_inside_uncertain"))
  {
    return { name, "string", "" };
  }
  if (name == "frame")
  {
    return { name, "int", "" };
  }
  const bool length = EndsWith(name, "_mm") || EndsWith(name, "_x") || EndsWith(name, "_y") || EndsWith(name, "_z");
  const std::string unit = name == "time" ? "s"
    : EndsWith(name, "_ms")               ? "ms"
    : EndsWith(name, "_mm3")              ? "mm3"
    : EndsWith(name, "_n")                ? "N"
    : name.rfind("axis_", 0) == 0 || name.rfind("haptic_", 0) == 0 ? ""
    : length                              ? "mm"
                                          : "";
  return { name, "double", unit };
}
} // namespace

std::vector<TableColumn> FramesTableColumns(const std::string& headerLine)
{
  std::vector<TableColumn> columns;
  std::string name;
  for (std::size_t i = 0; i <= headerLine.size(); ++i)
  {
    if (i == headerLine.size() || headerLine[i] == ',' || headerLine[i] == '\n' || headerLine[i] == '\r')
    {
      if (!name.empty())
      {
        columns.push_back(Typed(name));
      }
      name.clear();
      continue;
    }
    name += headerLine[i];
  }
  return columns;
}

void WriteTableSchema(const std::string& tableFile, const std::vector<TableColumn>& columns)
{
  const std::filesystem::path table(tableFile);
  const std::string separator = table.extension() == ".csv" ? "," : "\t";
  std::string schema = "columnName" + separator + "type" + separator + "unitLabel" + separator + "nullValue\n";
  for (const TableColumn& c : columns)
  {
    schema += c.Name + separator + c.Type + separator + c.Unit + separator + (c.Type == "double" ? "nan" : "") + "\n";
  }
  WriteFileAtomically((table.parent_path() / (table.stem().string() + ".schema" + table.extension().string())).string(), schema);
}
} // namespace cli
} // namespace vp
