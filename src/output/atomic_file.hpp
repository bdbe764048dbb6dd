// Replaces a text file atomically: the text goes to PATH.tmp, which is then
// rename()d over PATH (atomic on POSIX), so a concurrent reader (ParaView,
// a script) sees either the old or the new file, never a half-written one.
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

namespace exdyn::output {

// Writes the concatenation of `parts` to `path`. Throws std::runtime_error
// naming the path if writing or renaming fails; the temporary is removed then.
void write_file_atomically(const std::filesystem::path& path, const std::vector<std::string_view>& parts);

}  // namespace exdyn::output
