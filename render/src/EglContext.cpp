// EGL display/context creation: device platform first, then Mesa surfaceless; one stderr log line.
#include "vots/render/EglContext.h"

#include "vots/fit/Error.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <iostream>
#include <vector>

namespace vots::render {

struct EglContext::Handles {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
};

namespace {

std::string eglErrorName(EGLint code) {
    switch (code) {
    case EGL_NOT_INITIALIZED:
        return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
        return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
        return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
        return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
        return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
        return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
        return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
        return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
        return "EGL_BAD_PARAMETER";
    default:
        return "EGL error " + std::to_string(code);
    }
}

bool hasExtension(const char* list, const std::string& name) {
    if (!list) return false;
    const std::string all = std::string(" ") + list + " ";
    return all.find(" " + name + " ") != std::string::npos;
}

// Initialises the display and makes a 4.5 core context current without a surface.
// Returns an empty string on success, else the reason; the display is terminated on failure.
std::string makeContext(EGLDisplay display, EglContext::Handles& out) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) return "eglInitialize: " + eglErrorName(eglGetError());
    auto fail = [&](const std::string& why) {
        eglTerminate(display);
        return why;
    };
    if (!hasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
        return fail("no EGL_KHR_surfaceless_context");
    if (!eglBindAPI(EGL_OPENGL_API)) return fail("eglBindAPI(OpenGL): " + eglErrorName(eglGetError()));
    // No surface is ever made, so any OpenGL config will do. Some drivers list none for SURFACE_TYPE 0
    // but do for pbuffers; with neither, a context without config needs KHR_no_config_context.
    EGLConfig config = nullptr;
    for (const EGLint surfaceType : {EGLint{0}, EGLint{EGL_PBUFFER_BIT}}) {
        const EGLint configAttribs[] = {EGL_SURFACE_TYPE, surfaceType, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                        EGL_NONE};
        EGLint count = 0;
        if (eglChooseConfig(display, configAttribs, &config, 1, &count) && count >= 1) break;
        config = nullptr;
    }
    // 4.6 fails with EGL_BAD_MATCH on Mesa 22 llvmpipe (docs/DESIGN.md §10); 4.5 core is what we need.
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
    if (context == EGL_NO_CONTEXT) return fail("OpenGL 4.5 core context: " + eglErrorName(eglGetError()));
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        eglDestroyContext(display, context);
        return fail("eglMakeCurrent: " + eglErrorName(eglGetError()));
    }
    if (epoxy_gl_version() < 45) {
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context);
        return fail("context is OpenGL " + std::to_string(epoxy_gl_version()) + ", need 4.5");
    }
    out.display = display;
    out.context = context;
    return {};
}

} // namespace

std::unique_ptr<EglContext> EglContext::create(std::string* error) {
    std::string reasons;
    auto note = [&](const std::string& what) { reasons += (reasons.empty() ? "" : "; ") + what; };
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto handles = std::make_unique<Handles>();
    std::string platform;

    // 1. EGL_EXT_platform_device: real GPUs first; Mesa also lists a software device.
    if (hasExtension(clientExtensions, "EGL_EXT_platform_device") &&
        hasExtension(clientExtensions, "EGL_EXT_device_enumeration")) {
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (eglQueryDevicesEXT(16, devices, &count) && count > 0) {
            // Prefer a device that is not Mesa's software device; fall back to it otherwise.
            std::vector<EGLDeviceEXT> order;
            for (EGLint i = 0; i < count; ++i)
                if (!hasExtension(eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS),
                                  "EGL_MESA_device_software"))
                    order.push_back(devices[i]);
            for (EGLint i = 0; i < count; ++i)
                if (hasExtension(eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS),
                                 "EGL_MESA_device_software"))
                    order.push_back(devices[i]);
            for (EGLDeviceEXT device : order) {
                EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
                if (display == EGL_NO_DISPLAY) {
                    note("device display: " + eglErrorName(eglGetError()));
                    continue;
                }
                const std::string why = makeContext(display, *handles);
                if (why.empty()) {
                    platform = "device";
                    break;
                }
                note("device: " + why);
            }
        } else {
            note("device: no EGL devices");
        }
    } else {
        note("device: EGL_EXT_platform_device not offered");
    }

    // 2. Mesa surfaceless (llvmpipe on CPU-only machines). No X server involved.
    if (platform.empty()) {
        if (hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
            EGLDisplay display =
                eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            const std::string why = display == EGL_NO_DISPLAY ? "no display" : makeContext(display, *handles);
            if (why.empty())
                platform = "surfaceless";
            else
                note("surfaceless: " + why);
        } else {
            note("surfaceless: EGL_MESA_platform_surfaceless not offered");
        }
    }

    if (platform.empty()) {
        if (error) *error = "no headless OpenGL 4.5 context (" + reasons + ")";
        return nullptr;
    }
    std::unique_ptr<EglContext> result(new EglContext());
    result->mHandles = std::move(handles);
    result->mPlatform = platform;
    result->mRenderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    result->mVersion = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    std::cerr << "vots: EGL platform " << result->mPlatform << ", renderer " << result->mRenderer
              << ", OpenGL " << result->mVersion;
    // Why the preferred platform was passed over: a GPU reached through another platform works, but
    // whoever set the machine up will want to know.
    if (platform != "device") std::cerr << " (" << reasons << ")";
    std::cerr << '\n';
    return result;
}

std::unique_ptr<EglContext> EglContext::createOrThrow() {
    std::string error;
    auto context = create(&error);
    if (!context) throw fit::GraphicsError(error);
    return context;
}

EglContext::~EglContext() {
    if (!mHandles || mHandles->display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(mHandles->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(mHandles->display, mHandles->context);
    // Not eglTerminate: the surfaceless display is shared process-wide (docs/DESIGN.md §10), and another
    // context made on it later would die with it. EGL reclaims it at process exit.
}

void EglContext::makeCurrent() {
    if (!eglMakeCurrent(mHandles->display, EGL_NO_SURFACE, EGL_NO_SURFACE, mHandles->context))
        throw fit::GraphicsError("eglMakeCurrent: " + eglErrorName(eglGetError()));
}

bool EglContext::isSoftware() const {
    return isSoftwareRenderer(mRenderer);
}

bool EglContext::isSoftwareRenderer(const std::string& renderer) {
    return renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos ||
           renderer.find("swrast") != std::string::npos;
}

} // namespace vots::render
