#ifndef vpInstrumentMethod_h
#define vpInstrumentMethod_h

namespace vp
{
/// How the whole instrument is measured beside the tip.
enum class InstrumentMethod
{
  /// From the z-buffer's own layers when the engine is the z-buffer with its box fixed around the
  /// vessels (within a stated bound), else FCL (exact): what the module does.
  Automatic,
  /// FCL between the instrument's and the vessels' trees, warm-started from the previous frame.
  Fcl,
  /// Our own search over bounding spheres of the instrument's triangles (the reference).
  BoundingSpheres,
};

/// "automatic", "fcl", "bounding spheres": as reports and PrintSelf name them.
inline const char* InstrumentMethodName(InstrumentMethod method)
{
  switch (method)
  {
    case InstrumentMethod::Fcl:
      return "fcl";
    case InstrumentMethod::BoundingSpheres:
      return "bounding spheres";
    default:
      return "automatic";
  }
}
} // namespace vp

#endif
