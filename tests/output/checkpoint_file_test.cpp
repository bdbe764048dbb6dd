// The checkpoint container (output/checkpoint_file.hpp): what is written reads back
// the same, and a checkpoint damaged anywhere (truncated, one bit flipped, a section
// missing or of the wrong length) is refused with an InputError naming the fault.
#include "output/checkpoint_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "common/errors.hpp"

namespace exdyn::output {
namespace {

namespace fs = std::filesystem;

class CheckpointFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() / ("exdyn_checkpoint_" + std::to_string(::getpid()));
    fs::create_directories(directory_);
    path_ = (directory_ / "run.00000007.restart").string();
  }
  void TearDown() override { fs::remove_all(directory_); }
  std::vector<unsigned char> bytes() const {
    std::ifstream in(path_, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  void write_sample() const {
    CheckpointWriter file(path_);
    file.add("state/u", std::vector<double>{1.0, -2.5, 3.25});
    file.add("deck", std::string_view("name: run\n"));
    file.add_value("next_step", 7L);
    file.add("empty", std::vector<int>{});
    file.commit();
  }
  fs::path directory_;
  std::string path_;
};

TEST_F(CheckpointFileTest, WhatIsWrittenReadsBackTheSame) {
  write_sample();
  EXPECT_FALSE(fs::exists(path_ + ".tmp"));
  const CheckpointReader file(path_);
  EXPECT_EQ(file.values<double>("state/u"), (std::vector<double>{1.0, -2.5, 3.25}));
  EXPECT_EQ(file.text("deck"), "name: run\n");
  EXPECT_EQ(file.value<long>("next_step"), 7L);
  EXPECT_TRUE(file.values<int>("empty").empty());
  EXPECT_FALSE(file.has("nothing"));
  EXPECT_THROW((void)file.bytes("nothing"), InputError);
  EXPECT_THROW((void)file.values<double>("state/u", 4), InputError);  // not the size the model has
  EXPECT_THROW((void)file.values<double>("deck"), InputError);        // 10 bytes: not whole doubles
}

TEST_F(CheckpointFileTest, AWriterNotCommittedLeavesNoFile) {
  {
    CheckpointWriter file(path_);
    file.add("state/u", std::vector<double>{1.0});
    EXPECT_TRUE(fs::exists(path_ + ".tmp"));
  }
  EXPECT_FALSE(fs::exists(path_));
  EXPECT_FALSE(fs::exists(path_ + ".tmp"));
}

// Every bit of the file matters: each single-bit flip is refused, at every byte.
TEST_F(CheckpointFileTest, EveryFlippedBitAndEveryTruncationIsRefused) {
  write_sample();
  const std::vector<unsigned char> good = bytes();
  EXPECT_NO_THROW(CheckpointReader(good, "good"));
  for (std::size_t at = 0; at < good.size(); ++at)
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<unsigned char> bad = good;
      bad[at] = static_cast<unsigned char>(bad[at] ^ (1u << bit));
      EXPECT_THROW(CheckpointReader(bad, "bad"), InputError) << "byte " << at << " bit " << bit;
    }
  for (std::size_t size = 0; size < good.size(); ++size)
    EXPECT_THROW(CheckpointReader(std::vector<unsigned char>(good.begin(), good.begin() + long(size)), "cut"),
                 InputError)
        << size << " bytes";
}

TEST_F(CheckpointFileTest, TheMessageNamesTheFileAndTheFault) {
  write_sample();
  std::vector<unsigned char> bad = bytes();
  bad[40] ^= 4;  // inside the first section's bytes
  try {
    CheckpointReader(bad, "damaged.restart");
    FAIL() << "a damaged checkpoint was read";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("damaged.restart"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("checksum"), std::string::npos) << error.what();
  }
  EXPECT_THROW(CheckpointReader((directory_ / "none.restart").string()), InputError);
  EXPECT_THROW(CheckpointReader(directory_.string()), InputError);  // a directory, not a file
}

// The hash's tail and length: inputs that differ only past a multiple of 32 bytes, or
// only in their length (a zero byte more), hash apart.
// A section written in pieces (NAME#K, as the ranks of a run write their rows and
// chunks) reads as the whole, in the order of K, whatever the order in the file; a gap
// in the pieces, a section both whole and in pieces, or a piece number that is none are
// refused.
TEST_F(CheckpointFileTest, PiecesReadAsTheWholeSectionInTheirOrder) {
  {
    CheckpointWriter file(path_);
    file.add("u#2", std::vector<double>{5.0});
    file.add("u#0", std::vector<double>{1.0, 2.0});
    file.add("u#1", std::vector<double>{});
    file.add("u#3", std::vector<double>{6.0, 7.0});
    file.add("empty#0", std::vector<double>{});
    file.add_value("next_step", 3L);
    file.commit();
  }
  const CheckpointReader reader(path_);
  EXPECT_EQ(reader.values<double>("u"), (std::vector<double>{1.0, 2.0, 5.0, 6.0, 7.0}));
  EXPECT_TRUE(reader.values<double>("empty").empty());
  EXPECT_FALSE(reader.has("u#0"));
  const auto refused = [&](const std::vector<std::string>& names, const std::string& fault) {
    {
      CheckpointWriter file(path_);
      for (const std::string& name : names) file.add(name, std::vector<double>{1.0});
      file.commit();
    }
    try {
      const CheckpointReader bad(path_);
      ADD_FAILURE() << "read: " << names.front();
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(fault), std::string::npos) << error.what();
    }
  };
  refused({"u#0", "u#2"}, "lacks piece 1");
  refused({"u", "u#0"}, "is whole and in pieces");
  refused({"u#x"}, "is no piece of a section");
  refused({"#0"}, "is no piece of a section");
}

TEST(HashBytes, TheTailAndTheLengthCount) {
  std::vector<unsigned char> a(37, 0), b(38, 0);
  EXPECT_NE(hash_bytes(a.data(), a.size()), hash_bytes(b.data(), b.size()));
  std::vector<unsigned char> c = a;
  c[36] = 1;
  EXPECT_NE(hash_bytes(a.data(), a.size()), hash_bytes(c.data(), c.size()));
  EXPECT_EQ(hash_bytes(a.data(), a.size()), hash_bytes(std::vector<unsigned char>(37, 0).data(), 37));
}

TEST_F(CheckpointFileTest, TheWrittenPositionReadsBackAndABadOneIsRefused) {
  WrittenPosition position{
      {0, 100, 200}, {0.0, 1.0e-6, 2.0e-6}, 41, {{0, {input::OutputField::displacement}}}};
  {
    CheckpointWriter file(path_);
    add_position(file, position);
    file.commit();
  }
  const WrittenPosition back = read_position(CheckpointReader(path_));
  EXPECT_EQ(back.steps, position.steps);
  EXPECT_EQ(back.times, position.times);
  EXPECT_EQ(back.history_rows, 41u);
  ASSERT_EQ(back.field_sets.size(), 1u);
  EXPECT_EQ(back.field_sets[0].fields, position.field_sets[0].fields);
  position.steps = {0, 200, 100};  // out of order
  {
    CheckpointWriter file(path_);
    add_position(file, position);
    file.commit();
  }
  EXPECT_THROW(read_position(CheckpointReader(path_)), InputError);
}

// The fuzzer's seeds and past findings (tests/fuzz/{seeds,regressions}/checkpoint/): each
// is read or refused with an InputError, never anything else.
TEST(CheckpointFuzzInputs, AreReadOrRefused) {
  int files = 0;
  for (const char* folder : {"seeds/checkpoint", "regressions/checkpoint"}) {
    const fs::path path = fs::path(EXDYN_SOURCE_DIR) / "tests" / "fuzz" / folder;
    for (const fs::directory_entry& entry : fs::directory_iterator(path)) {
      ++files;
      try {
        const CheckpointReader file(entry.path().string());
        (void)read_position(file);
      } catch (const InputError&) {
      }
    }
  }
  EXPECT_GE(files, 2);
}

}  // namespace
}  // namespace exdyn::output
