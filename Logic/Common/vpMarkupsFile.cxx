#include "vpMarkupsFile.h"

#include "vpDecimal.h"
#include "vpInputError.h"
#include "vpPhysicalLimits.h"
#include "vpRegularFile.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace vp
{
namespace
{
bool EndsWith(std::string text, const std::string& suffix)
{
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// "RAS", "LPS", "0" (RAS) or "1" (LPS), exactly as Slicer takes them: whether it is RAS.
bool IsRas(const std::string& system, const std::string& source, const std::string& where)
{
  if (system == "RAS" || system == "0")
  {
    return true;
  }
  if (system == "LPS" || system == "1")
  {
    return false;
  }
  throw InputError(source, where + "coordinate system '" + system + "' is none of RAS, LPS, 0, 1 (Slicer's spellings)");
}

MarkupsPoint CheckedPoint(std::array<double, 3> p, bool ras, std::string label, const std::string& source, const std::string& where)
{
  CheckCoordinates(p.data(), source, where);
  if (ras)
  {
    p[0] = -p[0];
    p[1] = -p[1];
  }
  return { std::move(label), std::string(), p };
}

std::vector<MarkupsPoint> ParseJson(const std::string& text, const std::string& source)
{
  nlohmann::json doc;
  try
  {
    doc = nlohmann::json::parse(text);
  }
  catch (const nlohmann::json::exception& e)
  {
    throw InputError(source, std::string("not a markups file: not valid JSON (") + e.what() + ")");
  }
  if (!doc.is_object() || !doc.contains("markups") || !doc["markups"].is_array() || doc["markups"].empty() ||
    !doc["markups"][0].is_object())
  {
    throw InputError(source, "not a markups file: no \"markups\" list with a markup in it");
  }
  const nlohmann::json& markup = doc["markups"][0];
  bool ras = false;
  if (markup.contains("coordinateSystem"))
  {
    if (!markup["coordinateSystem"].is_string())
    {
      throw InputError(source, "markups[0].coordinateSystem is not text");
    }
    ras = IsRas(markup["coordinateSystem"].get<std::string>(), source, "markups[0]: ");
  }
  if (!markup.contains("controlPoints") || !markup["controlPoints"].is_array())
  {
    throw InputError(source, "markups[0] has no \"controlPoints\" list");
  }
  std::vector<MarkupsPoint> points;
  const nlohmann::json& list = markup["controlPoints"];
  for (std::size_t i = 0; i < list.size(); ++i)
  {
    const std::string where = "markups[0].controlPoints[" + std::to_string(i) + "]";
    const nlohmann::json& c = list[i];
    if (!c.is_object())
    {
      throw InputError(source, where + " is not an object");
    }
    if (c.contains("positionStatus") && c["positionStatus"] != "defined")
    {
      continue; // placed later, or skipped, in Slicer: not a point
    }
    const auto position = c.find("position");
    if (position == c.end() || !position->is_array() || position->size() != 3 ||
      !std::all_of(position->begin(), position->end(), [](const nlohmann::json& v) { return v.is_number(); }))
    {
      throw InputError(source, where + ": \"position\" is not three numbers");
    }
    const std::array<double, 3> p = { (*position)[0].get<double>(), (*position)[1].get<double>(), (*position)[2].get<double>() };
    const auto label = c.find("label");
    points.push_back(CheckedPoint(p, ras, label != c.end() && label->is_string() ? label->get<std::string>() : std::string(),
      source, where));
  }
  return points;
}

/// One row of a CSV line, with Slicer's quoting ("a, b" and "" for a quote).
std::vector<std::string> CsvFields(const std::string& line)
{
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i)
  {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"')
    {
      fields.back() += '"';
      ++i;
    }
    else if (c == '"')
    {
      quoted = !quoted;
    }
    else if (c == ',' && !quoted)
    {
      fields.emplace_back();
    }
    else
    {
      fields.back() += c;
    }
  }
  return fields;
}


std::vector<MarkupsPoint> ParseFcsv(const std::string& text, const std::string& source)
{
  std::istringstream lines(text);
  bool versioned = false, ras = false, systemStated = false;
  std::vector<MarkupsPoint> points;
  int number = 0;
  for (std::string line; std::getline(lines, line);)
  {
    ++number;
    const std::string where = "line " + std::to_string(number) + ": ";
    if (number == 1 && line.compare(0, 3, "\xEF\xBB\xBF") == 0)
    {
      line.erase(0, 3); // a byte order mark, as editors on Windows write
    }
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    if (line.empty())
    {
      continue;
    }
    if (line[0] == '#')
    {
      const auto eq = line.find('=');
      if (eq == std::string::npos)
      {
        continue;
      }
      auto trim = [](std::string s) {
        s.erase(0, s.find_first_not_of(" \t#"));
        s.erase(s.find_last_not_of(" \t") + 1);
        return s;
      };
      const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
      if (key.rfind("Markups fiducial file version", 0) == 0 && !value.empty())
      {
        versioned = true;
      }
      else if (key == "CoordinateSystem")
      {
        const bool stated = IsRas(value, source, where);
        if (systemStated && stated != ras)
        {
          // Which one the points follow cannot be told: taking either could mirror the tip.
          throw InputError(source, where + "a second CoordinateSystem (" + value + ") that contradicts the first");
        }
        ras = stated;
        systemStated = true;
      }
      continue;
    }
    if (!versioned)
    {
      throw InputError(source, where + "a point before the '# Markups fiducial file version = ...' line (Slicer would read "
                                       "the Slicer 3 layout)");
    }
    const std::vector<std::string> f = CsvFields(line);
    std::array<double, 3> p{};
    if (f.size() < 4 || !ParseDecimal(f[1], p[0]) || !ParseDecimal(f[2], p[1]) || !ParseDecimal(f[3], p[2]))
    {
      throw InputError(source, where + "expected id,x,y,z,..., the position three numbers");
    }
    points.push_back(CheckedPoint(p, ras, f.size() > 11 ? f[11] : std::string(), source, where.substr(0, where.size() - 2)));
  }
  return points;
}
} // namespace

std::vector<MarkupsPoint> ParseMarkupsPoints(const std::string& text, bool fcsv, const std::string& source)
{
  std::vector<MarkupsPoint> points = fcsv ? ParseFcsv(text, source) : ParseJson(text, source);
  if (points.empty())
  {
    throw InputError(source, "holds no defined control point");
  }
  return points;
}

std::vector<MarkupsPoint> ReadMarkupsPoints(const std::string& fileName)
{
  return ParseMarkupsPoints(ReadSmallFile(fileName, "point list", 16u << 20), EndsWith(fileName, ".fcsv"), fileName);
}

std::string MarkupsJsonText(const std::vector<MarkupsPoint>& points)
{
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const MarkupsPoint& p = points[i];
    list.push_back({ { "id", std::to_string(i + 1) }, { "label", p.Label }, { "description", p.Description },
      { "position", p.PositionLps }, { "positionStatus", "defined" } });
  }
  nlohmann::ordered_json doc = {
    { "@schema",
      "https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/Markups/Resources/Schema/"
      "markups-schema-v1.0.3.json#" },
    { "markups", nlohmann::ordered_json::array({ { { "type", "Fiducial" }, { "coordinateSystem", "LPS" },
                   { "coordinateUnits", "mm" }, { "controlPoints", list } } }) }
  };
  return doc.dump(2) + "\n";
}
} // namespace vp
