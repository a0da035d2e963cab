// A headless OpenGL 4.5 core context through EGL (device platform, then Mesa surfaceless); no window, no X.
#pragma once

#include <memory>
#include <string>

namespace vots::render {

/// Owns an EGL display and a surfaceless OpenGL 4.5 core context, current on the creating thread.
/// Use it from one thread only (the server's render thread). All renderers need it current.
class EglContext {
public:
    /// Tries EGL_EXT_platform_device (each device; a real GPU when there is one), then
    /// EGL_PLATFORM_SURFACELESS_MESA (llvmpipe). On success logs one line to stderr naming the
    /// platform and renderer and returns a current context; on failure returns null and, when
    /// error is given, a one-line reason for every platform tried.
    static std::unique_ptr<EglContext> create(std::string* error = nullptr);
    /// As create(), but throws fit::GraphicsError with the reason.
    static std::unique_ptr<EglContext> createOrThrow();

    ~EglContext();
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    /// Makes the context current on the calling thread (create() already did for its thread).
    void makeCurrent();

    const std::string& platform() const { return mPlatform; } // "device" or "surfaceless"
    const std::string& renderer() const {
        return mRenderer;
    } // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    const std::string& version() const { return mVersion; } // GL_VERSION
    bool isSoftware() const;                                // llvmpipe / softpipe / swrast
    /// Whether a GL_RENDERER string names one of Mesa's CPU rasterisers.
    static bool isSoftwareRenderer(const std::string& renderer);

    struct Handles; // EGL handles, private to EglContext.cpp

private:
    EglContext() = default;
    std::unique_ptr<Handles> mHandles;
    std::string mPlatform;
    std::string mRenderer;
    std::string mVersion;
};

} // namespace vots::render
