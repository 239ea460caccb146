#include "csg/mesh/BoxGrid.h"

#include <algorithm>
#include <cmath>

#include "primitives/base/MixBits.h"

namespace csg {

namespace {

// Cell coordinates are kept within 21 bits each (three fit a 64-bit key), centred on origin.
constexpr int32_t kCoordLimit = (1 << 20) - 1;

int32_t cellCoord(double x) {
    if (!(x > -double(kCoordLimit))) return -kCoordLimit;  // NaN too
    if (!(x < double(kCoordLimit))) return kCoordLimit;
    return int32_t(std::floor(x));
}

}  // namespace

BoxGrid::BoxGrid(const Vec3& origin, double cell)
    : origin_(origin), inverseCell_(1.0 / cell), slots_(64, Slot{0, kEmpty}) {}

BoxGrid::Entry BoxGrid::entry(uint32_t id, const Bounds3& box) {
    Entry e;
    for (int a = 0; a < 3; ++a) {
        // One float step outward from the nearest float contains the double.
        e.lo[a] = std::nextafter(float(box.lo[a]), -INFINITY);
        e.hi[a] = std::nextafter(float(box.hi[a]), INFINITY);
    }
    e.id = id;
    return e;
}

BoxGrid::Range BoxGrid::range(const Bounds3& box) const {
    Range r;
    for (int a = 0; a < 3; ++a) {
        r.lo[a] = cellCoord((box.lo[a] - origin_[a]) * inverseCell_);
        r.hi[a] = cellCoord((box.hi[a] - origin_[a]) * inverseCell_);
    }
    return r;
}

uint64_t BoxGrid::key(int32_t x, int32_t y, int32_t z) {
    constexpr uint64_t kMask = (uint64_t(1) << 21) - 1;
    return (uint64_t(x + kCoordLimit) & kMask) | ((uint64_t(y + kCoordLimit) & kMask) << 21) |
           ((uint64_t(z + kCoordLimit) & kMask) << 42);
}

uint32_t BoxGrid::find(uint64_t key) const {
    const size_t mask = slots_.size() - 1;
    for (size_t i = mixBits(key) & mask;; i = (i + 1) & mask) {
        const Slot& s = slots_[i];
        if (s.list == kEmpty) return kEmpty;
        if (s.key == key) return uint32_t(i);
    }
}

std::vector<BoxGrid::Entry>& BoxGrid::listOf(uint64_t key) {
    // At most half full, so probes stay short and an empty slot always ends them.
    if (2 * (lists_.size() + 1) > slots_.size()) grow();
    const size_t mask = slots_.size() - 1;
    size_t i = mixBits(key) & mask;
    for (; slots_[i].list != kEmpty; i = (i + 1) & mask)
        if (slots_[i].key == key) return lists_[slots_[i].list];
    slots_[i] = {key, uint32_t(lists_.size())};
    return lists_.emplace_back();
}

void BoxGrid::grow() {
    std::vector<Slot> old(slots_.size() * 2, Slot{0, kEmpty});
    old.swap(slots_);
    const size_t mask = slots_.size() - 1;
    for (const Slot& s : old) {
        if (s.list == kEmpty) continue;
        size_t i = mixBits(s.key) & mask;
        while (slots_[i].list != kEmpty) i = (i + 1) & mask;
        slots_[i] = s;
    }
}

void BoxGrid::insert(uint32_t id, const Bounds3& box) {
    const Entry e = entry(id, box);
    forEachCellKey(box, [&](uint64_t cell) { listOf(cell).push_back(e); });
}

void BoxGrid::remove(uint32_t id, const Bounds3& box) {
    forEachCellKey(box, [&](uint64_t cell) {
        const uint32_t slot = find(cell);
        if (slot == kEmpty) return;
        std::vector<Entry>& list = lists_[slots_[slot].list];
        const auto it =
            std::find_if(list.begin(), list.end(), [id](const Entry& e) { return e.id == id; });
        if (it == list.end()) return;
        *it = list.back();  // order within a cell does not matter
        list.pop_back();
    });
}

}  // namespace csg
