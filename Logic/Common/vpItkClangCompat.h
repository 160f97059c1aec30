// Debian 12's ITK 5.2 ships a compiler-detection header generated for GCC alone, which stops any
// other compiler with "#error Unsupported compiler". The sanitizer and fuzzing build uses clang,
// which speaks the same GNU dialect: for the length of that header only, clang presents itself as
// the GCC that built ITK. Included first by the ITK translation units (vpLabelmapFileReader.cxx,
// vpItkTransformFile.cxx) in clang builds; its include guard then makes ITK's own inclusion a
// no-op.
#pragma push_macro("__clang__")
#pragma push_macro("__GNUC__")
#pragma push_macro("__GNUC_MINOR__")
#undef __clang__
#undef __GNUC__
#undef __GNUC_MINOR__
#define __GNUC__ 12
#define __GNUC_MINOR__ 2
#include <itk_compiler_detection.h>
#pragma pop_macro("__GNUC_MINOR__")
#pragma pop_macro("__GNUC__")
#pragma pop_macro("__clang__")
