#include "viewer/cli/dist/Ranks.h"

#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <string>

namespace viewer::dist {

namespace {

bool launchedByMpi() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
        if (std::getenv(name)) return true;
    return false;
}

// Where csgray_mpi.so is: CSGRAY_MPI_MODULE when set, else beside the executable (the build
// tree) or where `cmake --install` puts it relative to bin/ (CSGRAY_MPI_MODULE_FROM_BIN).
std::string modulePath() {
    if (const char* path = std::getenv("CSGRAY_MPI_MODULE")) return path;
    std::error_code error;
    const std::filesystem::path bin =
        std::filesystem::read_symlink("/proc/self/exe", error).parent_path();
    for (const std::filesystem::path& path :
         {bin / "csgray_mpi.so", bin / CSGRAY_MPI_MODULE_FROM_BIN / "csgray_mpi.so"})
        if (std::filesystem::exists(path, error)) return path.lexically_normal().string();
    return (bin / CSGRAY_MPI_MODULE_FROM_BIN / "csgray_mpi.so").lexically_normal().string();
}

const CsgrayMpiCalls* loaded = nullptr;

void finalizeAtExit() {
    loaded->finalize();
}

}  // namespace

Ranks::Ranks() {
    if (!launchedByMpi()) return;
    // RTLD_GLOBAL: Open MPI loads its own components, which look for libmpi's symbols there.
    const std::string path = modulePath();
    void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
    const auto entry =
        module ? reinterpret_cast<CsgrayMpiCallsFunction>(dlsym(module, "csgrayMpiCalls"))
               : nullptr;
    if (!entry) {
        std::fprintf(stderr, "csgray: error: started by an MPI launcher, but cannot load %s: %s\n",
                     path.c_str(), dlerror());
        std::exit(1);
    }
    const CsgrayMpiCalls* calls = entry();
    if (calls->init(&rank_, &size_) != 0) {
        std::fprintf(stderr, "csgray: error: MPI_Init failed\n");
        std::exit(1);
    }
    calls_ = loaded = calls;
    std::atexit(finalizeAtExit);
}

Ranks& Ranks::job() {
    static Ranks ranks;
    return ranks;
}

bool Ranks::allOk(bool ok) const {
    if (!calls_) return ok;
    return calls_->allMin(ok ? 1 : 0) == 1;
}

void Ranks::sumToRoot(unsigned long long* values, int n) const {
    if (calls_ && size_ > 1) calls_->sumToRoot(values, n, root() ? 1 : 0);
}

void Ranks::broadcast(std::string& bytes) const {
    if (!calls_ || size_ == 1) return;
    unsigned long long n = bytes.size();
    calls_->broadcast(&n, sizeof n);
    bytes.resize(n);
    calls_->broadcast(bytes.data(), static_cast<long long>(n));
}

void Ranks::abort(int code) const {
    if (calls_) calls_->abort(code);
    std::exit(code);
}

}  // namespace viewer::dist
