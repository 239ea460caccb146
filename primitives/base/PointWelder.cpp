#include "primitives/base/PointWelder.h"

#include <algorithm>
#include <bit>

#include "primitives/base/MixBits.h"

namespace csg {
namespace {

constexpr uint32_t kEmpty = UINT32_MAX;

// The coordinates' bits chained through the finalizer: every input bit reaches the low bits
// the table masks (a mesh's coordinates often differ only high up). -0 + 0 = +0, so both
// zeros hash alike.
uint64_t hashOf(const Vec3& p) {
    const auto bits = [&](int i) { return std::bit_cast<uint64_t>(p[i] + 0.0); };
    return mixBits(bits(0) ^ mixBits(bits(1) ^ mixBits(bits(2))));
}

}  // namespace

PointWelder::PointWelder(size_t expectedPoints) {
    // Half full at most: room for a sixth of the expected points at that load.
    grow(std::bit_ceil(std::max<size_t>(64, expectedPoints / 3)));
}

void PointWelder::grow(size_t capacity) {
    table_.assign(capacity, kEmpty);
    mask_ = capacity - 1;
    for (uint32_t v = 0; v < distinct_.size(); ++v) {
        uint64_t slot = hashOf(distinct_[v]) & mask_;
        while (table_[slot] != kEmpty) slot = (slot + 1) & mask_;
        table_[slot] = v;
    }
}

uint32_t PointWelder::add(const Vec3& p) {
    uint64_t slot = hashOf(p) & mask_;
    while (table_[slot] != kEmpty && distinct_[table_[slot]] != p) slot = (slot + 1) & mask_;
    if (table_[slot] != kEmpty) return table_[slot];
    const uint32_t index = static_cast<uint32_t>(distinct_.size());
    table_[slot] = index;
    distinct_.push_back(p);
    if (2 * distinct_.size() > table_.size()) grow(2 * table_.size());
    return index;
}

std::vector<Vec3> PointWelder::take() {
    std::vector<Vec3> out = std::move(distinct_);
    distinct_.clear();
    table_.assign(table_.size(), kEmpty);
    return out;
}

}  // namespace csg
