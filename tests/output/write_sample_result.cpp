// Writes a synthetic result with the real ResultWriter, for ParaView's
// acceptance check (../shared/tools/paraview/check_xdmf.py):
//
//   output_sample_result DIR NAME [STEPS=5] [NX=10 NY=10 NZ=1]
//
// A box [0,1]x[0,1]x[0,0.1] of NX x NY x NZ hexahedra, all seven fields, each
// component a different analytic function of position and time, so that a
// component or node-order mix-up changes the values ParaView shows.
#include <cmath>
#include <cstdint>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "output/result_writer.hpp"

int main(int argc, char** argv) {
  using namespace exdyn;
  if (argc < 3) {
    std::cerr << "usage: output_sample_result DIR NAME [STEPS=5] [NX=10 NY=10 NZ=1]\n";
    return 2;
  }
  try {
    const std::string directory = argv[1];
    const std::string name = argv[2];
    const long steps = argc > 3 ? std::stol(argv[3]) : 5;
    const std::size_t nx = argc > 4 ? std::stoul(argv[4]) : 10;
    const std::size_t ny = argc > 5 ? std::stoul(argv[5]) : 10;
    const std::size_t nz = argc > 6 ? std::stoul(argv[6]) : 1;

    auto node_id = [&](std::size_t i, std::size_t j, std::size_t k) {
      return static_cast<std::uint32_t>(i + (nx + 1) * (j + (ny + 1) * k));
    };
    const std::size_t node_count = (nx + 1) * (ny + 1) * (nz + 1);
    NodalVectors x_ref(node_count);
    for (std::size_t k = 0; k <= nz; ++k)
      for (std::size_t j = 0; j <= ny; ++j)
        for (std::size_t i = 0; i <= nx; ++i) {
          const std::uint32_t n = node_id(i, j, k);
          x_ref.x[n] = static_cast<double>(i) / static_cast<double>(nx);
          x_ref.y[n] = static_cast<double>(j) / static_cast<double>(ny);
          x_ref.z[n] = 0.1 * static_cast<double>(k) / static_cast<double>(nz);
        }
    std::vector<std::uint32_t> connectivity;
    std::vector<std::int32_t> part;
    for (std::size_t k = 0; k < nz; ++k)
      for (std::size_t j = 0; j < ny; ++j)
        for (std::size_t i = 0; i < nx; ++i) {
          // VTK hexahedron: bottom face counter-clockwise seen from +z, then the top.
          connectivity.insert(connectivity.end(),
                              {node_id(i, j, k), node_id(i + 1, j, k), node_id(i + 1, j + 1, k),
                               node_id(i, j + 1, k), node_id(i, j, k + 1), node_id(i + 1, j, k + 1),
                               node_id(i + 1, j + 1, k + 1), node_id(i, j + 1, k + 1)});
          part.push_back(i < nx / 2 ? 0 : 1);
        }
    const std::size_t element_count = part.size();

    output::ResultWriter writer(directory, name, {&x_ref, &connectivity, &part},
                                {input::all_output_fields.begin(), input::all_output_fields.end()});

    NodalVectors displacement(node_count), velocity(node_count), acceleration(node_count),
        contact_force(node_count);
    std::vector<double> stress(6 * element_count), von_mises(element_count), gap(node_count);
    const double dt = 1.0e-7 / 3.0;  // times with 17 significant digits
    for (long s = 0; s < steps; ++s) {
      const double t = static_cast<double>(s) * dt;
      const double a = std::sin(2.0e6 * t) + 0.1 * (1.0 + static_cast<double>(s));
      for (std::size_t n = 0; n < node_count; ++n) {
        const double x = x_ref.x[n], y = x_ref.y[n], z = x_ref.z[n];
        displacement.x[n] = 1e-3 * a * x * (1 + y);
        displacement.y[n] = 2e-3 * a * y * y;
        displacement.z[n] = 5e-4 * a * z;
        velocity.x[n] = 3.0 * a * x;
        velocity.y[n] = -2.0 * a * y;
        velocity.z[n] = 0.5 * a * (z + x);
        acceleration.x[n] = 1e6 * a * y;
        acceleration.y[n] = 2e6 * a * x;
        acceleration.z[n] = -3e6 * a * (x + y);
        contact_force.x[n] = 0.0;
        contact_force.y[n] = 0.1 * a * x * y;
        contact_force.z[n] = z > 0.0 ? -a * x : 0.0;
        gap[n] = z > 0.0 ? -1e-4 * a * x * y : 0.0;
      }
      for (std::size_t e = 0; e < element_count; ++e) {
        double xc = 0, yc = 0, zc = 0;
        for (int c = 0; c < 8; ++c) {
          const std::uint32_t n = connectivity[8 * e + static_cast<std::size_t>(c)];
          xc += x_ref.x[n] / 8;
          yc += x_ref.y[n] / 8;
          zc += x_ref.z[n] / 8;
        }
        const double sxx = 100 * a * (1 + xc), syy = 50 * a * (1 + yc), szz = 10 * a * (1 + zc);
        const double sxy = 20 * a * xc * yc, syz = 3 * a * yc, sxz = 2 * a * xc;
        double* s6 = &stress[6 * e];  // ParaView's order: xx yy zz xy yz xz
        s6[0] = sxx, s6[1] = syy, s6[2] = szz, s6[3] = sxy, s6[4] = syz, s6[5] = sxz;
        von_mises[e] = std::sqrt(
            0.5 * ((sxx - syy) * (sxx - syy) + (syy - szz) * (syy - szz) + (szz - sxx) * (szz - sxx)) +
            3 * (sxy * sxy + syz * syz + sxz * sxz));
      }
      writer.add_history({t, a, 2 * a, 0.0, 0.0, 0.0, 3 * a});
      output::StepData data;
      data.step = 10 * s;
      data.time = t;
      data.displacement = &displacement;
      data.velocity = &velocity;
      data.acceleration = &acceleration;
      data.contact_force = &contact_force;
      data.stress = stress.data();
      data.von_mises = von_mises.data();
      data.gap = gap.data();
      writer.write_step(data);
    }
    writer.flush();
    // With no step there is no .xmf (ParaView's Xdmf2 reader crashes on an empty collection).
    std::cout << (steps > 0 ? writer.xmf_path() : writer.h5_path() + " (no step, no .xmf)") << "\n";
  } catch (const std::exception& error) {
    std::cerr << "output_sample_result: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
