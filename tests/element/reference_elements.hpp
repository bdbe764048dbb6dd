// Plain reference implementations of the element kernels, written the textbook
// way (Eigen B matrices, the Jacobian computed at every Gauss point), and test
// element generators. The fast kernels are checked against these.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <random>

#include "element/hex8.hpp"

namespace exdyn::element::testing {

using Matrix6x24 = Eigen::Matrix<double, 6, 24>;
using Vector24 = Eigen::Matrix<double, 24, 1>;
using Matrix24 = Eigen::Matrix<double, 24, 24>;

// Node signs in VTK order, restated here independently of the library.
inline const double node_sign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                       {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

// Isotropic elasticity in Voigt form with engineering shear strains,
// order xx yy zz xy yz xz.
inline Eigen::Matrix<double, 6, 6> elasticity_matrix(double lambda, double mu) {
  Eigen::Matrix<double, 6, 6> c = Eigen::Matrix<double, 6, 6>::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) c(i, j) = lambda;
    c(i, i) = lambda + 2.0 * mu;
    c(i + 3, i + 3) = mu;
  }
  return c;
}

inline Vector24 to_vector(const ElementVectors& v) {
  Vector24 out;
  for (int I = 0; I < 8; ++I) {
    out(3 * I) = v.x[I];
    out(3 * I + 1) = v.y[I];
    out(3 * I + 2) = v.z[I];
  }
  return out;
}

inline ElementVectors from_vector(const Vector24& v) {
  ElementVectors out;
  for (int I = 0; I < 8; ++I) {
    out.x[I] = v(3 * I);
    out.y[I] = v(3 * I + 1);
    out.z[I] = v(3 * I + 2);
  }
  return out;
}

// dN_I/dxi_a, written out.
inline Eigen::Matrix<double, 8, 3> natural_derivatives(double xi, double eta, double zeta) {
  Eigen::Matrix<double, 8, 3> d;
  for (int I = 0; I < 8; ++I) {
    const double* s = node_sign[I];
    d(I, 0) = s[0] * (1 + s[1] * eta) * (1 + s[2] * zeta) / 8;
    d(I, 1) = s[1] * (1 + s[0] * xi) * (1 + s[2] * zeta) / 8;
    d(I, 2) = s[2] * (1 + s[0] * xi) * (1 + s[1] * eta) / 8;
  }
  return d;
}

struct GaussPointKinematics {
  Matrix6x24 b;                       // eps (engineering shear) = B u
  Eigen::Matrix<double, 8, 3> dn_dx;  // dN_I/dx_j
  double det_jacobian = 0.0;
};

inline GaussPointKinematics kinematics(const ElementVectors& x, double xi, double eta, double zeta) {
  const Eigen::Matrix<double, 8, 3> dn = natural_derivatives(xi, eta, zeta);
  Eigen::Matrix<double, 8, 3> coordinates;
  for (int I = 0; I < 8; ++I) coordinates.row(I) << x.x[I], x.y[I], x.z[I];
  const Eigen::Matrix3d jacobian = dn.transpose() * coordinates;  // J_aj = dx_j/dxi_a
  GaussPointKinematics k;
  k.det_jacobian = jacobian.determinant();
  k.dn_dx = dn * jacobian.inverse().transpose();  // dN/dx = J^-1 dN/dxi
  k.b.setZero();
  for (int I = 0; I < 8; ++I) {
    const double nx = k.dn_dx(I, 0), ny = k.dn_dx(I, 1), nz = k.dn_dx(I, 2);
    k.b(0, 3 * I) = nx;
    k.b(1, 3 * I + 1) = ny;
    k.b(2, 3 * I + 2) = nz;
    k.b(3, 3 * I) = ny;
    k.b(3, 3 * I + 1) = nx;
    k.b(4, 3 * I + 1) = nz;
    k.b(4, 3 * I + 2) = ny;
    k.b(5, 3 * I) = nz;
    k.b(5, 3 * I + 2) = nx;
  }
  return k;
}

struct ReferenceResult {
  Vector24 force = Vector24::Zero();
  Eigen::Matrix<double, 6, 1> mean_stress = Eigen::Matrix<double, 6, 1>::Zero();
  double strain_energy = 0.0;
  double hourglass_energy = 0.0;
  Matrix24 stiffness = Matrix24::Zero();
};

// Fully integrated hex8: 8 Gauss points, f = sum B^T sigma w det J.
inline ReferenceResult reference_hex8(const ElementVectors& x, double lambda, double mu,
                                      const ElementVectors& u) {
  const double g = 1.0 / std::sqrt(3.0);
  const Eigen::Matrix<double, 6, 6> c = elasticity_matrix(lambda, mu);
  const Vector24 displacement = to_vector(u);
  ReferenceResult result;
  double volume = 0.0;
  for (int p = 0; p < 8; ++p) {
    const GaussPointKinematics k =
        kinematics(x, g * node_sign[p][0], g * node_sign[p][1], g * node_sign[p][2]);
    const Eigen::Matrix<double, 6, 1> strain = k.b * displacement;
    const Eigen::Matrix<double, 6, 1> stress = c * strain;
    result.force += k.b.transpose() * stress * k.det_jacobian;
    result.stiffness += k.b.transpose() * c * k.b * k.det_jacobian;
    result.mean_stress += stress * k.det_jacobian;
    result.strain_energy += 0.5 * stress.dot(strain) * k.det_jacobian;
    volume += k.det_jacobian;
  }
  result.mean_stress /= volume;
  return result;
}

// One-point hex8 with Flanagan-Belytschko hourglass stiffness, node by node:
// b_I = integral dN_I/dx dV, gamma = h - (h.x) b / V,
// k = coefficient 2 mu b.b / (8 V).
inline ReferenceResult reference_hex8r(const ElementVectors& x, double lambda, double mu, double coefficient,
                                       const ElementVectors& u) {
  const double g = 1.0 / std::sqrt(3.0);
  Eigen::Matrix<double, 8, 3> b = Eigen::Matrix<double, 8, 3>::Zero();
  double volume = 0.0;
  for (int p = 0; p < 8; ++p) {
    const GaussPointKinematics k =
        kinematics(x, g * node_sign[p][0], g * node_sign[p][1], g * node_sign[p][2]);
    b += k.dn_dx * k.det_jacobian;
    volume += k.det_jacobian;
  }
  // Uniform-strain B matrix.
  Matrix6x24 bbar = Matrix6x24::Zero();
  for (int I = 0; I < 8; ++I) {
    const double nx = b(I, 0) / volume, ny = b(I, 1) / volume, nz = b(I, 2) / volume;
    bbar(0, 3 * I) = nx;
    bbar(1, 3 * I + 1) = ny;
    bbar(2, 3 * I + 2) = nz;
    bbar(3, 3 * I) = ny;
    bbar(3, 3 * I + 1) = nx;
    bbar(4, 3 * I + 1) = nz;
    bbar(4, 3 * I + 2) = ny;
    bbar(5, 3 * I) = nz;
    bbar(5, 3 * I + 2) = nx;
  }
  // Hourglass base vectors: eta zeta, zeta xi, xi eta, xi eta zeta at the nodes.
  Eigen::Matrix<double, 4, 8> h;
  for (int I = 0; I < 8; ++I) {
    const double* s = node_sign[I];
    h(0, I) = s[1] * s[2];
    h(1, I) = s[2] * s[0];
    h(2, I) = s[0] * s[1];
    h(3, I) = s[0] * s[1] * s[2];
  }
  Eigen::Matrix<double, 8, 3> coordinates;
  for (int I = 0; I < 8; ++I) coordinates.row(I) << x.x[I], x.y[I], x.z[I];
  const Eigen::Matrix<double, 4, 8> gamma = h - (h * coordinates) * b.transpose() / volume;
  const double k = coefficient * 2.0 * mu * b.squaredNorm() / (8.0 * volume);
  Matrix24 hourglass = Matrix24::Zero();
  for (int alpha = 0; alpha < 4; ++alpha)
    for (int I = 0; I < 8; ++I)
      for (int J = 0; J < 8; ++J)
        for (int i = 0; i < 3; ++i) hourglass(3 * I + i, 3 * J + i) += k * gamma(alpha, I) * gamma(alpha, J);

  const Eigen::Matrix<double, 6, 6> c = elasticity_matrix(lambda, mu);
  const Vector24 displacement = to_vector(u);
  ReferenceResult result;
  const Eigen::Matrix<double, 6, 1> strain = bbar * displacement;
  result.mean_stress = c * strain;
  result.stiffness = bbar.transpose() * c * bbar * volume + hourglass;
  result.force = result.stiffness * displacement;
  result.strain_energy = 0.5 * volume * result.mean_stress.dot(strain);
  result.hourglass_energy = 0.5 * displacement.dot(hourglass * displacement);
  return result;
}

// A cube [0, side]^3 in VTK order.
inline ElementVectors cube(double side) {
  ElementVectors x;
  for (int I = 0; I < 8; ++I) {
    x.x[I] = 0.5 * side * (1 + node_sign[I][0]);
    x.y[I] = 0.5 * side * (1 + node_sign[I][1]);
    x.z[I] = 0.5 * side * (1 + node_sign[I][2]);
  }
  return x;
}

// A random well-shaped but distorted hexahedron of size ~ `size`: a cube with
// each node moved by up to `distortion` * size, then sheared and rotated.
inline ElementVectors random_distorted_hex(std::mt19937_64& rng, double size = 1.0, double distortion = 0.2) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::Matrix3d map = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) map(i, j) += 0.2 * unit(rng);
  const Eigen::Vector3d shift(unit(rng), unit(rng), unit(rng));
  ElementVectors x;
  for (int I = 0; I < 8; ++I) {
    Eigen::Vector3d p(0.5 * size * node_sign[I][0], 0.5 * size * node_sign[I][1],
                      0.5 * size * node_sign[I][2]);
    for (int i = 0; i < 3; ++i) p(i) += distortion * size * unit(rng);
    p = map * p + size * shift;
    x.x[I] = p(0);
    x.y[I] = p(1);
    x.z[I] = p(2);
  }
  return x;
}

// A random parallelepiped: the image of the cube [-size/2, size/2]^3 under a random affine map.
inline ElementVectors random_parallelepiped(std::mt19937_64& rng, double size = 1.0) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::Matrix3d map = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) map(i, j) += 0.3 * unit(rng);
  const Eigen::Vector3d shift(unit(rng), unit(rng), unit(rng));
  ElementVectors x;
  for (int I = 0; I < 8; ++I) {
    Eigen::Vector3d p(0.5 * size * node_sign[I][0], 0.5 * size * node_sign[I][1],
                      0.5 * size * node_sign[I][2]);
    p = map * p + size * shift;
    x.x[I] = p(0);
    x.y[I] = p(1);
    x.z[I] = p(2);
  }
  return x;
}

inline ElementVectors random_vectors(std::mt19937_64& rng, double scale = 1.0e-3) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  ElementVectors u;
  for (int I = 0; I < 8; ++I) {
    u.x[I] = scale * unit(rng);
    u.y[I] = scale * unit(rng);
    u.z[I] = scale * unit(rng);
  }
  return u;
}

// u = A x + d at every node.
inline ElementVectors linear_field(const ElementVectors& x, const Eigen::Matrix3d& a,
                                   const Eigen::Vector3d& d) {
  ElementVectors u;
  for (int I = 0; I < 8; ++I) {
    const Eigen::Vector3d p(x.x[I], x.y[I], x.z[I]);
    const Eigen::Vector3d v = a * p + d;
    u.x[I] = v(0);
    u.y[I] = v(1);
    u.z[I] = v(2);
  }
  return u;
}

}  // namespace exdyn::element::testing
