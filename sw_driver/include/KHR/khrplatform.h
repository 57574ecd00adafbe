/* The Khronos platform types (KHR/khrplatform.h) for the platforms tessera's
 * SDK is built for: GCC or Clang on Linux, with 32- or 64-bit pointers.
 *
 * <GLES/gl.h> includes it, as the Khronos gl.h does, so that code written
 * for the Khronos headers finds these names after including it, and a
 * header that includes it (another Khronos API's, say) takes this copy from
 * the SDK's include folder rather than the system's. The names and their
 * sizes are those Khronos defines for these platforms; the GL and EGL types
 * of tessera's headers are the same types (tests/include checks it). */
#ifndef TESSERA_KHR_KHRPLATFORM_H
#define TESSERA_KHR_KHRPLATFORM_H

#include <stdint.h>

/* Linkage, calling convention and attributes of Khronos API functions. */
#ifndef KHRONOS_APICALL
#if defined(__GNUC__)
#define KHRONOS_APICALL __attribute__((visibility("default")))
#else
#define KHRONOS_APICALL
#endif
#endif
#ifndef KHRONOS_APIENTRY
#define KHRONOS_APIENTRY
#endif
#ifndef KHRONOS_APIATTRIBUTES
#define KHRONOS_APIATTRIBUTES
#endif

/* Both are available on every platform above. */
#define KHRONOS_SUPPORT_INT64 1
#define KHRONOS_SUPPORT_FLOAT 1

/* Exact-width integers. */
typedef int8_t khronos_int8_t;
typedef uint8_t khronos_uint8_t;
typedef int16_t khronos_int16_t;
typedef uint16_t khronos_uint16_t;
typedef int32_t khronos_int32_t;
typedef uint32_t khronos_uint32_t;
typedef int64_t khronos_int64_t;
typedef uint64_t khronos_uint64_t;

/* Pointer-sized integers and sizes: `long` on both ILP32 and LP64. */
typedef signed long int khronos_intptr_t;
typedef unsigned long int khronos_uintptr_t;
typedef signed long int khronos_ssize_t;
typedef unsigned long int khronos_usize_t;

/* IEEE single precision. */
typedef float khronos_float_t;

/* Times in nanoseconds: unsigned for absolute times, signed for
 * differences. */
typedef khronos_uint64_t khronos_utime_nanoseconds_t;
typedef khronos_int64_t khronos_stime_nanoseconds_t;

/* The largest enum value, which keeps enums 32 bits wide. */
#define KHRONOS_MAX_ENUM 0x7FFFFFFF

/* The names are the ones Khronos gives; the house's naming check does not apply. */
/* NOLINTBEGIN(readability-identifier-naming) */
typedef enum {
  KHRONOS_FALSE = 0,
  KHRONOS_TRUE = 1,
  KHRONOS_BOOLEAN_ENUM_FORCE_SIZE = KHRONOS_MAX_ENUM
} khronos_boolean_enum_t;
/* NOLINTEND(readability-identifier-naming) */

#endif
