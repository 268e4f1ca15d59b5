#pragma once
// The directional albedo of GGX with F = 1 (ggx_albedo.glsl.h), as the table the shaders
// read and its C++ reader. The table is computed once, deterministically, by quadrature.
#include <array>

namespace specula {

inline constexpr int kGgxAlbedoTableSize = 32;

// Row-major: entry [j * size + i] is E at n.v = i / (size - 1), roughness j / (size - 1).
const std::array<float, kGgxAlbedoTableSize * kGgxAlbedoTableSize>& ggxAlbedoTable();

// E(n.v, perceptual roughness) by quadrature (alpha = roughness^2; Smith height-correlated
// G2): what each table entry holds; `n` samples a side of the grid. Within 6e-4 of a
// converged quadrature at n = 128 (tests/raytrace/ggx_albedo_test.cpp); the whole table
// takes ~0.1 s on first use.
double ggxAlbedoQuadrature(double nv, double roughness, int n = 128);

// The table read bilinearly: the C++ twin of the shaders' ggxAlbedo.
float ggxAlbedo(float nv, float roughness);

} // namespace specula
