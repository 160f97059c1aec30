#include "vpCohortManifest.h"

#include "vpInputError.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>
#include <sstream>

#include <sys/stat.h>

namespace vp
{
namespace
{
constexpr std::size_t MaxCaseNameLength = 64;
/// A manifest is a list of paths: a file larger than this (some 20,000 cases) is not one.
constexpr std::streamoff MaxManifestBytes = 4 << 20;

std::string Trim(const std::string& text)
{
  const std::size_t begin = text.find_first_not_of(" \t\r");
  const std::size_t end = text.find_last_not_of(" \t\r");
  return begin == std::string::npos ? std::string() : text.substr(begin, end - begin + 1);
}

/// Why name cannot be a case's folder ("" when it can): no path, no hidden file, nothing a shell
/// or a file system would read otherwise.
std::string CaseNameProblem(const std::string& name)
{
  if (name.size() > MaxCaseNameLength)
  {
    return "a case name has at most " + std::to_string(MaxCaseNameLength) + " characters";
  }
  if (name == "." || name == ".." || name[0] == '.' || name[0] == '-')
  {
    return "a case name cannot start with '.' or '-'";
  }
  for (const char c : name)
  {
    const auto u = static_cast<unsigned char>(c);
    if (!(u < 128 && (std::isalnum(u) || c == '_' || c == '-' || c == '.')))
    {
      return "a case name holds letters, digits, '.', '_' and '-' only";
    }
  }
  // The run's own files beside the case folders: a case so named would be written over them.
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  if (IsCohortFileName(lower))
  {
    return "the name of one of the cohort's own files (cohort.csv, cohort.png, cohort-K-of-N.csv)";
  }
  return std::string();
}

std::string Resolved(const std::string& path, const std::string& folder)
{
  return path.empty() || path[0] == '/' || folder.empty() ? path : folder + "/" + path;
}
} // namespace

bool IsCohortFileName(const std::string& name)
{
  return name == "cohort.csv" || name == "cohort.png" ||
    (name.rfind("cohort-", 0) == 0 && name.size() >= 11 && name.compare(name.size() - 4, 4, ".csv") == 0);
}

const std::vector<std::string>& CohortManifestColumns()
{
  static const std::vector<std::string> columns = { "case", "segmentation", "poses", "tips", "plan", "scalpel", "pose_space",
    "pose_units", "time_units", "tool", "reference" };
  return columns;
}

std::vector<std::string> SplitCsvLine(const std::string& line, const std::string& source)
{
  std::vector<std::string> cells(1);
  bool quoted = false, closed = false;
  for (std::size_t i = 0; i < line.size(); ++i)
  {
    const char c = line[i];
    if (quoted)
    {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
      {
        cells.back() += '"';
        ++i;
      }
      else if (c == '"')
      {
        quoted = false;
        closed = true;
      }
      else
      {
        cells.back() += c;
      }
    }
    else if (c == ',')
    {
      cells.emplace_back();
      closed = false;
    }
    else if (c == '"' && Trim(cells.back()).empty() && !closed)
    {
      cells.back().clear();
      quoted = true;
    }
    else if (closed && c != ' ' && c != '\t' && c != '\r')
    {
      throw InputError(source, "text after a closing quote");
    }
    else if (!closed)
    {
      cells.back() += c;
    }
  }
  if (quoted)
  {
    throw InputError(source, "a quote is not closed");
  }
  for (std::string& cell : cells)
  {
    cell = Trim(cell);
  }
  return cells;
}

namespace
{
/// The header's columns: per cell, its index in CohortManifestColumns(); case and segmentation
/// required, none twice.
std::vector<int> HeaderColumns(const std::vector<std::string>& cells, const std::string& at)
{
  const auto& known = CohortManifestColumns();
  std::vector<int> columnOf;
  std::set<int> seen;
  for (const std::string& cell : cells)
  {
    std::string name = cell;
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
    const auto it = std::find(known.begin(), known.end(), name);
    if (it == known.end())
    {
      throw InputError(at, "unknown column '" + Printable(cell) +
          "' (the header names case,segmentation[,poses][,tips][,plan][,scalpel][,pose_space][,pose_units][,time_units]"
          "[,tool][,reference])");
    }
    const int index = static_cast<int>(it - known.begin());
    if (!seen.insert(index).second)
    {
      throw InputError(at, "column '" + name + "' is named twice");
    }
    columnOf.push_back(index);
  }
  if (!seen.count(0) || !seen.count(1))
  {
    throw InputError(at, "the header must name the columns case and segmentation (a header comes first)");
  }
  return columnOf;
}

/// The plan's cell: tumours separated by ';', each FILE or ID=FILE, the files the manifest's.
std::vector<std::string> PlanEntries(const std::string& cell, const std::string& folder, const std::string& at)
{
  std::vector<std::string> plan;
  for (std::size_t begin = 0; begin <= cell.size() && !cell.empty();)
  {
    const std::size_t end = std::min(cell.find(';', begin), cell.size());
    const std::string entry = Trim(cell.substr(begin, end - begin));
    if (entry.empty())
    {
      throw InputError(at, "an empty entry in the plan ('" + Printable(cell) + "')");
    }
    const std::size_t equals = entry.find('=');
    plan.push_back(equals == std::string::npos ? Resolved(entry, folder)
                                               : entry.substr(0, equals + 1) + Resolved(entry.substr(equals + 1), folder));
    begin = end + 1;
  }
  return plan;
}

/// A cell saying how the case's poses are read (column 6 to 10), as track's option of its name
/// does; empty: as the file declares.
void ReadingCell(int column, const std::string& value, const std::string& at, PoseReading& reading)
{
  if (value.empty())
  {
    return;
  }
  static const char* const declared[] = { "pose-space", "pose-units", "time-units" };
  if (column <= 8)
  {
    ApplyPoseDeclaration(std::string(declared[column - 6]) + ": " + value, at, reading);
  }
  else
  {
    (column == 9 ? reading.ToolName : reading.ReferenceName) = value;
  }
}

/// One case's row, checked: its name a folder's, its segmentation given, a plan only with poses.
CohortCase CaseOf(const std::vector<std::string>& cells, const std::vector<int>& columnOf, const std::string& folder,
  const std::string& at)
{
  if (cells.size() != columnOf.size())
  {
    throw InputError(at, std::to_string(cells.size()) + " cells where the header names " + std::to_string(columnOf.size()));
  }
  CohortCase c;
  for (std::size_t k = 0; k < cells.size(); ++k)
  {
    const std::string& v = cells[k];
    switch (columnOf[k])
    {
      case 0:
        c.Name = v;
        break;
      case 1:
        c.Segmentation = Resolved(v, folder);
        break;
      case 2:
        c.Poses = Resolved(v, folder);
        break;
      case 3:
        c.Tips = Resolved(v, folder);
        break;
      case 4:
        c.Plan = PlanEntries(v, folder, at);
        break;
      case 5:
        c.Scalpel = Resolved(v, folder);
        break;
      default:
        ReadingCell(columnOf[k], v, at, c.Reading);
    }
  }
  if (c.Name.empty() || c.Segmentation.empty())
  {
    throw InputError(at, "a case needs its name and its segmentation");
  }
  if (c.Poses.empty() && (c.Reading.Space || c.Reading.MillimetresPerUnit || c.Reading.SecondsPerUnit ||
                           !c.Reading.ToolName.empty() || !c.Reading.ReferenceName.empty()))
  {
    throw InputError(at, "case '" + Printable(c.Name) + "' says how to read poses but gives none");
  }
  if (!c.Plan.empty() && c.Poses.empty())
  {
    throw InputError(at, "case '" + Printable(c.Name) + "' has a plan but no poses: the margin is measured along a tracked "
      "session (give its poses, or leave the plan out)");
  }
  const std::string problem = CaseNameProblem(c.Name);
  if (!problem.empty())
  {
    throw InputError(at, "case '" + Printable(c.Name) + "': " + problem);
  }
  return c;
}

/// The manifest opened for reading: a regular file (a FIFO would hang the run and a device never
/// end, so it is looked at before it is opened) of at most MaxManifestBytes.
std::ifstream OpenManifest(const std::string& file)
{
  struct stat info{};
  if (::stat(file.c_str(), &info) != 0)
  {
    throw InputError(file, "cannot be read");
  }
  if (!S_ISREG(info.st_mode))
  {
    throw InputError(file, "not a regular file: a manifest is a CSV file");
  }
  if (info.st_size > MaxManifestBytes)
  {
    throw InputError(file, "larger than 4 MiB: not a manifest");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in)
  {
    throw InputError(file, "cannot be read");
  }
  return in;
}
} // namespace

std::vector<CohortCase> ReadCohortManifest(const std::string& file)
{
  std::ifstream in = OpenManifest(file);
  const std::size_t slash = file.find_last_of('/');
  const std::string folder = slash == std::string::npos ? std::string() : file.substr(0, slash);
  std::vector<int> columnOf;
  std::vector<CohortCase> cases;
  std::set<std::string> names;
  int lineNumber = 0;
  for (std::string line; std::getline(in, line);)
  {
    ++lineNumber;
    if (lineNumber == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0)
    {
      line.erase(0, 3); // Excel's "CSV UTF-8" starts with a byte order mark
    }
    const std::string at = file + ": line " + std::to_string(lineNumber);
    if (line.find('\0') != std::string::npos)
    {
      throw InputError(file, "line " + std::to_string(lineNumber) + ": a NUL byte: not a text manifest");
    }
    if (Trim(line).empty() || Trim(line)[0] == '#')
    {
      continue;
    }
    const std::vector<std::string> cells = SplitCsvLine(line, at);
    if (columnOf.empty())
    {
      columnOf = HeaderColumns(cells, at);
      continue;
    }
    CohortCase c = CaseOf(cells, columnOf, folder, at);
    c.Line = lineNumber;
    // Folders named alike but for case are one folder on some file systems (macOS, SMB shares).
    std::string folded = c.Name;
    std::transform(folded.begin(), folded.end(), folded.begin(), [](unsigned char ch) { return std::tolower(ch); });
    if (!names.insert(folded).second)
    {
      throw InputError(at, "case '" + c.Name + "' is given twice (names that differ only in case are one folder on some disks)");
    }
    cases.push_back(std::move(c));
  }
  if (in.bad())
  {
    throw InputError(file, "read failed");
  }
  if (columnOf.empty() || cases.empty())
  {
    throw InputError(file, "no case (a header naming case,segmentation[,...], then a case per line)");
  }
  return cases;
}
} // namespace vp
