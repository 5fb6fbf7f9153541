// rhabel/materials/text_file.hpp: reading a user's text file (a master curve, a scene, a sweep, a
// profile) safely.
//
// A path given by a user may name anything: a directory (std::ifstream then throws from
// basic_filebuf::underflow), a device such as /dev/zero (read until memory runs out), a FIFO
// without a writer (blocks forever) or a file of gigabytes. read_text_file opens only regular files
// (and "-" as stdin when asked to), without blocking on a FIFO, and reads at most a given number of
// bytes; everything else is a std::invalid_argument whose message names the file and why.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace rhabel::materials {

/// The size limit of the text files rhabel reads from its users (master curves, scenes, sweeps,
/// profiles): 256 MiB. The largest realistic ones are a few MB (a profile of 10^5 samples is
/// ~4 MB); the limit bounds the memory a wrong path (a disk image, a log) can take before it is
/// refused. A sweep's own output, read back when resuming, is bounded by its row count instead
/// (cli/sweep_command.cpp).
inline constexpr std::size_t max_text_file_bytes = std::size_t{256} << 20;

/// The whole content of `path`, which must be a regular file of at most `max_bytes` bytes (or, with
/// `allow_stdin`, "-" for standard input, read with the same bound). `what` names the file in the
/// message of the std::invalid_argument thrown otherwise: "cannot read <what> '<path>': <why>"
/// (why: not found, a directory, not a regular file, larger than the limit, a NUL byte in the
/// name, a read error).
std::string read_text_file(const std::string& path, const std::string& what,
                           std::size_t max_bytes = max_text_file_bytes, bool allow_stdin = false);

/// `text` safe to echo inside a one-line message: control characters escaped as the command line
/// does (\n, \r, \t, \xHH), at most `max_bytes` bytes of it (then "...").
std::string printable(std::string_view text, std::size_t max_bytes);

/// `text` without a leading UTF-8 byte-order mark (EF BB BF), which spreadsheet programs write at
/// the start of a CSV file. The one rule of every CSV rhabel reads (master curves, profiles): a
/// mark at the very start is skipped, anywhere else it is an ordinary (invalid) character.
std::string_view without_bom(std::string_view text);

}  // namespace rhabel::materials
