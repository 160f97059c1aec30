#ifndef vpCliTableSchema_h
#define vpCliTableSchema_h

#include <string>
#include <vector>

namespace vp
{
namespace cli
{
/// One column of a table a CLI hands Slicer: its name, its type as Slicer's table schema names it
/// ("string", "int", "double") and its unit.
struct TableColumn
{
  std::string Name;
  std::string Type;
  std::string Unit;
};

/// The columns of a frames table (frames.csv) typed by their names: levels, classes and inside
/// flags text (an unknown inside stays empty, never 0), the frame a whole number, every other
/// column a number with its unit (mm, mm3, ms, s, N).
std::vector<TableColumn> FramesTableColumns(const std::string& headerLine);

/// Writes the schema Slicer reads beside a table to type its columns (vtkMRMLTableStorageNode:
/// table.csv's is table.schema.csv, comma-separated; a .tsv's is tab-separated): columnName,
/// type, unitLabel, and nullValue "nan" for numbers, so that an empty cell (no answer) is read as
/// no number rather than 0. Without it Slicer reads every column as text. Throws InputError
/// naming the file.
void WriteTableSchema(const std::string& tableFile, const std::vector<TableColumn>& columns);
} // namespace cli
} // namespace vp

#endif
