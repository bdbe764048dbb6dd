#include "element/hex20_matrix.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "element/hex20.hpp"

namespace exdyn::element::hex20_setup {

// flatten: the kernel and Eigen inlined here, compiled with this file's options.
[[gnu::flatten]] void element_matrix(int gauss_points, const double* table, const double* reference,
                                     double lambda, double mu, double* matrix) {
  for (int c = 0; c < dofs; ++c) {
    hex20::ElementVectors20 unit, f{hex20::ElementVectors20::Uninitialized{}};
    (c < 20 ? unit.x[c] : c < 40 ? unit.y[c - 20] : unit.z[c - 40]) = 1.0;
    material::SymTensor s;
    hex20::internal_forces(gauss_points, table, reference, lambda, mu, unit, f, s);
    for (int k = 0; k < 20; ++k) {
      matrix[dofs * k + c] = f.x[k];
      matrix[dofs * (20 + k) + c] = f.y[k];
      matrix[dofs * (40 + k) + c] = f.z[k];
    }
    for (int k = 0; k < 6; ++k) matrix[dofs * (60 + k) + c] = s[k];
  }
}

[[gnu::flatten]] double element_step(const double* matrix, const std::array<double, 20>& masses) {
  Eigen::Matrix<double, dofs, dofs> a;
  for (int r = 0; r < dofs; ++r)
    for (int c = 0; c < dofs; ++c)
      a(r, c) = matrix[dofs * r + c] / std::sqrt(masses[std::size_t(r % 20)] * masses[std::size_t(c % 20)]);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, dofs, dofs>> solver(a, Eigen::EigenvaluesOnly);
  return 2.0 / std::sqrt(solver.eigenvalues().maxCoeff());
}

}  // namespace exdyn::element::hex20_setup
