// SDL2 for `csgray view`, loaded when the window is wanted rather than when csgray starts:
// linking it made every command (render, probe, export, ...) load SDL's dozens of libraries
// (X11, Wayland, PulseAudio, D-Bus, codecs), start-up CPU that only the viewer needs
// (bench/README.md, csgray view).
// SDL's headers still give the types and constants; its functions are called through the
// table, with SDL's own signatures.
#pragma once

#include <SDL.h>

#include <string>

namespace viewer::window {

// What the Debian runtime package installs, and what to tell the user to install.
inline constexpr const char* kSdlLibraryName = "libSDL2-2.0.so.0";
inline constexpr const char* kSdlPackageName = "libsdl2-2.0-0";

// The SDL functions viewer/window calls. A macro that expands to a function call (e.g.
// SDL_LoadBMP, SDL_BlitSurface) needs the function it expands to here too.
struct SdlFunctions {
#define CSGRAY_SDL_FUNCTIONS(X)   \
    X(SDL_CreateRenderer)         \
    X(SDL_CreateTexture)          \
    X(SDL_CreateWindow)           \
    X(SDL_DestroyRenderer)        \
    X(SDL_DestroyTexture)         \
    X(SDL_DestroyWindow)          \
    X(SDL_GetCurrentVideoDriver)  \
    X(SDL_GetError)               \
    X(SDL_GetRenderDrawBlendMode) \
    X(SDL_GetRendererInfo)        \
    X(SDL_GetRendererOutputSize)  \
    X(SDL_Init)                   \
    X(SDL_PollEvent)              \
    X(SDL_PushEvent)              \
    X(SDL_Quit)                   \
    X(SDL_RegisterEvents)         \
    X(SDL_RenderClear)            \
    X(SDL_RenderCopy)             \
    X(SDL_RenderFillRectF)        \
    X(SDL_RenderFillRects)        \
    X(SDL_RenderFillRectsF)       \
    X(SDL_RenderPresent)          \
    X(SDL_SetHint)                \
    X(SDL_SetRenderDrawBlendMode) \
    X(SDL_SetRenderDrawColor)     \
    X(SDL_SetWindowTitle)         \
    X(SDL_UpdateTexture)          \
    X(SDL_WaitEventTimeout)
#define CSGRAY_SDL_MEMBER(name) decltype(&::name) name = nullptr;
    CSGRAY_SDL_FUNCTIONS(CSGRAY_SDL_MEMBER)
#undef CSGRAY_SDL_MEMBER
};

// Opens the shared library `libraryName` and looks up every function of SdlFunctions in it.
// On success fills `out` and returns an empty string (the library stays loaded for the
// process); else returns what failed, naming the library, the missing symbol if any, and
// the Debian package to install. Never throws.
std::string loadSdlFunctions(const char* libraryName, SdlFunctions& out);

// Loads kSdlLibraryName once for the process (thread-safe). Returns an empty string when SDL
// is usable, else the error of loadSdlFunctions. Call it before sdl().
const std::string& loadSdl();

// The process's SDL table; only after loadSdl() returned an empty string.
const SdlFunctions& sdl();

}  // namespace viewer::window
