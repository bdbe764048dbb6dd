// The 20-node brick's setup kernels (hex20_family.cpp): its element matrix [K; S] and
// its critical step. In their own file so that the sanitizer build can compile them
// optimised and uninstrumented (src/element/CMakeLists.txt): the dense eigenvalues and
// the 60 unit-displacement passes are most of a 20-node model's setup, and the release
// build's tests run them in full.
#pragma once

#include <array>

namespace exdyn::element::hex20_setup {

inline constexpr int dofs = 60;         // 20 nodes x 3: x of the 20 nodes, then y, then z
inline constexpr int matrix_rows = 66;  // K (60 rows) then S (6 rows: mean xx yy zz xy yz xz)
inline constexpr int matrix_size = matrix_rows * dofs;

// [K; S] (matrix_rows x dofs, row-major) of one element from its general reference data
// (hex20::make_reference) and the table of dN/dxi: column c is the force and the mean
// stress of the unit displacement of degree of freedom c.
void element_matrix(int gauss_points, const double* table, const double* reference, double lambda, double mu,
                    double* matrix);

// 2 / omega_max of one element (s): omega_max^2 the largest eigenvalue of M^-1 K, from the
// symmetric M^-1/2 K M^-1/2, M the element's HRZ masses.
double element_step(const double* matrix, const std::array<double, 20>& masses);

}  // namespace exdyn::element::hex20_setup
