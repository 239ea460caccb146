// libFuzzer entry point for the file readers of compare and import(): bytes in, parsed as OBJ,
// STL, OFF, 3MF, GLB, glTF, and as DXF and SVG drawings (see FuzzMeshInput.h). Built only with
// -DCSGRAY_FUZZ=ON and clang; run it with scripts/fuzz.sh SECONDS mesh.
#include <cstddef>
#include <cstdint>

#include "tests/fuzz/FuzzMeshInput.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    fuzz::readMeshInput(std::string_view(reinterpret_cast<const char*>(data), size));
    return 0;
}
