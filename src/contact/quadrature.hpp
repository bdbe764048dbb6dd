// Gauss-Legendre rules on [-1, 1] for the slave segments' quadrature points
// (slave_points: quadrature): n points integrate polynomials of degree 2n - 1 exactly.
#pragma once

#include <array>

namespace exdyn::contact {

inline constexpr int max_gauss_legendre_points = 6;

struct GaussLegendre {
  int count = 0;
  std::array<double, max_gauss_legendre_points> abscissa{};
  std::array<double, max_gauss_legendre_points> weight{};  // sum 2
};

// The n-point rule, 1 <= n <= max_gauss_legendre_points (abscissae ascending).
constexpr GaussLegendre gauss_legendre(int n) {
  switch (n) {
    case 1:
      return {1, {0.0}, {2.0}};
    case 2:
      return {2, {-0.57735026918962576451, 0.57735026918962576451}, {1.0, 1.0}};
    case 3:
      return {3, {-0.77459666924148337704, 0.0, 0.77459666924148337704}, {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0}};
    case 4:
      return {
          4,
          {-0.86113631159405257522, -0.33998104358485626480, 0.33998104358485626480, 0.86113631159405257522},
          {0.34785484513745385737, 0.65214515486254614263, 0.65214515486254614263, 0.34785484513745385737}};
    case 5:
      return {5,
              {-0.90617984593866399280, -0.53846931010568309104, 0.0, 0.53846931010568309104,
               0.90617984593866399280},
              {0.23692688505618908751, 0.47862867049936646804, 0.56888888888888888889, 0.47862867049936646804,
               0.23692688505618908751}};
    default:
      return {6,
              {-0.93246951420315202781, -0.66120938646626451366, -0.23861918608319690863,
               0.23861918608319690863, 0.66120938646626451366, 0.93246951420315202781},
              {0.17132449237917034504, 0.36076157304813860757, 0.46791393457269104739, 0.46791393457269104739,
               0.36076157304813860757, 0.17132449237917034504}};
  }
}

}  // namespace exdyn::contact
