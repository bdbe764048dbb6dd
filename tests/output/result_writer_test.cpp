// ResultWriter: what lands in NAME.h5 and NAME.xmf, read back with the HDF5 C
// API and a scan of the XML (../shared/spec/output.md).
#include "output/result_writer.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace exdyn::output {
namespace {

namespace fs = std::filesystem;
using input::OutputField;

// ---------------------------------------------------------------------------
// Reading back

struct DatasetInfo {
  std::vector<hsize_t> shape;
  H5T_class_t type_class = H5T_NO_CLASS;
  std::size_t type_size = 0;
  H5T_sign_t sign = H5T_SGN_ERROR;
};

class H5Reader {
 public:
  explicit H5Reader(const fs::path& path) : file_(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)) {
    if (file_ < 0) throw std::runtime_error("cannot open " + path.string());
  }
  ~H5Reader() { H5Fclose(file_); }
  H5Reader(const H5Reader&) = delete;
  H5Reader& operator=(const H5Reader&) = delete;

  bool exists(const std::string& path) const { return H5Lexists(file_, path.c_str(), H5P_DEFAULT) > 0; }

  DatasetInfo info(const std::string& path) const {
    const hid_t dataset = open(path);
    DatasetInfo result;
    const hid_t space = H5Dget_space(dataset);
    result.shape.resize(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
    H5Sget_simple_extent_dims(space, result.shape.data(), nullptr);
    H5Sclose(space);
    const hid_t type = H5Dget_type(dataset);
    result.type_class = H5Tget_class(type);
    result.type_size = H5Tget_size(type);
    if (result.type_class == H5T_INTEGER) result.sign = H5Tget_sign(type);
    H5Tclose(type);
    H5Dclose(dataset);
    return result;
  }

  template <typename T>
  std::vector<T> read(const std::string& path, hid_t memory_type) const {
    const DatasetInfo shape = info(path);
    std::size_t count = 1;
    for (hsize_t d : shape.shape) count *= d;
    std::vector<T> values(count);
    const hid_t dataset = open(path);
    const herr_t status = H5Dread(dataset, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Dclose(dataset);
    if (status < 0) throw std::runtime_error("cannot read " + path);
    return values;
  }
  std::vector<double> doubles(const std::string& path) const { return read<double>(path, H5T_NATIVE_DOUBLE); }

  template <typename T>
  T attribute(const std::string& object, const char* name, hid_t memory_type,
              H5T_class_t* type_class = nullptr, std::size_t* type_size = nullptr) const {
    const hid_t attribute = H5Aopen_by_name(file_, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
    if (attribute < 0) throw std::runtime_error("no attribute " + object + "@" + name);
    const hid_t type = H5Aget_type(attribute);
    if (type_class != nullptr) *type_class = H5Tget_class(type);
    if (type_size != nullptr) *type_size = H5Tget_size(type);
    H5Tclose(type);
    T value{};
    H5Aread(attribute, memory_type, &value);
    H5Aclose(attribute);
    return value;
  }

  std::vector<std::string> members(const std::string& group) const {
    std::vector<std::string> names;
    auto collect = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
      static_cast<std::vector<std::string>*>(data)->emplace_back(name);
      return 0;
    };
    H5Literate_by_name(file_, group.c_str(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect, &names,
                       H5P_DEFAULT);
    return names;
  }

 private:
  hid_t open(const std::string& path) const {
    const hid_t dataset = H5Dopen2(file_, path.c_str(), H5P_DEFAULT);
    if (dataset < 0) throw std::runtime_error("no dataset " + path);
    return dataset;
  }
  hid_t file_;
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string g17(double value) {
  std::array<char, 40> text{};
  std::snprintf(text.data(), text.size(), "%.17g", value);
  return text.data();
}

int open_hdf5_files() { return static_cast<int>(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_FILE)); }

// ---------------------------------------------------------------------------
// A 2 x 1 x 1 block of hexahedra: 12 nodes, 2 elements, two parts.

struct TinyMesh {
  NodalVectors x_ref{12};
  std::vector<std::uint32_t> connectivity;
  std::vector<std::int32_t> part{0, 1};

  TinyMesh() {
    auto id = [](std::uint32_t i, std::uint32_t j, std::uint32_t k) { return i + 3 * (j + 2 * k); };
    for (std::uint32_t k = 0; k < 2; ++k)
      for (std::uint32_t j = 0; j < 2; ++j)
        for (std::uint32_t i = 0; i < 3; ++i) {
          x_ref.x[id(i, j, k)] = 1.0 * i;
          x_ref.y[id(i, j, k)] = 0.5 * j;
          x_ref.z[id(i, j, k)] = 0.25 * k;
        }
    for (std::uint32_t i = 0; i < 2; ++i) {
      connectivity.insert(connectivity.end(), {id(i, 0, 0), id(i + 1, 0, 0), id(i + 1, 1, 0), id(i, 1, 0),
                                               id(i, 0, 1), id(i + 1, 0, 1), id(i + 1, 1, 1), id(i, 1, 1)});
    }
  }
  MeshView view() const { return {&x_ref, &connectivity, &part}; }
  std::size_t nodes() const { return x_ref.size(); }
  std::size_t elements() const { return part.size(); }
};

// Field values that differ for every step, entity, component and field, so
// a mix-up of any two shows: value = 1000 step + 10 entity + component + offset.
double value(long step, std::size_t entity, int component, double offset) {
  return 1000.0 * static_cast<double>(step) + 10.0 * static_cast<double>(entity) + component + offset;
}

struct StepFields {
  NodalVectors displacement, velocity, acceleration, contact_force;
  std::vector<double> stress, von_mises, gap;

  StepFields(const TinyMesh& mesh, long step)
      : displacement(mesh.nodes()),
        velocity(mesh.nodes()),
        acceleration(mesh.nodes()),
        contact_force(mesh.nodes()),
        stress(6 * mesh.elements()),
        von_mises(mesh.elements()),
        gap(mesh.nodes()) {
    for (std::size_t n = 0; n < mesh.nodes(); ++n) {
      for (int c = 0; c < 3; ++c) {
        displacement.component(c)[n] = value(step, n, c, 0.1);
        velocity.component(c)[n] = value(step, n, c, 0.2);
        acceleration.component(c)[n] = value(step, n, c, 0.3);
        contact_force.component(c)[n] = value(step, n, c, 0.4);
      }
      gap[n] = -value(step, n, 0, 0.5);
    }
    for (std::size_t e = 0; e < mesh.elements(); ++e) {
      for (int c = 0; c < 6; ++c) stress[6 * e + static_cast<std::size_t>(c)] = value(step, e, c, 0.6);
      von_mises[e] = value(step, e, 0, 0.7);
    }
  }

  StepData data(long step, double time) const {
    StepData d;
    d.step = step;
    d.time = time;
    d.displacement = &displacement;
    d.velocity = &velocity;
    d.acceleration = &acceleration;
    d.contact_force = &contact_force;
    d.stress = stress.data();
    d.von_mises = von_mises.data();
    d.gap = gap.data();
    return d;
  }
};

const std::vector<OutputField> all_fields{input::all_output_fields.begin(), input::all_output_fields.end()};
const std::array<long, 3> step_numbers{0, 5, 10};
const std::array<double, 3> step_times{0.0, 1.0e-7 / 3.0, 2.0e-7 / 3.0};  // need all 17 digits

class ResultWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ =
        fs::temp_directory_path() / ("exdyn_output_" + std::to_string(::getpid()) + "_" +
                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
  }
  void TearDown() override {
    if (!HasFailure()) fs::remove_all(directory_);
  }
  fs::path h5() const { return directory_ / "run.h5"; }
  fs::path xmf() const { return directory_ / "run.xmf"; }

  fs::path directory_;
  TinyMesh mesh_;
};

// ---------------------------------------------------------------------------

TEST_F(ResultWriterTest, MeshIsWrittenOnceWithContractShapesAndTypes) {
  ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields);
  EXPECT_EQ(writer.h5_path(), h5().string());
  EXPECT_EQ(writer.xmf_path(), xmf().string());
  EXPECT_EQ(open_hdf5_files(), 0) << "the constructor must close the file";

  H5Reader file(h5());
  const DatasetInfo coordinates = file.info("/mesh/coordinates");
  EXPECT_EQ(coordinates.shape, (std::vector<hsize_t>{12, 3}));
  EXPECT_EQ(coordinates.type_class, H5T_FLOAT);
  EXPECT_EQ(coordinates.type_size, 8u);
  const std::vector<double> xyz = file.doubles("/mesh/coordinates");
  for (std::size_t n = 0; n < 12; ++n) {
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(xyz[3 * n + static_cast<std::size_t>(c)], mesh_.x_ref.component(c)[n]);
  }

  const DatasetInfo connectivity = file.info("/mesh/connectivity");
  EXPECT_EQ(connectivity.shape, (std::vector<hsize_t>{2, 8}));
  EXPECT_EQ(connectivity.type_class, H5T_INTEGER);
  EXPECT_EQ(connectivity.type_size, 8u);
  EXPECT_EQ(connectivity.sign, H5T_SGN_2);
  const std::vector<std::int64_t> nodes = file.read<std::int64_t>("/mesh/connectivity", H5T_NATIVE_INT64);
  ASSERT_EQ(nodes.size(), mesh_.connectivity.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) EXPECT_EQ(nodes[i], mesh_.connectivity[i]);

  const DatasetInfo part = file.info("/mesh/part");
  EXPECT_EQ(part.shape, (std::vector<hsize_t>{2}));
  EXPECT_EQ(part.type_class, H5T_INTEGER);
  EXPECT_EQ(part.type_size, 4u);
  EXPECT_EQ(part.sign, H5T_SGN_2);
  EXPECT_EQ(file.read<std::int32_t>("/mesh/part", H5T_NATIVE_INT32), mesh_.part);

  EXPECT_EQ(file.info("/time").shape, (std::vector<hsize_t>{0}));
  EXPECT_TRUE(file.members("/steps").empty());
  // the seven energies, plastic_work, friction_work, eroded_energy and eroded_mass
  EXPECT_EQ(file.members("/history").size(), 11u);
}

TEST_F(ResultWriterTest, NoXdmfBeforeTheFirstStepAndAStaleOneIsRemoved) {
  // A .xmf of an earlier run would name steps of the .h5 now truncated.
  fs::create_directories(directory_);
  std::ofstream(xmf()) << "stale";
  std::ofstream(directory_ / "run.xmf.tmp") << "stale";
  ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields);
  EXPECT_FALSE(fs::exists(xmf()));
  EXPECT_FALSE(fs::exists(directory_ / "run.xmf.tmp"));
  EXPECT_TRUE(fs::exists(h5()));
}

TEST_F(ResultWriterTest, StepsHoldEveryRequestedFieldInContractLayout) {
  ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields);
  for (std::size_t s = 0; s < 3; ++s) {
    const StepFields fields(mesh_, step_numbers[s]);
    writer.write_step(fields.data(step_numbers[s], step_times[s]));
    EXPECT_EQ(open_hdf5_files(), 0) << "the file must be closed after each step (HDF5 file lock)";
  }

  H5Reader file(h5());
  EXPECT_EQ(file.members("/steps"), (std::vector<std::string>{"000000", "000005", "000010"}));
  EXPECT_EQ(file.info("/time").shape, (std::vector<hsize_t>{3}));
  EXPECT_EQ(file.doubles("/time"), (std::vector<double>(step_times.begin(), step_times.end())));

  for (std::size_t s = 0; s < 3; ++s) {
    const long step = step_numbers[s];
    char group_name[16];
    std::snprintf(group_name, sizeof group_name, "/steps/%06ld", step);
    const std::string group = group_name;
    H5T_class_t type_class{};
    std::size_t type_size = 0;
    EXPECT_EQ(file.attribute<double>(group, "time", H5T_NATIVE_DOUBLE, &type_class, &type_size),
              step_times[s]);
    EXPECT_EQ(type_class, H5T_FLOAT);
    EXPECT_EQ(type_size, 8u);
    EXPECT_EQ(file.attribute<std::int64_t>(group, "step", H5T_NATIVE_INT64, &type_class, &type_size), step);
    EXPECT_EQ(type_class, H5T_INTEGER);
    EXPECT_EQ(type_size, 8u);
    // plastic_strain and damage (zeros: not given) and status (ones) among them
    EXPECT_EQ(file.members(group).size(), 10u);
    EXPECT_EQ(file.doubles(group + "/status"), std::vector<double>(2, 1.0));
    EXPECT_EQ(file.doubles(group + "/damage"), std::vector<double>(2, 0.0));

    // Node vectors: SoA in memory, interleaved (N, 3) on disk.
    const std::map<std::string, double> vectors{
        {"displacement", 0.1}, {"velocity", 0.2}, {"acceleration", 0.3}, {"contact_force", 0.4}};
    for (const auto& [name, offset] : vectors) {
      const DatasetInfo info = file.info(group + "/" + name);
      EXPECT_EQ(info.shape, (std::vector<hsize_t>{12, 3})) << name;
      EXPECT_EQ(info.type_class, H5T_FLOAT);
      EXPECT_EQ(info.type_size, 8u);
      const std::vector<double> v = file.doubles(group + "/" + name);
      for (std::size_t n = 0; n < 12; ++n) {
        for (int c = 0; c < 3; ++c) {
          EXPECT_EQ(v[3 * n + static_cast<std::size_t>(c)], value(step, n, c, offset))
              << name << " node " << n;
        }
      }
    }
    // Stress is copied as-is: the solver's order xx yy zz xy yz xz is ParaView's.
    EXPECT_EQ(file.info(group + "/stress").shape, (std::vector<hsize_t>{2, 6}));
    const std::vector<double> stress = file.doubles(group + "/stress");
    for (std::size_t e = 0; e < 2; ++e) {
      for (int c = 0; c < 6; ++c)
        EXPECT_EQ(stress[6 * e + static_cast<std::size_t>(c)], value(step, e, c, 0.6));
    }
    EXPECT_EQ(file.info(group + "/von_mises").shape, (std::vector<hsize_t>{2}));
    EXPECT_EQ(file.doubles(group + "/von_mises"),
              (std::vector<double>{value(step, 0, 0, 0.7), value(step, 1, 0, 0.7)}));
    EXPECT_EQ(file.info(group + "/gap").shape, (std::vector<hsize_t>{12}));
    const std::vector<double> gap = file.doubles(group + "/gap");
    for (std::size_t n = 0; n < 12; ++n) EXPECT_EQ(gap[n], -value(step, n, 0, 0.5));
  }
}

TEST_F(ResultWriterTest, PureShearStaysInTheXyColumn) {
  // ParaView labels column 3 of a 6-component Matrix "XY"; a Voigt-ordered
  // writer would put a pure xy shear in column 5.
  ResultWriter writer(directory_.string(), "run", mesh_.view(), {OutputField::stress});
  const std::vector<double> shear{0, 0, 0, 7.5, 0, 0, 0, 0, 0, 7.5, 0, 0};
  StepData data;
  data.stress = shear.data();
  writer.write_step(data);
  H5Reader file(h5());
  EXPECT_EQ(file.doubles("/steps/000000/stress"), shear);
}

TEST_F(ResultWriterTest, RequestedFieldWithoutDataIsWrittenAsZeros) {
  ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields);
  StepData data;  // no pointers: e.g. contact_force and gap in a run without contact
  data.time = 1.0;
  writer.write_step(data);
  H5Reader file(h5());
  for (const char* name : {"displacement", "velocity", "acceleration", "contact_force"}) {
    EXPECT_EQ(file.doubles(std::string("/steps/000000/") + name), std::vector<double>(36, 0.0)) << name;
  }
  EXPECT_EQ(file.doubles("/steps/000000/stress"), std::vector<double>(12, 0.0));
  EXPECT_EQ(file.doubles("/steps/000000/von_mises"), std::vector<double>(2, 0.0));
  EXPECT_EQ(file.doubles("/steps/000000/gap"), std::vector<double>(12, 0.0));
}

TEST_F(ResultWriterTest, FieldLeftOutOfTheDeckIsAbsentFromStepsAndXdmf) {
  ResultWriter writer(directory_.string(), "run", mesh_.view(),
                      {OutputField::stress, OutputField::displacement, OutputField::stress});
  const StepFields fields(mesh_, 0);
  writer.write_step(fields.data(0, 0.0));
  writer.write_step(fields.data(1, 0.5));

  H5Reader file(h5());
  for (const char* group : {"/steps/000000", "/steps/000001"}) {
    EXPECT_EQ(file.members(group), (std::vector<std::string>{"displacement", "stress"}));
  }
  const std::string xml = read_text(xmf());
  EXPECT_EQ(count(xml, "<Attribute "), 4);
  EXPECT_EQ(count(xml, "Name=\"displacement\""), 2);
  EXPECT_EQ(count(xml, "Name=\"stress\""), 2);
  for (const char* absent : {"velocity", "acceleration", "von_mises", "contact_force", "gap"}) {
    EXPECT_EQ(xml.find(absent), std::string::npos) << absent;
  }
}

TEST_F(ResultWriterTest, HistoryRowsAreAppendedAtEveryStepAndFlush) {
  ResultWriter writer(directory_.string(), "run", mesh_.view(), {OutputField::velocity});
  const StepFields fields(mesh_, 0);
  auto row = [](int i) { return HistoryRow{0.1 * i, 1.0 + i, 2.0 + i, 3.0 + i, 4.0 + i, 5.0 + i, 6.0 + i}; };
  const std::array<const char*, 7> columns{"time",           "kinetic_energy",   "internal_energy",
                                           "contact_energy", "hourglass_energy", "external_work",
                                           "total_energy"};
  auto history_length = [&]() {
    H5Reader file(h5());
    const hsize_t length = file.info("/history/time").shape.at(0);
    for (const char* column : columns)
      EXPECT_EQ(file.info(std::string("/history/") + column).shape.at(0), length);
    return length;
  };

  writer.add_history(row(0));
  writer.add_history(row(1));
  EXPECT_EQ(history_length(), 0u) << "rows are buffered until a step or flush";
  writer.write_step(fields.data(0, 0.0));
  EXPECT_EQ(history_length(), 2u);
  for (int i = 2; i < 5; ++i) writer.add_history(row(i));
  writer.write_step(fields.data(1, 0.25));
  EXPECT_EQ(history_length(), 5u);
  writer.write_step(fields.data(2, 0.5));
  EXPECT_EQ(history_length(), 5u);
  writer.flush();  // nothing buffered: no change
  EXPECT_EQ(history_length(), 5u);
  writer.add_history(row(5));
  writer.flush();
  EXPECT_EQ(history_length(), 6u);
  EXPECT_EQ(open_hdf5_files(), 0);

  H5Reader file(h5());
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const std::vector<double> values = file.doubles(std::string("/history/") + columns[c]);
    ASSERT_EQ(values.size(), 6u);
    for (int i = 0; i < 6; ++i) {
      const HistoryRow expected = row(i);
      const std::array<double, 7> fields_of_row{
          expected.time,           expected.kinetic_energy,   expected.internal_energy,
          expected.contact_energy, expected.hourglass_energy, expected.external_work,
          expected.total_energy};
      EXPECT_EQ(values[static_cast<std::size_t>(i)], fields_of_row[c]) << columns[c] << " row " << i;
    }
  }
}

// Crash safety of a step's link (docs/stability.md, "Interrupted and killed runs"): /steps keeps its
// links in its own object header, sized at creation for the steps the run plans, so
// adding a step rewrites that one block where it is. The header neither moves nor
// grows nor gains a chunk over the planned steps; past them it may grow, and every
// step stays readable. (A group of the old format, a local heap and a B-tree of
// symbol nodes, fails the first check: its links are not "compact".)
TEST_F(ResultWriterTest, StepLinksAreRewrittenInPlaceInOneBlock) {
  constexpr long planned = 40;
  ResultWriter writer(directory_.string(), "run", mesh_.view(), {OutputField::velocity}, {}, planned);
  const StepFields fields(mesh_, 0);
  struct Header {
    haddr_t address;
    hsize_t bytes;
    unsigned chunks;
  };
  auto steps_header = [&](H5G_storage_type_t* storage) {
    const hid_t file = H5Fopen(h5().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t group = H5Gopen2(file, "/steps", H5P_DEFAULT);
    H5O_info_t info{};
    H5Oget_info2(group, &info, H5O_INFO_BASIC | H5O_INFO_HDR);
    H5G_info_t group_info{};
    H5Gget_info(group, &group_info);
    *storage = group_info.storage_type;
    H5Gclose(group);
    H5Fclose(file);
    return Header{info.addr, info.hdr.space.total, info.hdr.nchunks};
  };
  H5G_storage_type_t storage{};
  const Header before = steps_header(&storage);
  EXPECT_EQ(storage, H5G_STORAGE_TYPE_COMPACT);
  EXPECT_EQ(before.chunks, 1u);
  for (long step = 0; step < planned; ++step) {
    writer.write_step(fields.data(step, 1e-3 * static_cast<double>(step)));
    const Header now = steps_header(&storage);
    ASSERT_EQ(storage, H5G_STORAGE_TYPE_COMPACT) << "step " << step;
    ASSERT_EQ(now.address, before.address) << "step " << step;
    ASSERT_EQ(now.bytes, before.bytes) << "step " << step;
    ASSERT_EQ(now.chunks, 1u) << "step " << step;
  }
  for (long step = planned; step < 3 * planned; ++step)  // more steps than planned: still fine
    writer.write_step(fields.data(step, 1e-3 * static_cast<double>(step)));
  H5Reader file(h5());
  const std::vector<std::string> names = file.members("/steps");
  ASSERT_EQ(names.size(), static_cast<std::size_t>(3 * planned));
  for (long step = 0; step < 3 * planned; ++step) {
    char name[8];
    std::snprintf(name, sizeof name, "%06ld", step);
    EXPECT_EQ(names[static_cast<std::size_t>(step)], name);
    EXPECT_EQ(file.attribute<double>(std::string("/steps/") + name, "time", H5T_NATIVE_DOUBLE),
              1e-3 * static_cast<double>(step));
  }
  // Superblock version 0: the file stays readable by every HDF5 reader, and a killed
  // writer leaves no "file is open for writing" flag (a version 3 superblock would).
  const hid_t raw = H5Fopen(h5().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  H5F_info2_t info{};
  H5Fget_info2(raw, &info);
  H5Fclose(raw);
  EXPECT_EQ(info.super.version, 0u);
}

TEST_F(ResultWriterTest, DestructorFlushesHistoryLeftInTheBuffer) {
  {
    ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields);
    writer.add_history(HistoryRow{1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0});
  }
  H5Reader file(h5());
  EXPECT_EQ(file.doubles("/history/total_energy"), std::vector<double>{7.0});
}

TEST_F(ResultWriterTest, XdmfDescribesEveryStepWithTheDatasetsShapesAndTypes) {
  ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields);
  for (std::size_t s = 0; s < 3; ++s) {
    const StepFields fields(mesh_, step_numbers[s]);
    writer.write_step(fields.data(step_numbers[s], step_times[s]));
    const std::string xml = read_text(xmf());
    EXPECT_EQ(count(xml, "<Grid Name=\"step_"), static_cast<int>(s + 1))
        << "the .xmf is rewritten at each step";
    EXPECT_FALSE(fs::exists(directory_ / "run.xmf.tmp"));
  }
  const std::string xml = read_text(xmf());

  EXPECT_NE(xml.find("<Xdmf Version=\"3.0\""), std::string::npos);
  EXPECT_NE(xml.find("<Grid Name=\"TimeSeries\" GridType=\"Collection\" CollectionType=\"Temporal\">"),
            std::string::npos);
  EXPECT_EQ(count(xml, "<Grid Name=\"step_"), 3);
  EXPECT_EQ(count(xml, "<Topology TopologyType=\"Hexahedron\" NumberOfElements=\"2\" NodesPerElement=\"8\">"),
            3);
  EXPECT_EQ(count(xml, "<Geometry GeometryType=\"XYZ\">"), 3);
  for (std::size_t s = 0; s < 3; ++s) {
    char grid[40];
    std::snprintf(grid, sizeof grid, "<Grid Name=\"step_%06ld\"", step_numbers[s]);
    EXPECT_EQ(count(xml, grid), 1) << grid;
    EXPECT_EQ(count(xml, "<Time Value=\"" + g17(step_times[s]) + "\"/>"), 1) << g17(step_times[s]);
  }
  EXPECT_EQ(g17(step_times[1]), "3.3333333333333334e-08") << "the check above needs 17 digits";

  // Attribute kinds and centres.
  for (const char* vector : {"displacement", "velocity", "acceleration", "contact_force"}) {
    EXPECT_EQ(count(xml, "<Attribute Name=\"" + std::string(vector) +
                             "\" AttributeType=\"Vector\" Center=\"Node\">"),
              3);
  }
  EXPECT_EQ(count(xml, "<Attribute Name=\"stress\" AttributeType=\"Matrix\" Center=\"Cell\">"), 3);
  EXPECT_EQ(count(xml, "<Attribute Name=\"von_mises\" AttributeType=\"Scalar\" Center=\"Cell\">"), 3);
  EXPECT_EQ(count(xml, "<Attribute Name=\"gap\" AttributeType=\"Scalar\" Center=\"Node\">"), 3);

  // Every DataItem names a dataset by a path relative to the .xmf, and its
  // Dimensions, NumberType and Precision are those of that dataset.
  const std::regex data_item(
      "<DataItem Dimensions=\"([0-9 ]+)\" NumberType=\"(\\w+)\" Precision=\"(\\d)\" "
      "Format=\"HDF\">([^<:]+):([^<]+)</DataItem>");
  H5Reader file(h5());
  int items = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), data_item); it != std::sregex_iterator();
       ++it) {
    const std::smatch& m = *it;
    ++items;
    EXPECT_EQ(m[4].str(), "run.h5");
    const DatasetInfo info = file.info(m[5].str());
    std::string dims;
    for (hsize_t d : info.shape) dims += (dims.empty() ? "" : " ") + std::to_string(d);
    EXPECT_EQ(m[1].str(), dims) << m[5].str();
    EXPECT_EQ(m[2].str(), info.type_class == H5T_FLOAT ? "Float" : "Int") << m[5].str();
    EXPECT_EQ(m[3].str(), std::to_string(info.type_size)) << m[5].str();
  }
  EXPECT_EQ(items, 3 * (2 + 10));  // mesh, then the ten fields
  EXPECT_EQ(count(xml, "<DataItem "), items) << "a DataItem the scan above did not recognise";
  EXPECT_EQ(count(xml, "Dimensions=\"2 6\""), 3);
  EXPECT_EQ(count(xml, "run.h5:/mesh/coordinates"), 3);
  EXPECT_EQ(xml.find(directory_.string()), std::string::npos) << "no absolute path";
}

TEST_F(ResultWriterTest, TimeMustIncreaseStrictly) {
  ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields);
  const StepFields fields(mesh_, 0);
  writer.write_step(fields.data(0, 1.0));
  EXPECT_THROW(writer.write_step(fields.data(1, 1.0)), std::logic_error);
  EXPECT_THROW(writer.write_step(fields.data(1, 0.5)), std::logic_error);
  EXPECT_THROW(writer.write_step(fields.data(0, 2.0)), std::logic_error) << "step number repeated";
  EXPECT_THROW(writer.write_step(fields.data(1, std::numeric_limits<double>::quiet_NaN())), std::logic_error);
  writer.write_step(fields.data(1, 2.0));  // the rejected calls left nothing behind
  H5Reader file(h5());
  EXPECT_EQ(file.doubles("/time"), (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(count(read_text(xmf()), "<Grid Name=\"step_"), 2);
}

TEST_F(ResultWriterTest, FieldOfTheWrongSizeIsALogicErrorAndLeavesNoPartialStep) {
  ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields);
  StepFields fields(mesh_, 0);
  const NodalVectors short_velocity(5);
  StepData data = fields.data(0, 0.0);
  data.velocity = &short_velocity;
  EXPECT_THROW(writer.write_step(data), std::logic_error);
  writer.write_step(fields.data(0, 0.0));
  H5Reader file(h5());
  EXPECT_EQ(file.members("/steps"), std::vector<std::string>{"000000"});
}

TEST_F(ResultWriterTest, Hdf5FailureThrowsRuntimeErrorNamingTheFile) {
  // The .h5 path is taken by a directory: the file cannot be created.
  fs::create_directories(h5());
  try {
    ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(h5().string()), std::string::npos) << error.what();
  }
  fs::remove_all(h5());

  // The file disappears during the run.
  ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields);
  fs::remove(h5());
  const StepFields fields(mesh_, 0);
  try {
    writer.write_step(fields.data(0, 0.0));
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(h5().string()), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(xmf())) << "a step that failed must not be named in the .xmf";
  EXPECT_EQ(open_hdf5_files(), 0);
}

// Written in the background, a run leaves the same bytes in every dataset and the same
// .xmf as written by the caller; the caller's buffers may change as soon as write_step
// returns (the step was copied).
TEST_F(ResultWriterTest, InTheBackgroundTheFilesAreTheSame) {
  const std::vector<std::string> pairs{"interface"};
  auto run = [&](const fs::path& directory, bool background) {
    ResultWriter writer(directory.string(), "run", mesh_.view(), all_fields, pairs);
    writer.write_in_background(background);
    for (long step = 0; step < 12; ++step) {
      for (int row = 0; row < 3; ++row) {
        const double t = 1e-3 * static_cast<double>(3 * step + row);
        writer.add_history({t, 1.0 + t, 2.0, 3.0, 4.0, 5.0, 6.0 + t}, {{{{t, 2 * t, 3 * t}}, t}});
      }
      auto fields = std::make_unique<StepFields>(mesh_, step);
      writer.write_step(fields->data(step, 1e-3 * static_cast<double>(3 * step)));
      fields.reset();  // the writer must not read the caller's arrays after write_step
    }
    writer.add_history({1.0, 0, 0, 0, 0, 0, 0}, {{{{0, 0, 0}}, 0}});
    writer.flush();
    EXPECT_EQ(open_hdf5_files(), 0);
  };
  run(directory_ / "caller", false);
  run(directory_ / "background", true);
  H5Reader a(directory_ / "caller" / "run.h5"), b(directory_ / "background" / "run.h5");
  std::vector<std::string> datasets{"/time", "/history/time", "/history/total_energy",
                                    "/history/contact/interface/force",
                                    "/history/contact/interface/max_penetration"};
  for (const std::string& step : a.members("/steps")) {
    for (const std::string& field : a.members("/steps/" + step))
      datasets.push_back("/steps/" + step + "/" + field);
  }
  EXPECT_EQ(a.members("/steps").size(), 12u);
  EXPECT_EQ(datasets.size(), 5u + 12u * 10u);
  for (const std::string& path : datasets) EXPECT_EQ(a.doubles(path), b.doubles(path)) << path;
  EXPECT_EQ(a.doubles("/history/time").size(), 37u);
  EXPECT_EQ(read_text(directory_ / "caller" / "run.xmf"), read_text(directory_ / "background" / "run.xmf"));
}

// A failure of the writer's thread is thrown by the caller's next call, and the .xmf
// never names the step that failed.
TEST_F(ResultWriterTest, InTheBackgroundAFailureIsThrownByTheNextCall) {
  ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields);
  writer.write_in_background(true);
  const StepFields fields(mesh_, 0);
  writer.write_step(fields.data(0, 0.0));
  writer.flush();  // step 0 is on disk
  EXPECT_THROW(writer.write_in_background(false), std::logic_error) << "only before the first step";
  fs::remove(h5());
  writer.write_step(fields.data(1, 1.0));  // copied; the thread fails to open the file
  try {
    writer.write_step(fields.data(2, 2.0));
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(h5().string()), std::string::npos) << error.what();
  }
  const std::string xmf_text = read_text(xmf());
  EXPECT_NE(xmf_text.find("/steps/000000/"), std::string::npos);
  EXPECT_EQ(xmf_text.find("/steps/000001/"), std::string::npos);
  EXPECT_EQ(open_hdf5_files(), 0);
}

TEST_F(ResultWriterTest, BadMeshOrNameIsRejected) {
  EXPECT_THROW(ResultWriter(directory_.string(), "a:b", mesh_.view(), all_fields), std::invalid_argument);
  EXPECT_THROW(ResultWriter(directory_.string(), "", mesh_.view(), all_fields), std::invalid_argument);
  TinyMesh bad = mesh_;
  bad.connectivity[3] = 12;
  EXPECT_THROW(ResultWriter(directory_.string(), "run", bad.view(), all_fields), std::invalid_argument);
  bad = mesh_;
  bad.part.push_back(2);
  EXPECT_THROW(ResultWriter(directory_.string(), "run", bad.view(), all_fields), std::invalid_argument);
}

TEST_F(ResultWriterTest, MeshWithoutPartsIsOnePart) {
  ResultWriter writer(directory_.string(), "run", {&mesh_.x_ref, &mesh_.connectivity, nullptr}, all_fields);
  H5Reader file(h5());
  EXPECT_EQ(file.read<std::int32_t>("/mesh/part", H5T_NATIVE_INT32), (std::vector<std::int32_t>{0, 0}));
}

// The friction histories: friction_work beside the energies, each pair's normal and
// tangential force, each rigid wall's force, one row per history row.
TEST_F(ResultWriterTest, WallAndFrictionHistoriesAreWrittenRowByRow) {
  {
    ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields,
                        HistoryGroups{{"interface"}, {"floor"}});
    for (int row = 0; row < 5; ++row) {
      const double t = 1e-3 * row;
      writer.add_history({t, 0, 0, 0, 0, 0, 0, 0, 2 * t}, {{{{t, 0, 0}}, 0.0, 4.0 + t, 5.0 + t}},
                         {{{{t, 0, -t}}}});
    }
    EXPECT_THROW(writer.add_history({1.0}, {{}}), std::logic_error) << "a row for each wall";
    writer.flush();
  }
  H5Reader file(h5());
  EXPECT_EQ(file.info("/history/wall/floor/force").shape, (std::vector<hsize_t>{5, 3}));
  EXPECT_EQ(file.doubles("/history/wall/floor/force")[3 * 4 + 2], -4e-3);
  EXPECT_EQ(file.doubles("/history/friction_work")[4], 8e-3);
  EXPECT_EQ(file.doubles("/history/contact/interface/normal_force")[2], 4.0 + 2e-3);
  EXPECT_EQ(file.doubles("/history/contact/interface/tangential_force")[2], 5.0 + 2e-3);
  EXPECT_THROW(ResultWriter(directory_.string(), "bad", mesh_.view(), all_fields, HistoryGroups{{}, {"a/b"}}),
               std::invalid_argument);
}

// The reactions of the boundary conditions: /history/boundary/INDEX/force after the
// walls' rows; eroded_energy and eroded_mass beside the energies.
TEST_F(ResultWriterTest, BoundaryReactionsFollowTheWallsRows) {
  {
    HistoryGroups groups{{}, {"floor"}};
    groups.boundaries = 2;
    ResultWriter writer(directory_.string(), "run", mesh_.view(), all_fields, groups);
    for (int row = 0; row < 3; ++row) {
      const double t = 1e-3 * row;
      writer.add_history({t, 0, 0, 0, 0, 0, 0, 0, 0, 3 * t, 0}, {},
                         {{{{t, 0, 0}}}, {{{0, 0, 10 * t}}}, {{{0, -t, 0}}}});
    }
    EXPECT_THROW(writer.add_history({1.0}, {}, {{}}), std::logic_error)
        << "a row for each wall and condition";
    writer.flush();
  }
  H5Reader file(h5());
  EXPECT_EQ(file.members("/history/boundary"), (std::vector<std::string>{"0", "1"}));
  EXPECT_EQ(file.info("/history/boundary/1/force").shape, (std::vector<hsize_t>{3, 3}));
  EXPECT_EQ(file.doubles("/history/boundary/0/force")[3 * 2 + 2], 2e-2);
  EXPECT_EQ(file.doubles("/history/boundary/1/force")[3 * 1 + 1], -1e-3);
  EXPECT_EQ(file.doubles("/history/wall/floor/force")[3 * 2], 2e-3);
  EXPECT_EQ(file.doubles("/history/eroded_energy")[2], 6e-3);
  EXPECT_EQ(file.doubles("/history/eroded_mass")[2], 0.0);
}

}  // namespace
}  // namespace exdyn::output
