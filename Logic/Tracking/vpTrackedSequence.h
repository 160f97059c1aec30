#ifndef vpTrackedSequence_h
#define vpTrackedSequence_h

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace vp
{
/// A tracked sequence as PLUS (and Slicer's IGT modules after it) records one: the header of a
/// MetaImage (`.igs.mha`, `.mha`: "Key = Value" lines up to ElementDataFile) or of a NRRD
/// (`.igs.nrrd`, `.seq.nrrd`: "key:=value" lines up to the first blank line) whose per-frame
/// fields are `Seq_FrameNNNN_<From>To<To>Transform` (16 numbers, row-major, mm),
/// `Seq_FrameNNNN_<From>To<To>TransformStatus` (`OK`; `INVALID` or `MISSING` when the tool was not
/// seen) and `Seq_FrameNNNN_Timestamp` (s). Any image data after the header is not read.
struct TrackedSequence
{
  struct Frame
  {
    double TimeS = 0.0;
    bool HasTime = false;
    std::map<std::string, std::array<double, 16>> Transforms; ///< by name, "StylusToTracker"
    std::map<std::string, bool> Valid;                         ///< by name: its status is OK
  };
  std::vector<Frame> Frames;
  /// Every transform name of the frames ("StylusToTracker", without "Transform"), sorted.
  std::vector<std::string> TransformNames;
  /// The header's DefaultFrameTransformName, without "Transform"; empty when there is none.
  std::string DefaultTransform;

  /// The transform a user's name means: the name itself ("StylusToTracker", with or without
  /// "Transform"), or NAME for NAMEToTracker ("Stylus"); with no name, the default transform, or the
  /// only one. Throws InputError(source, ...) naming the transforms there are.
  std::string Resolve(const std::string& name, const std::string& source, const std::string& what) const;
};

/// The largest header read (64 MiB: an hour at 60 Hz of five fields a frame).
constexpr std::size_t MaxSequenceHeaderBytes = std::size_t(64) << 20;

/// Parses a sequence header (text: the file's bytes, whole when complete, else its first
/// MaxSequenceHeaderBytes); source names it in messages. Throws InputError(source, ...) naming the
/// line for a field it cannot read (a transform without 16 finite numbers, a frame number that is
/// not one, a status other than OK, INVALID, MISSING or OUT_OF_VIEW), for a header longer than
/// the text it was given, and for a file with no frames.
TrackedSequence ParseTrackedSequence(const std::string& text, const std::string& source, bool complete = true);

/// Reads and parses a sequence file; refuses what is not a regular file or holds no sequence.
TrackedSequence ReadTrackedSequence(const std::string& fileName);

/// Whether a file name is a sequence's (.mha, .mhd, .nrrd, .nhdr, any case).
bool IsSequenceFileName(const std::string& fileName);
} // namespace vp

#endif
