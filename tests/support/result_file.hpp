// Test helper: reads datasets of a result file (NAME.h5) with the HDF5 C API.
#pragma once

#include <hdf5.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace exdyn::testing {

struct Dataset {
  std::vector<hsize_t> shape;
  std::vector<double> values;  // row-major
};

inline Dataset read_dataset(const std::string& file, const std::string& path) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw std::runtime_error("cannot open " + file);
  const hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
  if (d < 0) {
    H5Fclose(f);
    throw std::runtime_error("no dataset " + path + " in " + file);
  }
  const hid_t space = H5Dget_space(d);
  Dataset result;
  result.shape.resize(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, result.shape.data(), nullptr);
  hsize_t count = 1;
  for (auto s : result.shape) count *= s;
  result.values.resize(count);
  if (count > 0) H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, result.values.data());
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
  return result;
}

// "/steps/000448/stress"
inline std::string step_path(long step, const std::string& field) {
  char name[32];
  std::snprintf(name, sizeof name, "/steps/%06ld/", step);
  return name + field;
}

}  // namespace exdyn::testing
