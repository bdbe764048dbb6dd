// A restart checkpoint on disk (checkpoint_file.hpp).
#include "output/checkpoint_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "common/errors.hpp"

namespace exdyn::output {

namespace {

constexpr char head_magic[8] = {'E', 'X', 'D', 'Y', 'N', 'C', 'K', 'P'};
constexpr char tail_magic[8] = {'E', 'X', 'D', 'Y', 'N', 'E', 'N', 'D'};
constexpr std::size_t trailer_size = 8 + 3 * 8;
constexpr std::size_t max_name = 256;

inline std::uint64_t rotl(std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }

// The lane step: a bijection of x for a fixed word w (xor, multiply by an odd number,
// rotate), so a change of any word of a lane reaches its final value.
inline std::uint64_t mix(std::uint64_t x, std::uint64_t w) {
  return rotl((x ^ w) * 0x9e3779b97f4a7c15ULL, 29);
}

std::uint64_t load_word(const unsigned char* p) {
  std::uint64_t w;
  std::memcpy(&w, p, 8);
  return w;
}

std::string system_error(const std::string& what, const std::string& path) {
  return what + " " + path + ": " + std::strerror(errno);
}

// Every rank's section headers on rank 0, rank after rank (the file's order), for the
// trailer's hash, and the ranks' sections counted (`sections`, rank 0). Collective.
std::vector<unsigned char> gather_headers(const mpi::Communicator& comm,
                                          const std::vector<unsigned char>& mine, std::uint64_t count,
                                          std::uint64_t& sections) {
  const auto ranks = std::size_t(comm.size);
  const int bytes = int(mine.size());
  std::vector<int> counts(ranks), displacements(ranks, 0);
  mpi::check(MPI_Gather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm.comm),
             "MPI_Gather of the checkpoint's headers");
  for (std::size_t r = 1; r < ranks; ++r) displacements[r] = displacements[r - 1] + counts[r - 1];
  std::vector<unsigned char> headers(comm.root() ? std::size_t(displacements.back() + counts.back()) : 0);
  mpi::check(MPI_Gatherv(mine.data(), bytes, MPI_BYTE, headers.data(), counts.data(), displacements.data(),
                         MPI_BYTE, 0, comm.comm),
             "MPI_Gatherv of the checkpoint's headers");
  mpi::check(MPI_Reduce(&count, &sections, 1, MPI_UINT64_T, MPI_SUM, 0, comm.comm),
             "MPI_Reduce of the checkpoint's sections");
  return headers;
}

}  // namespace

std::uint64_t hash_bytes(const void* data, std::size_t n) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::array<std::uint64_t, 4> lane{0x243f6a8885a308d3ULL, 0x13198a2e03707344ULL, 0xa4093822299f31d0ULL,
                                    0x082efa98ec4e6c89ULL};
  std::size_t i = 0;
  for (; i + 32 <= n; i += 32)
    for (std::size_t k = 0; k < 4; ++k) lane[k] = mix(lane[k], load_word(p + i + 8 * k));
  // The tail, padded with zeros, then the length: a zero tail and a shorter one differ.
  unsigned char tail[32] = {};
  if (n > i) std::memcpy(tail, p + i, n - i);
  for (std::size_t k = 0; k < 4; ++k) lane[k] = mix(lane[k], load_word(tail + 8 * k));
  std::uint64_t h = std::uint64_t(n);
  for (std::size_t k = 0; k < 4; ++k) h = mix(h, lane[k]);
  return h ^ (h >> 31);
}

// ---------------------------------------------------------------------------

CheckpointWriter::CheckpointWriter(std::string path, const mpi::Communicator& comm)
    : path_(std::move(path)), temporary_(path_ + ".tmp"), comm_(comm) {
  if (comm_.distributed()) {  // in memory until commit (the head is rank 0's)
    if (comm_.root()) length_ = sizeof head_magic + sizeof checkpoint_format;
    return;
  }
  file_ = std::fopen(temporary_.c_str(), "wb");
  if (file_ == nullptr) throw std::runtime_error(system_error("cannot create the checkpoint", temporary_));
  put(head_magic, sizeof head_magic);
  put(&checkpoint_format, sizeof checkpoint_format);
}

CheckpointWriter::~CheckpointWriter() {
  if (comm_.distributed() && mine_ > 0 && comm_.root()) std::remove(temporary_.c_str());
  if (file_ == nullptr) return;
  std::fclose(file_);
  std::remove(temporary_.c_str());
}

void CheckpointWriter::put(const void* data, std::size_t bytes) {
  if (comm_.distributed()) {  // a span of the region (one with the span before, if that is the region's too)
    if (bytes == 0) return;
    const auto* b = static_cast<const unsigned char*>(data);
    if (!spans_.empty() && spans_.back().external == nullptr)
      spans_.back().bytes += bytes;
    else
      spans_.push_back({nullptr, region_.size(), bytes});
    region_.insert(region_.end(), b, b + bytes);
    mine_ += bytes;
    return;
  }
  if (bytes > 0 && std::fwrite(data, 1, bytes, file_) != bytes)
    throw std::runtime_error(system_error("cannot write the checkpoint", temporary_));
  length_ += bytes;
}

void CheckpointWriter::add_view(std::string_view name, const void* data, std::size_t bytes) {
  if (!comm_.distributed()) {
    add(name, data, bytes);
    return;
  }
  add_header(name, data, bytes);
  if (bytes == 0) return;
  spans_.push_back({static_cast<const unsigned char*>(data), 0, bytes});
  mine_ += bytes;
}

void CheckpointWriter::add(std::string_view name, const void* data, std::size_t bytes) {
  add_header(name, data, bytes);
  put(data, bytes);
}

void CheckpointWriter::add_header(std::string_view name, const void* data, std::size_t bytes) {
  if (name.empty() || name.size() > max_name) throw std::logic_error("checkpoint section name of bad length");
  const std::uint32_t name_length = std::uint32_t(name.size());
  const std::uint64_t length = bytes, hash = hash_bytes(data, bytes);
  put(&name_length, sizeof name_length);
  put(name.data(), name.size());
  put(&length, sizeof length);
  put(&hash, sizeof hash);
  const auto* n = reinterpret_cast<const unsigned char*>(name.data());
  headers_.insert(headers_.end(), n, n + name.size());
  for (const std::uint64_t v : {length, hash}) {
    const auto* b = reinterpret_cast<const unsigned char*>(&v);
    headers_.insert(headers_.end(), b, b + 8);
  }
  ++sections_;
}

void CheckpointWriter::commit() {
  if (comm_.distributed()) {
    commit_ranks();
    return;
  }
  const std::uint64_t total = length_ + trailer_size, hash = hash_bytes(headers_.data(), headers_.size());
  put(tail_magic, sizeof tail_magic);
  put(&sections_, sizeof sections_);
  put(&total, sizeof total);
  put(&hash, sizeof hash);
  // On disk before it takes the name: a machine lost right after the rename keeps a whole file.
  if (std::fflush(file_) != 0 || ::fdatasync(fileno(file_)) != 0)
    throw std::runtime_error(system_error("cannot write the checkpoint", temporary_));
  const int closed = std::fclose(file_);
  file_ = nullptr;
  if (closed != 0) {
    std::remove(temporary_.c_str());
    throw std::runtime_error(system_error("cannot write the checkpoint", temporary_));
  }
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const std::string message = system_error("cannot rename the checkpoint to", path_);
    std::remove(temporary_.c_str());
    throw std::runtime_error(message);
  }
}

void CheckpointWriter::commit_ranks() {
  const MPI_Comm comm = comm_.comm;
  const auto ranks = std::size_t(comm_.size);
  // Where each rank's sections go: after the head, rank after rank.
  const std::uint64_t mine = mine_;
  std::vector<std::uint64_t> sizes(ranks);
  mpi::check(MPI_Allgather(&mine, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, comm),
             "MPI_Allgather of the checkpoint's parts");
  std::uint64_t at = sizeof head_magic + sizeof checkpoint_format, offset = 0;
  for (std::size_t r = 0; r < ranks; ++r) {
    if (int(r) == comm_.rank) offset = at;
    at += sizes[r];
  }
  const std::uint64_t total = at + trailer_size;
  std::uint64_t sections = 0;
  const std::vector<unsigned char> headers = gather_headers(comm_, headers_, sections_, sections);
  if (comm_.root()) std::remove(temporary_.c_str());  // MPI_MODE_CREATE keeps an old file's bytes
  mpi::check(MPI_Barrier(comm), "MPI_Barrier before the checkpoint");
  MPI_File file;
  if (MPI_File_open(comm, temporary_.c_str(), MPI_MODE_CREATE | MPI_MODE_WRONLY, MPI_INFO_NULL, &file) !=
      MPI_SUCCESS)
    throw std::runtime_error("cannot create the checkpoint " + temporary_ + " on every rank");
  const auto write = [&](std::uint64_t where, const unsigned char* data, std::uint64_t bytes) {
    constexpr std::uint64_t most = std::uint64_t(1) << 30;  // an int's count of bytes
    for (std::uint64_t done = 0; done < bytes;) {
      const std::uint64_t n = std::min(most, bytes - done);
      if (MPI_File_write_at(file, MPI_Offset(where + done), data + done, int(n), MPI_BYTE,
                            MPI_STATUS_IGNORE) != MPI_SUCCESS)
        throw std::runtime_error("cannot write the checkpoint " + temporary_);
      done += n;
    }
  };
  // This rank's spans (its headers and copied sections in the region, the viewed
  // sections where they lie) in one write: an hindexed type of their addresses.
  std::vector<int> lengths;
  std::vector<MPI_Aint> addresses;
  for (const Span& span : spans_) {
    const unsigned char* data = span.external != nullptr ? span.external : region_.data() + span.at;
    constexpr std::uint64_t most = std::uint64_t(1) << 30;
    for (std::uint64_t done = 0; done < span.bytes; done += most) {
      MPI_Aint address;
      MPI_Get_address(data + done, &address);
      addresses.push_back(address);
      lengths.push_back(int(std::min(most, span.bytes - done)));
    }
  }
  MPI_Datatype spans;
  MPI_Type_create_hindexed(int(lengths.size()), lengths.data(), addresses.data(), MPI_BYTE, &spans);
  MPI_Type_commit(&spans);
  const int written =
      lengths.empty() ? MPI_SUCCESS
                      : MPI_File_write_at(file, MPI_Offset(offset), MPI_BOTTOM, 1, spans, MPI_STATUS_IGNORE);
  MPI_Type_free(&spans);
  if (written != MPI_SUCCESS) throw std::runtime_error("cannot write the checkpoint " + temporary_);
  if (comm_.root()) {
    unsigned char head[sizeof head_magic + sizeof checkpoint_format];
    std::memcpy(head, head_magic, sizeof head_magic);
    std::memcpy(head + sizeof head_magic, &checkpoint_format, sizeof checkpoint_format);
    write(0, head, sizeof head);
    unsigned char trailer[trailer_size];
    const std::uint64_t hash = hash_bytes(headers.data(), headers.size());
    std::memcpy(trailer, tail_magic, sizeof tail_magic);
    std::memcpy(trailer + 8, &sections, 8);
    std::memcpy(trailer + 16, &total, 8);
    std::memcpy(trailer + 24, &hash, 8);
    write(total - trailer_size, trailer, trailer_size);
  }
  // On disk, from every rank, before it takes the name.
  const bool synced = MPI_File_sync(file) == MPI_SUCCESS;
  const bool closed = MPI_File_close(&file) == MPI_SUCCESS;
  if (!synced || !closed) throw std::runtime_error("cannot write the checkpoint " + temporary_);
  length_ = total;
  region_ = {};
  spans_.clear();
  mine_ = 0;
  if (comm_.root() && std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const std::string message = system_error("cannot rename the checkpoint to", path_);
    std::remove(temporary_.c_str());
    throw std::runtime_error(message);
  }
  mpi::check(MPI_Barrier(comm), "MPI_Barrier after the checkpoint");  // the name is there for every rank
}

// ---------------------------------------------------------------------------

CheckpointReader::CheckpointReader(const std::string& path) : path_(path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    throw InputError("the checkpoint " + path + " is not a file");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError("cannot read the checkpoint " + path + ": " + std::strerror(errno));
  const std::streamoff size = in.tellg();
  if (size < 0) throw InputError("cannot read the checkpoint " + path);
  data_.resize(std::size_t(std::max<std::streamoff>(size, 0)));
  in.seekg(0);
  if (!data_.empty() && !in.read(reinterpret_cast<char*>(data_.data()), size))
    throw InputError("cannot read the checkpoint " + path);
  parse();
}

CheckpointReader::CheckpointReader(std::vector<unsigned char> bytes, std::string path)
    : path_(std::move(path)), data_(std::move(bytes)) {
  parse();
}

void CheckpointReader::fail(const std::string& what) const {
  throw InputError("the checkpoint " + path_ + " " + what);
}

void CheckpointReader::parse() {
  const std::size_t n = data_.size();
  const unsigned char* p = data_.data();
  if (n < sizeof head_magic + 4 + trailer_size || std::memcmp(p, head_magic, sizeof head_magic) != 0)
    fail("is not an exdyn checkpoint (or is truncated to " + std::to_string(n) + " bytes)");
  std::uint32_t format = 0;
  std::memcpy(&format, p + 8, 4);
  if (format != checkpoint_format)
    fail("has format " + std::to_string(format) + "; this exdyn reads format " +
         std::to_string(checkpoint_format));
  const unsigned char* trailer = p + n - trailer_size;
  std::uint64_t count = 0, total = 0, headers_hash = 0;
  std::memcpy(&count, trailer + 8, 8);
  std::memcpy(&total, trailer + 16, 8);
  std::memcpy(&headers_hash, trailer + 24, 8);
  if (std::memcmp(trailer, tail_magic, sizeof tail_magic) != 0 || total != n)
    fail("is truncated or damaged: its end is not a checkpoint's end (" + std::to_string(n) + " bytes)");
  std::vector<unsigned char> headers;
  std::size_t at = 12;
  const std::size_t end = n - trailer_size;
  for (std::uint64_t s = 0; s < count; ++s) {
    std::uint32_t name_length = 0;
    std::uint64_t length = 0, hash = 0;
    if (end - at < 4) fail("is damaged: section " + std::to_string(s) + " runs past the end");
    std::memcpy(&name_length, p + at, 4);
    at += 4;
    if (name_length == 0 || name_length > max_name || end - at < std::size_t(name_length) + 16)
      fail("is damaged: section " + std::to_string(s) + " has a bad header");
    const std::string_view name(reinterpret_cast<const char*>(p + at), name_length);
    at += name_length;
    std::memcpy(&length, p + at, 8);
    std::memcpy(&hash, p + at + 8, 8);
    at += 16;
    if (length > end - at) fail("is damaged: section '" + std::string(name) + "' runs past the end");
    if (hash_bytes(p + at, std::size_t(length)) != hash)
      fail("is damaged: section '" + std::string(name) + "' does not match its checksum");
    headers.insert(headers.end(), name.begin(), name.end());
    for (const std::uint64_t v : {length, hash}) {
      const auto* b = reinterpret_cast<const unsigned char*>(&v);
      headers.insert(headers.end(), b, b + 8);
    }
    if (!sections_.emplace(std::string(name), std::string_view(reinterpret_cast<const char*>(p + at), length))
             .second)
      fail("is damaged: section '" + std::string(name) + "' appears twice");
    at += std::size_t(length);
  }
  if (at != end || hash_bytes(headers.data(), headers.size()) != headers_hash)
    fail("is damaged: its sections do not match the checksum of its end");
  join_pieces();
}

// Sections written in pieces (NAME#0, NAME#1, ...) joined into NAME, in the order of
// their numbers, which must run from 0 without a gap.
void CheckpointReader::join_pieces() {
  std::map<std::string, std::map<std::uint64_t, std::string_view>> pieces;
  for (auto it = sections_.begin(); it != sections_.end();) {
    const std::size_t hash_at = it->first.rfind('#');
    if (hash_at == std::string::npos) {
      ++it;
      continue;
    }
    const std::string base = it->first.substr(0, hash_at), digits = it->first.substr(hash_at + 1);
    std::uint64_t k = 0;
    const auto [end, status] = std::from_chars(digits.data(), digits.data() + digits.size(), k);
    if (base.empty() || digits.empty() || status != std::errc() || end != digits.data() + digits.size())
      fail("is damaged: section '" + it->first + "' is no piece of a section");
    pieces[base][k] = it->second;
    it = sections_.erase(it);
  }
  for (const auto& [base, parts] : pieces) {
    if (sections_.count(base) != 0) fail("is damaged: section '" + base + "' is whole and in pieces");
    std::string joined;
    std::uint64_t next = 0;
    for (const auto& [k, part] : parts) {
      if (k != next++) fail("is damaged: section '" + base + "' lacks piece " + std::to_string(next - 1));
      joined.append(part.data(), part.size());
    }
    joined_.push_back(std::move(joined));
    sections_.emplace(base, std::string_view(joined_.back()));
  }
}

std::string_view CheckpointReader::bytes(std::string_view name) const {
  const auto found = sections_.find(name);
  if (found == sections_.end()) fail("has no section '" + std::string(name) + "'");
  return found->second;
}

void CheckpointReader::check_length(std::string_view name, std::size_t bytes, std::size_t size,
                                    long expected) const {
  if (bytes % size != 0 || (expected >= 0 && bytes != std::size_t(expected) * size))
    fail("section '" + std::string(name) + "' has " + std::to_string(bytes) + " bytes, not " +
         (expected >= 0 ? std::to_string(expected) : std::string("a whole number of")) + " values of " +
         std::to_string(size) + " bytes: another model's checkpoint");
}

// ---------------------------------------------------------------------------

// The field sets as longs: from_step, count, the fields' numbers, per set.
void add_position(CheckpointWriter& file, const WrittenPosition& position) {
  std::vector<long> sets;
  for (const FieldSet& set : position.field_sets) {
    sets.push_back(set.from_step);
    sets.push_back(long(set.fields.size()));
    for (const input::OutputField field : set.fields) sets.push_back(long(field));
  }
  file.add("output/steps", position.steps);
  file.add("output/times", position.times);
  file.add_value("output/history_rows", position.history_rows);
  file.add("output/field_sets", sets);
}

WrittenPosition read_position(const CheckpointReader& file) {
  const auto bad = [&](const std::string& what) {
    return InputError("the checkpoint " + file.path() + " holds " + what);
  };
  WrittenPosition position;
  position.steps = file.values<long>("output/steps");
  position.times = file.values<double>("output/times", long(position.steps.size()));
  position.history_rows = file.value<std::uint64_t>("output/history_rows");
  for (std::size_t k = 1; k < position.steps.size(); ++k)
    if (!(position.steps[k] > position.steps[k - 1]) || !(position.times[k] > position.times[k - 1]))
      throw bad("written steps out of order");
  if (!position.steps.empty() && position.steps[0] < 0) throw bad("a negative step");
  const std::vector<long> sets = file.values<long>("output/field_sets");
  for (std::size_t k = 0; k + 1 < sets.size();) {
    FieldSet set{sets[k], {}};
    const long count = sets[k + 1];
    k += 2;
    if (count < 0 || std::size_t(count) > sets.size() - k) throw bad("a bad list of output fields");
    for (long f = 0; f < count; ++f, ++k) {
      if (sets[k] < 0 || std::size_t(sets[k]) >= input::all_output_fields.size())
        throw bad("an unknown output field");
      set.fields.push_back(input::OutputField(sets[k]));
    }
    position.field_sets.push_back(std::move(set));
  }
  if (position.field_sets.empty()) throw bad("no output fields");
  return position;
}

}  // namespace exdyn::output
