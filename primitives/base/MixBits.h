// The one 64-bit hash finalizer of the project's open-addressing tables (PointWelder, the mesh
// export's BoxGrid): splitmix64's, so that keys differing in any of their bits land in unrelated
// slots, where a table masks the low bits.
#pragma once

#include <cstdint>

namespace csg {

inline uint64_t mixBits(uint64_t k) {
    k ^= k >> 30;
    k *= 0xbf58476d1ce4e5b9ull;
    k ^= k >> 27;
    k *= 0x94d049bb133111ebull;
    return k ^ (k >> 31);
}

}  // namespace csg
