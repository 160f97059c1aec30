#ifndef vpJsonPoseReader_h
#define vpJsonPoseReader_h

#include "vpPoseReading.h"

#include <nlohmann/json.hpp>

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace vp
{
class JsonFileInput;

/// A JSON pose list ({"poses": [{"time": t, "matrix": [16]} or {"time": t, "position": [3],
/// "quaternion": [4]}, ...]}) read a pose at a time, so that an hour of recording is never held
/// whole: nlohmann's parser runs on a thread of its own and hands each pose over through a small
/// queue, dropping it from its document once handed over. The values are checked for their
/// shape here; the caller checks the pose itself (rigid, times rising).
class JsonPoseReader
{
public:
  /// One pose as the file gives it: its time and 16 matrix values, or 3 position and 4
  /// quaternion values.
  struct Item
  {
    double Time = 0.0;
    std::vector<double> Values;
  };

  /// Opens the file and starts reading; throws vp::InputError naming the file when it cannot.
  explicit JsonPoseReader(const std::string& fileName);
  /// Stops the parser, wherever it is.
  ~JsonPoseReader();
  /// How the file says its numbers are read: its top-level "space", "units" and "time_units"
  /// (or "pose-space", "pose-units", "time-units") before "poses". Complete once the first pose
  /// has been handed over.
  PoseReading Declarations() const;
  /// The same declared after "poses" began: known when the last pose has been read, too late to
  /// read the poses by; the caller refuses one that contradicts how they were read.
  PoseReading LateDeclarations() const;
  JsonPoseReader(const JsonPoseReader&) = delete;
  JsonPoseReader& operator=(const JsonPoseReader&) = delete;

  /// The next pose; false after the last. Throws vp::InputError naming the file and the pose
  /// ("pose 3: ...") for a pose of the wrong shape, invalid JSON, or a file without poses.
  bool Next(Item& item);

private:
  void Parse(std::unique_ptr<JsonFileInput> in);
  /// Called by the parser's thread for each pose: waits while the queue is full.
  void Hand(Item item);
  /// A top-level declaration (IsPoseDeclarationKey) into Declared; refused after a pose.
  void Declare(const std::string& key, const nlohmann::json& value, std::size_t posesBefore);

  std::string FileName;
  mutable std::mutex Mutex;
  std::condition_variable Changed;
  std::deque<Item> Queue;
  bool Finished = false;  ///< the parser is done: the queue holds what is left
  bool Cancelled = false; ///< the reader is going away: the parser stops
  std::exception_ptr Error;
  PoseReading Declared;
  PoseReading Late;
  std::thread Parser;
};
} // namespace vp

#endif
