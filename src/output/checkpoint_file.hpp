// A restart checkpoint on disk (docs/output.md, "Checkpoints"): named sections of raw
// bytes, each with its own 64-bit hash, and a trailer that hashes the section headers.
//
//   "EXDYNCKP" u32 format
//   per section: u32 name length, name, u64 bytes, u64 hash of the bytes, the bytes
//   "EXDYNEND" u64 sections, u64 file length, u64 hash of every section's name, length and hash
//
// (little-endian, as the machine writes it). A section named NAME#K (K = 0, 1, ...) is
// piece K of section NAME: a reader joins the pieces in the order of K (a run on many
// ranks writes a large array as the pieces its ranks hold). A reader takes nothing from a file before
// every hash agrees: a truncated file, a flipped byte anywhere or a file of another
// format is refused as a whole (InputError naming the file and what is wrong). What a
// section holds is its writer's business (solver/checkpoint.cpp).
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <deque>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "common/mpi.hpp"
#include "output/result_writer.hpp"

namespace exdyn::output {

inline constexpr std::uint32_t checkpoint_format = 1;

// A 64-bit hash of n bytes: four lanes of 8-byte words, each lane x <- rotl((x ^ w) *
// odd, 29), a bijection of x for each word, so a changed word always changes its lane;
// about 8 GB/s, a small part of a checkpoint's write.
std::uint64_t hash_bytes(const void* data, std::size_t n);

// Writes a checkpoint section by section straight to PATH.tmp; commit() renames it to
// PATH once it is whole and on disk (fdatasync), so a kill at any moment leaves the
// old PATH or the new one. Destroyed without commit(), it removes PATH.tmp.
// On many ranks (`comm` distributed) every rank adds its own sections (rank 0 the
// whole ones, each rank its pieces), kept in memory; commit(), collective, writes
// each rank's sections at its place in one file with MPI-IO (rank after rank), rank 0
// the head and the trailer (the headers' hash over every rank's, in file order), and
// renames the file once every rank's part is on disk.
class CheckpointWriter {
 public:
  explicit CheckpointWriter(std::string path, const mpi::Communicator& comm = {});
  ~CheckpointWriter();
  CheckpointWriter(const CheckpointWriter&) = delete;
  CheckpointWriter& operator=(const CheckpointWriter&) = delete;

  void add(std::string_view name, const void* data, std::size_t bytes);
  // A section whose bytes stay where they are until commit() (on many ranks they are
  // written from there; on one process as add).
  void add_view(std::string_view name, const void* data, std::size_t bytes);
  template <class T>
  void add(std::string_view name, const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    add(name, values.data(), values.size() * sizeof(T));
  }
  void add(std::string_view name, std::string_view text) { add(name, text.data(), text.size()); }
  template <class T>
  void add_value(std::string_view name, const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    add(name, &value, sizeof value);
  }
  void commit();
  // The file's length once committed (before: what is written so far).
  std::uint64_t bytes_written() const { return length_; }

 private:
  void put(const void* data, std::size_t bytes);
  void add_header(std::string_view name, const void* data, std::size_t bytes);
  void commit_ranks();
  std::string path_, temporary_;
  mpi::Communicator comm_;
  std::FILE* file_ = nullptr;
  // Many ranks: this rank's part of the file, in order: spans of the region (headers and
  // copied sections) and viewed sections; its length.
  struct Span {
    const unsigned char* external = nullptr;  // a viewed section's bytes; null: the region's
    std::size_t at = 0;                       // in the region
    std::uint64_t bytes = 0;
  };
  std::vector<Span> spans_;
  std::vector<unsigned char> region_;
  std::uint64_t mine_ = 0;
  std::uint64_t length_ = 0, sections_ = 0;
  std::vector<unsigned char> headers_;  // every section's name, length and hash, for the trailer's hash
};

// A whole checkpoint read and checked. Sections are views into the file's bytes.
class CheckpointReader {
 public:
  // Reads and checks PATH; throws InputError naming it and the fault.
  explicit CheckpointReader(const std::string& path);
  // Checks bytes already in memory (the fuzz target); `path` names them in messages.
  CheckpointReader(std::vector<unsigned char> bytes, std::string path);

  const std::string& path() const { return path_; }
  bool has(std::string_view name) const { return sections_.count(std::string(name)) != 0; }
  // The section's bytes; InputError when there is none.
  std::string_view bytes(std::string_view name) const;
  std::string text(std::string_view name) const { return std::string(bytes(name)); }
  // The section as values of T: InputError when its length is not a whole number of them,
  // or (expected_count >= 0) not that many.
  template <class T>
  std::vector<T> values(std::string_view name, long expected_count = -1) const {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::string_view b = bytes(name);
    check_length(name, b.size(), sizeof(T), expected_count);
    std::vector<T> out(b.size() / sizeof(T));
    if (!out.empty()) std::memcpy(static_cast<void*>(out.data()), b.data(), b.size());
    return out;
  }
  template <class T>
  T value(std::string_view name) const {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::string_view b = bytes(name);
    check_length(name, b.size(), sizeof(T), 1);
    T out;
    std::memcpy(static_cast<void*>(&out), b.data(), sizeof(T));
    return out;
  }
  // A section into an existing vector of the size it must have.
  template <class T>
  void read_into(std::string_view name, std::vector<T>& out) const {
    std::vector<T> v = values<T>(name, long(out.size()));
    out.swap(v);
  }

 private:
  void parse();
  void join_pieces();
  void check_length(std::string_view name, std::size_t bytes, std::size_t size, long expected) const;
  [[noreturn]] void fail(const std::string& what) const;
  std::string path_;
  std::vector<unsigned char> data_;
  std::deque<std::string> joined_;  // sections written in pieces, joined (views into them stay valid)
  std::map<std::string, std::string_view, std::less<>> sections_;
};

// Where a run stands in NAME.h5 (result_writer.hpp), as sections output/...: written
// with the checkpoint, and read back (InputError when they do not make one).
void add_position(CheckpointWriter& file, const WrittenPosition& position);
WrittenPosition read_position(const CheckpointReader& file);

}  // namespace exdyn::output
