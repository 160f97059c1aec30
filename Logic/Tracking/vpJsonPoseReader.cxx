#include "vpJsonPoseReader.h"

#include "vpInputError.h"
#include "vpJsonFile.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <stdexcept>

namespace vp
{
namespace
{
/// Poses read ahead of the caller: enough to keep the parser busy, few enough to be nothing.
constexpr std::size_t QueueCapacity = 256;

/// Thrown into the parser when the reader goes away, to stop it.
struct ParserCancelled
{
};

std::vector<double> Numbers(const nlohmann::json& value, std::size_t count, const std::string& what)
{
  if (!value.is_array() || value.size() != count)
  {
    throw std::runtime_error("\"" + what + "\" is not an array of " + std::to_string(count) + " numbers");
  }
  std::vector<double> out;
  for (const auto& v : value)
  {
    if (!v.is_number() || !std::isfinite(v.get<double>()))
    {
      throw std::runtime_error("\"" + what + "\" holds something other than a finite number");
    }
    out.push_back(v.get<double>());
  }
  return out;
}

/// One entry of "poses" as time and values; throws std::runtime_error saying what is wrong.
JsonPoseReader::Item ToItem(const nlohmann::json& entry)
{
  if (!entry.is_object() || !entry.contains("time"))
  {
    throw std::runtime_error("no \"time\"");
  }
  JsonPoseReader::Item item;
  item.Time = Numbers(nlohmann::json::array({ entry["time"] }), 1, "time")[0];
  if (entry.contains("matrix"))
  {
    item.Values = Numbers(entry["matrix"], 16, "matrix");
  }
  else if (entry.contains("position") && entry.contains("quaternion"))
  {
    item.Values = Numbers(entry["position"], 3, "position");
    const auto q = Numbers(entry["quaternion"], 4, "quaternion");
    item.Values.insert(item.Values.end(), q.begin(), q.end());
  }
  else
  {
    throw std::runtime_error("neither \"matrix\" nor \"position\" and \"quaternion\"");
  }
  return item;
}
} // namespace

PoseReading JsonPoseReader::Declarations() const
{
  const std::lock_guard<std::mutex> lock(this->Mutex);
  return this->Declared;
}

PoseReading JsonPoseReader::LateDeclarations() const
{
  const std::lock_guard<std::mutex> lock(this->Mutex);
  return this->Late;
}

void JsonPoseReader::Declare(const std::string& key, const nlohmann::json& value, std::size_t posesBefore)
{
  if (!value.is_string())
  {
    throw InputError(this->FileName, "\"" + key + "\" is not a string");
  }
  const std::lock_guard<std::mutex> lock(this->Mutex);
  ApplyPoseDeclaration(key + ":" + value.get<std::string>(), this->FileName, posesBefore > 0 ? this->Late : this->Declared);
}


JsonPoseReader::JsonPoseReader(const std::string& fileName)
  : FileName(fileName)
{
  auto in = std::make_unique<JsonFileInput>(fileName, "a pose list");
  this->Parser = std::thread(&JsonPoseReader::Parse, this, std::move(in));
}

JsonPoseReader::~JsonPoseReader()
{
  {
    const std::lock_guard<std::mutex> lock(this->Mutex);
    this->Cancelled = true;
  }
  this->Changed.notify_all();
  this->Parser.join();
}

bool JsonPoseReader::Next(Item& item)
{
  std::unique_lock<std::mutex> lock(this->Mutex);
  this->Changed.wait(lock, [this] { return !this->Queue.empty() || this->Finished; });
  if (this->Queue.empty())
  {
    if (this->Error)
    {
      std::rethrow_exception(this->Error);
    }
    return false;
  }
  item = std::move(this->Queue.front());
  this->Queue.pop_front();
  lock.unlock();
  this->Changed.notify_all();
  return true;
}

void JsonPoseReader::Hand(Item item)
{
  std::unique_lock<std::mutex> lock(this->Mutex);
  this->Changed.wait(lock, [this] { return this->Queue.size() < QueueCapacity || this->Cancelled; });
  if (this->Cancelled)
  {
    throw ParserCancelled();
  }
  this->Queue.push_back(std::move(item));
  lock.unlock();
  this->Changed.notify_all();
}

void JsonPoseReader::Parse(std::unique_ptr<JsonFileInput> in)
{
  using Event = nlohmann::json::parse_event_t;
  std::exception_ptr error;
  std::size_t count = 0;
  std::string topKey;
  try
  {
    // Depth 1 holds the document's keys; depth 2, the entries of its "poses" array. Each entry is
    // handed over as it ends and dropped from the document (the callback returns false).
    const nlohmann::json document = nlohmann::json::parse(*in, [&](int depth, Event event, nlohmann::json& parsed) {
      if (event == Event::key && depth == 1)
      {
        // Only "poses" and the declarations are kept: any other member, however long, is read
        // and dropped.
        topKey = parsed.get<std::string>();
        return topKey == "poses" || IsPoseDeclarationKey(topKey);
      }
      if (depth == 1 && event == Event::value && IsPoseDeclarationKey(topKey))
      {
        this->Declare(topKey, parsed, count);
        return false;
      }
      const bool entryEnds = event == Event::object_end || event == Event::array_end || event == Event::value;
      if (depth != 2 || topKey != "poses" || !entryEnds)
      {
        return true;
      }
      ++count;
      try
      {
        this->Hand(ToItem(parsed));
      }
      catch (const std::runtime_error& e)
      {
        throw InputError(this->FileName, "pose " + std::to_string(count) + ": " + e.what());
      }
      return false;
    });
    if (!document.is_object() || !document.contains("poses") || !document.at("poses").is_array() || count == 0)
    {
      throw InputError(this->FileName, "no poses: expected {\"poses\": [{\"time\": ..., \"matrix\": [...]}, ...]}");
    }
  }
  catch (const ParserCancelled&)
  {
  }
  catch (const nlohmann::json::exception& e)
  {
    error = std::make_exception_ptr(InputError(this->FileName, "not valid JSON: " + JsonErrorText(e)));
  }
  catch (...)
  {
    error = std::current_exception();
  }
  {
    const std::lock_guard<std::mutex> lock(this->Mutex);
    this->Error = error;
    this->Finished = true;
  }
  this->Changed.notify_all();
}
} // namespace vp
