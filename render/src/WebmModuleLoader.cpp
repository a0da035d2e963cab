// Loads libvots_webm.so with dlopen: installed beside the executable's bin/, or from the build tree.
#include "WebmModuleLoader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace vots::render {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> candidatePaths() {
    if (const char* chosen = std::getenv("VOTS_WEBM_MODULE"); chosen && *chosen) return {chosen};
    std::vector<std::string> paths;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec)
        paths.push_back(
            (exe.parent_path() / VOTS_WEBM_DIR_FROM_BIN / VOTS_WEBM_MODULE_NAME).lexically_normal());
    // Test and bench programs of the build tree live elsewhere than cli/vots: they take the module
    // where the build put it. An installed vots finds its own copy first.
    paths.push_back(VOTS_WEBM_BUILD_PATH);
    return paths;
}

template <typename Function> Function symbol(void* library, const char* name, const std::string& path) {
    void* address = dlsym(library, name);
    if (!address) throw std::runtime_error(path + ": lacks " + name);
    return reinterpret_cast<Function>(address);
}

/// The module at `path`, or a throw saying why not (dlopen's words, another build's module, ...).
WebmModule open(const std::string& path) {
    // Never closed once taken: FFmpeg and libvpx keep state for the process, and sanitizers' reports
    // at exit need the module's symbols.
    void* library = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library) {
        const char* why = dlerror();
        throw std::runtime_error(why ? why : path + ": cannot be loaded");
    }
    try {
        const int version =
            symbol<decltype(&vots_webm_abi_version)>(library, "vots_webm_abi_version", path)();
        if (version != VOTS_WEBM_ABI_VERSION)
            throw std::runtime_error(path + ": of another Vots build (interface " + std::to_string(version) +
                                     ", this one needs " + std::to_string(VOTS_WEBM_ABI_VERSION) + ")");
        WebmModule m;
        m.create = symbol<decltype(m.create)>(library, "vots_webm_create", path);
        m.addFrame = symbol<decltype(m.addFrame)>(library, "vots_webm_add_frame", path);
        m.finish = symbol<decltype(m.finish)>(library, "vots_webm_finish", path);
        m.destroy = symbol<decltype(m.destroy)>(library, "vots_webm_destroy", path);
        return m;
    } catch (...) {
        dlclose(library);
        throw;
    }
}

WebmModule load() {
    std::string tried;
    for (const std::string& path : candidatePaths()) {
        try {
            return open(path);
        } catch (const std::runtime_error& e) {
            tried += (tried.empty() ? "" : "; ") + std::string(e.what());
        }
    }
    throw std::runtime_error("WebM encoding needs the module " VOTS_WEBM_MODULE_NAME
                             " (FFmpeg's encoder), which did not load: " +
                             tried);
}

} // namespace

const WebmModule& webmModule() {
    static const WebmModule module = load(); // a throw leaves it unset: the next writer tries again
    return module;
}

} // namespace vots::render
