// Directional albedo tables of the GGX lobe that shaders/bsdf.glsl reads to conserve energy: E(mu, alpha)
// with F = 1, and W(mu, alpha) weighted by Schlick's (1 - v.h)^5, so a lobe with Schlick F0 reflects
// F0 (E - W) + W of what arrives from mu. Integrated once, at build time (BsdfTablesIntegrate.cpp).
#pragma once

#include <cstdint>
#include <vector>

namespace ripple::core {

// Entries per axis; must match BSDF_TABLE_SIZE in shaders/bsdf.glsl. mu is sampled at cell centres
// (i + 0.5) / size, roughness (= sqrt(alpha)) at j / (size - 1) with alpha floored as the shader does.
inline constexpr uint32_t kBsdfTableSize = 32;

// Two tables of size^2 floats, E then W, each row one roughness; the words the shader reads.
const std::vector<float>& bsdfEnergyTables();

// Bilinear lookup of table 0 (E) or 1 (W), exactly as the shader does it (for tests).
float bsdfEnergyLookup(uint32_t table, float mu, float alpha);

}  // namespace ripple::core
