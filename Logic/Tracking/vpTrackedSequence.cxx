#include "vpTrackedSequence.h"

#include "vpInputError.h"
#include "vpNumericCsv.h"
#include "vpRegularFile.h"
#include "vpText.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>

namespace vp
{
namespace
{
/// One header line as a key and its value: "Key = Value" (MetaImage) or "key:=value" (NRRD);
/// false for a line that is neither (a NRRD field "type: uchar", a comment).
bool SplitField(const std::string& line, bool nrrd, std::string& key, std::string& value)
{
  const std::size_t at = nrrd ? line.find(":=") : line.find('=');
  if (at == std::string::npos)
  {
    return false;
  }
  key = TrimBlanks(line.substr(0, at));
  value = TrimBlanks(line.substr(at + (nrrd ? 2 : 1)));
  return !key.empty();
}

/// A transform's name without its "Transform" ("StylusToTrackerTransform" -> "StylusToTracker").
std::string WithoutTransformSuffix(const std::string& name)
{
  const std::string suffix = "Transform";
  return EndsWith(name, suffix) ? name.substr(0, name.size() - suffix.size()) : name;
}

/// A per-frame field into its frame: "Seq_Frame0012_StylusToTrackerTransform" and its value.
void AddFrameField(const std::string& key, const std::string& value, std::map<long, TrackedSequence::Frame>& frames,
  const std::string& where)
{
  constexpr const char* Prefix = "Seq_Frame";
  std::size_t at = std::char_traits<char>::length(Prefix);
  std::size_t digits = 0;
  while (at + digits < key.size() && std::isdigit(static_cast<unsigned char>(key[at + digits])))
  {
    ++digits;
  }
  if (digits == 0 || digits > 7 || at + digits >= key.size() || key[at + digits] != '_')
  {
    throw InputError(where + "'" + Printable(key) + "' is not Seq_FrameNNNN_<field>");
  }
  TrackedSequence::Frame& frame = frames[std::stol(key.substr(at, digits))];
  const std::string field = key.substr(at + digits + 1);
  if (field == "Timestamp")
  {
    std::vector<double> numbers;
    std::string problem;
    if (!ParseNumbers(value, numbers, problem) || numbers.size() != 1)
    {
      throw InputError(where + "the timestamp '" + Printable(value) + "' is not a number");
    }
    frame.TimeS = numbers[0];
    frame.HasTime = true;
  }
  else if (EndsWith(field, "TransformStatus"))
  {
    if (value != "OK" && value != "INVALID" && value != "MISSING" && value != "OUT_OF_VIEW")
    {
      throw InputError(where + "the status '" + Printable(value) + "' is none of OK, INVALID, MISSING, OUT_OF_VIEW");
    }
    frame.Valid[WithoutTransformSuffix(field.substr(0, field.size() - std::string("Status").size()))] = value == "OK";
  }
  else if (EndsWith(field, "Transform"))
  {
    std::vector<double> numbers;
    std::string problem;
    if (!ParseSeparatedNumbers(value, numbers, problem) || numbers.size() != 16)
    {
      throw InputError(where + field + " is not 16 finite numbers");
    }
    std::array<double, 16> m{};
    std::copy(numbers.begin(), numbers.end(), m.begin());
    frame.Transforms[WithoutTransformSuffix(field)] = m;
  }
}
} // namespace

std::string TrackedSequence::Resolve(const std::string& name, const std::string& source, const std::string& what) const
{
  std::string names;
  for (const std::string& n : this->TransformNames)
  {
    names += (names.empty() ? "" : ", ") + n;
  }
  const std::string wanted = WithoutTransformSuffix(name);
  if (wanted.empty())
  {
    if (!this->DefaultTransform.empty() && std::count(this->TransformNames.begin(), this->TransformNames.end(), this->DefaultTransform))
    {
      return this->DefaultTransform;
    }
    if (this->TransformNames.size() == 1)
    {
      return this->TransformNames.front();
    }
    throw InputError(source, "several transforms (" + names + "): say which is the " + what);
  }
  for (const std::string& candidate : { wanted, wanted + "ToTracker" })
  {
    if (std::count(this->TransformNames.begin(), this->TransformNames.end(), candidate))
    {
      return candidate;
    }
  }
  throw InputError(source, "no transform " + Printable(name) + " for the " + what + " (the sequence has " + names + ")");
}

TrackedSequence ParseTrackedSequence(const std::string& text, const std::string& source, bool complete)
{
  bool ended = false;
  const bool nrrd = text.compare(0, 4, "NRRD") == 0;
  std::map<long, TrackedSequence::Frame> frames;
  TrackedSequence sequence;
  std::size_t lineNumber = 0;
  for (std::size_t start = 0; start < text.size();)
  {
    std::size_t end = text.find('\n', start);
    end = end == std::string::npos ? text.size() : end;
    const std::string line = TrimBlanks(text.substr(start, end - start));
    start = end + 1;
    ++lineNumber;
    if (nrrd && line.empty())
    {
      ended = true; // the NRRD header ends at its first blank line
      break;
    }
    std::string key, value;
    if (!SplitField(line, nrrd, key, value))
    {
      continue;
    }
    if (!nrrd && key == "ElementDataFile")
    {
      ended = true; // the MetaImage header ends here; image data may follow
      break;
    }
    if (key == "DefaultFrameTransformName")
    {
      sequence.DefaultTransform = WithoutTransformSuffix(value);
    }
    else if (key.compare(0, 9, "Seq_Frame") == 0)
    {
      AddFrameField(key, value, frames, source + ": line " + std::to_string(lineNumber) + ": ");
    }
  }
  if (!complete && !ended)
  {
    throw InputError(source, "the header is longer than " + std::to_string(text.size() >> 20) + " MiB: not read");
  }
  std::set<std::string> names;
  for (auto& [index, frame] : frames)
  {
    for (const auto& [name, matrix] : frame.Transforms)
    {
      names.insert(name);
    }
    sequence.Frames.push_back(std::move(frame));
  }
  if (sequence.Frames.empty() || names.empty())
  {
    throw InputError(source, "no tracked frames (no Seq_FrameNNNN_<From>To<To>Transform fields): not a tracked sequence");
  }
  sequence.TransformNames.assign(names.begin(), names.end());
  return sequence;
}

TrackedSequence ReadTrackedSequence(const std::string& fileName)
{
  const std::uint64_t size = RegularFileSize(fileName, "is a folder, not a tracked sequence",
    "is not a regular file (a device, pipe or socket), cannot read it as a tracked sequence");
  std::ifstream in(fileName, std::ios::binary);
  if (!in)
  {
    throw InputError(fileName, "cannot open as a tracked sequence");
  }
  std::string text(static_cast<std::size_t>(std::min<std::uint64_t>(size, MaxSequenceHeaderBytes)), '\0');
  in.read(&text[0], static_cast<std::streamsize>(text.size()));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return ParseTrackedSequence(text, fileName, size <= MaxSequenceHeaderBytes);
}

bool IsSequenceFileName(const std::string& fileName)
{
  const std::string lower = LowerCase(fileName);
  return EndsWith(lower, ".mha") || EndsWith(lower, ".mhd") || EndsWith(lower, ".nrrd") || EndsWith(lower, ".nhdr");
}
} // namespace vp
