// The C interface of the vots_webm module (FFmpeg's VP9/WebM encoder), which WebmWriter loads with dlopen.
#pragma once

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/// Raised whenever a function below changes meaning: the loader refuses a module of another build.
#define VOTS_WEBM_ABI_VERSION 1
/// The module's file name; installed in <libdir>/vots (cmake/VotsInstall.cmake).
#define VOTS_WEBM_MODULE_NAME "libvots_webm.so"

#define VOTS_WEBM_EXPORT __attribute__((visibility("default")))

typedef struct VotsWebmEncoder VotsWebmEncoder;

/// VOTS_WEBM_ABI_VERSION as the module was built.
VOTS_WEBM_EXPORT int vots_webm_abi_version(void);

/// The calls below report failure by returning null or nonzero and writing a NUL-terminated message of at
/// most errorSize bytes to error; they never throw. Sides are at least 2 pixels.
VOTS_WEBM_EXPORT VotsWebmEncoder* vots_webm_create(int width, int height, int fps, char* error,
                                                   size_t errorSize);
/// Encodes one width x height RGBA frame, rows `stride` bytes apart.
VOTS_WEBM_EXPORT int vots_webm_add_frame(VotsWebmEncoder* encoder, const uint8_t* rgba, int stride,
                                         char* error, size_t errorSize);
/// Flushes the encoder and points *bytes at the whole file, valid until vots_webm_destroy.
VOTS_WEBM_EXPORT int vots_webm_finish(VotsWebmEncoder* encoder, const uint8_t** bytes, size_t* size,
                                      char* error, size_t errorSize);
/// Frees the encoder; null is allowed.
VOTS_WEBM_EXPORT void vots_webm_destroy(VotsWebmEncoder* encoder);

#ifdef __cplusplus
}
#endif
