// libFuzzer entry point for the part language: bytes in, a part evaluated (see FuzzInput.h).
// Built only with -DCSGRAY_FUZZ=ON and clang; run it with scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    fuzz::evaluateInput(std::string_view(reinterpret_cast<const char*>(data), size));
    return 0;
}
