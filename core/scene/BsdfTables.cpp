// The GGX albedo tables, computed at build time by ripple_bsdf_tables (BsdfTablesIntegrate.cpp).
#include "core/scene/BsdfTables.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace ripple::core {

namespace {

constexpr float kTables[2 * kBsdfTableSize * kBsdfTableSize] = {
#include "core/scene/bsdf_tables.inc"
};

}  // namespace

const std::vector<float>& bsdfEnergyTables() {
    static const std::vector<float> tables(std::begin(kTables), std::end(kTables));
    return tables;
}

float bsdfEnergyLookup(uint32_t table, float mu, float alpha) {
    const auto& t = bsdfEnergyTables();
    const float n = float(kBsdfTableSize);
    const float x = std::clamp(mu * n - 0.5f, 0.0f, n - 1.0f);
    const float y = std::clamp(std::sqrt(alpha) * (n - 1.0f), 0.0f, n - 1.0f);
    const float ix = std::min(std::floor(x), n - 2.0f), iy = std::min(std::floor(y), n - 2.0f);
    const float fx = x - ix, fy = y - iy;
    const uint32_t base = table * kBsdfTableSize * kBsdfTableSize + uint32_t(iy) * kBsdfTableSize + uint32_t(ix);
    const float v00 = t[base], v10 = t[base + 1], v01 = t[base + kBsdfTableSize], v11 = t[base + kBsdfTableSize + 1];
    return (v00 * (1 - fx) + v10 * fx) * (1 - fy) + (v01 * (1 - fx) + v11 * fx) * fy;
}

}  // namespace ripple::core
