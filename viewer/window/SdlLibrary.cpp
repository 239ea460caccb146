#include "viewer/window/SdlLibrary.h"

#include <dlfcn.h>

namespace viewer::window {

namespace {

SdlFunctions& processTable() {
    static SdlFunctions table;
    return table;
}

std::string installHint() {
    return std::string("; `csgray view` needs SDL2 (Debian package ") + kSdlPackageName + ")";
}

}  // namespace

std::string loadSdlFunctions(const char* libraryName, SdlFunctions& out) {
    // RTLD_LOCAL: nothing else in csgray should resolve to SDL's symbols by accident.
    void* handle = dlopen(libraryName, RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* why = dlerror();
        return std::string("cannot load ") + libraryName + " (" + (why ? why : "unknown error") +
               ")" + installHint();
    }
    SdlFunctions table;
    std::string missing;
#define CSGRAY_SDL_LOOKUP(name)                                                \
    table.name = reinterpret_cast<decltype(table.name)>(dlsym(handle, #name)); \
    if (!table.name && missing.empty()) missing = #name;
    CSGRAY_SDL_FUNCTIONS(CSGRAY_SDL_LOOKUP)
#undef CSGRAY_SDL_LOOKUP
    if (!missing.empty()) {
        dlclose(handle);
        return std::string("cannot use ") + libraryName + ": it has no " + missing +
               " (SDL 2.0.10 or newer is needed)" + installHint();
    }
    out = table;
    return {};
}

const std::string& loadSdl() {
    static const std::string error = loadSdlFunctions(kSdlLibraryName, processTable());
    return error;
}

const SdlFunctions& sdl() {
    return processTable();
}

}  // namespace viewer::window
