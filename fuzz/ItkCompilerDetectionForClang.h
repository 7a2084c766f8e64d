// Included before every source of the fuzzing build (scripts/run-fuzzers.sh): Debian's
// ITK 5.2 was configured with g++ only, so its itk_compiler_detection.h knows no other
// compiler and stops clang with "Unsupported compiler". Clang speaks GCC's dialect, so
// the detection is run once as for g++ 12 and clang's own macros are restored after it.
#if defined(__cplusplus) && __has_include("itk_compiler_detection.h")
#pragma push_macro("__clang__")
#pragma push_macro("__GNUC__")
#pragma push_macro("__GNUC_MINOR__")
#undef __clang__
#undef __GNUC__
#undef __GNUC_MINOR__
#define __GNUC__ 12
#define __GNUC_MINOR__ 2
#include "itk_compiler_detection.h"
#pragma pop_macro("__GNUC_MINOR__")
#pragma pop_macro("__GNUC__")
#pragma pop_macro("__clang__")
#endif
