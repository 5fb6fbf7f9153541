// scene/src/sweep_output.cpp: the resumable output file of a sweep (rhabel/scene/sweep.hpp,
// sweep_output).
#include "rhabel/scene/error.hpp"
#include "rhabel/scene/sweep.hpp"

#include "rhabel/materials/text_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace rhabel::scene {
namespace {

[[noreturn]] void write_failed(const std::string& file, const std::string& what) {
  throw write_error("sweep: --out " + one_line(file) + ": " + what);
}

void write_all(int fd, const std::string& text, const std::string& file) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      write_failed(file, std::strerror(errno));
    }
    done += static_cast<std::size_t>(n);
  }
}

// The longest line a row can have when resuming: its numbers take < 30 bytes a column and its
// message is one line of a few hundred bytes; 16 KiB leaves room for long string values.
constexpr std::size_t max_row_bytes = 16384;

struct existing_rows {
  std::map<std::size_t, std::string> lines;  // row -> whole line (with '\n')
  std::size_t keep_bytes = 0;                 // length of the complete lines (a partial tail is cut)
  bool has_header = false;
};

// The solve options a row's line records (row_options' text, from `at`), as "tolerance 1e-12,
// acceptance 1e-06" for a message (the default acceptance as "default").
std::string options_named(const sweep_spec& sweep, row_format format, const std::string& line, std::size_t at) {
  const auto columns = row_columns(sweep);
  const std::size_t first = 1 + sweep.axes.size();
  std::string out;
  std::size_t pos = at;
  for (std::size_t j = first; j < columns.size() && columns[j] != "status"; ++j) {
    if (format == row_format::jsonl) pos = line.find(':', pos) + 1;  // past "name":
    if (pos == 0 || pos > line.size()) break;
    const std::size_t end = std::min(line.find(',', pos), line.size());
    // (a hand-edited line may hold anything there: one line, at most 40 characters of it)
    std::string value = one_line(line.substr(pos, std::min<std::size_t>(end - pos, 40)));
    if (value.empty() || value == "null") value = "default";
    out += (out.empty() ? "" : ", ") + columns[j] + " " + value;
    pos = end + 1;
  }
  return out;
}

// This sweep's CSV header without the option columns (row_options', between the swept values and
// the status): that of a file written before rows recorded their solve options, which is refused
// by name, not taken for another sweep's.
std::string header_without_options(const sweep_spec& sweep) {
  std::string line = header_line(sweep, row_format::csv);
  const auto columns = row_columns(sweep);
  for (std::size_t j = 1 + sweep.axes.size(); j < columns.size() && columns[j] != "status"; ++j) {
    const std::size_t at = line.find("," + columns[j] + ",");  // (option names need no quoting)
    if (at != std::string::npos) line.erase(at, 1 + columns[j].size());
  }
  return line;
}

[[noreturn]] void refuse_without_options(const std::string& file, const std::string& where) {
  throw input_error("sweep: --out " + one_line(file) + where +
                    " has no solve-option columns (tolerance, acceptance): it was written by an earlier rhabel, "
                    "and its rows cannot be resumed under known options: remove it or choose another name");
}

// Reads FILE if it exists: the header must be this sweep's, every complete line one of its rows
// solved under `options` (row_options' text).
existing_rows scan_existing(const sweep_spec& sweep, row_format format, const std::string& file,
                            const std::string& options) {
  existing_rows out;
  if (::access(file.c_str(), F_OK) != 0) return out;  // a new file
  std::string text;
  const std::string header = header_line(sweep, format);
  // A row is at most max_row_bytes, so this bound only stops a file that cannot be this sweep's.
  const std::size_t bound = std::max(materials::max_text_file_bytes, header.size() + sweep.rows * max_row_bytes);
  try {  // only a regular file, with a bound (/dev/full, a directory or a FIFO are refused)
    text = materials::read_text_file(file, "the existing output", bound);
  } catch (const std::invalid_argument& e) {
    throw input_error("sweep: --out " + one_line(file) + ": " + e.what());
  }
  std::size_t pos = 0, line_no = 0;
  if (!header.empty()) {
    if (text.empty()) return out;
    if (text.compare(0, header.size(), header) != 0) {
      if (header.compare(0, text.size(), text) == 0 && text.find('\n') == std::string::npos) return out;  // cut header
      if (text.compare(0, text.find('\n') + 1, header_without_options(sweep)) == 0) refuse_without_options(file, "");
      throw input_error("sweep: --out " + one_line(file) +
                        " exists with another header (from another sweep?): remove it or choose another name");
    }
    out.has_header = true;
    pos = header.size();
    line_no = 1;
  }
  out.keep_bytes = pos;
  while (pos < text.size()) {
    const auto end = text.find('\n', pos);
    if (end == std::string::npos) break;  // partial last line of a killed run: cut off
    ++line_no;
    const std::string line = text.substr(pos, end + 1 - pos);
    pos = end + 1;
    out.keep_bytes = pos;
    std::size_t row = 0;
    const std::size_t skip = format == row_format::csv ? 0 : 7;  // {"row":
    const char* digits = line.c_str() + std::min(skip, line.size());
    char* stop = nullptr;
    errno = 0;
    row = std::strtoull(digits, &stop, 10);
    const bool numbered = stop != digits && errno == 0 && row < sweep.rows;
    const std::string prefix = numbered ? row_prefix(sweep, row, format) : std::string();
    if (numbered && line.compare(0, prefix.size(), prefix) == 0) {
      // A row whose status follows its swept values: written without the option columns.
      if (format == row_format::jsonl && std::string_view(line).substr(prefix.size()).starts_with("\"status\":"))
        refuse_without_options(file, " line " + std::to_string(line_no));
      // This sweep's row, unless torn (a killed writer, a disk that filled up): then it is dropped
      // and solved again, never copied to the result.
      if (!is_complete_row(sweep, format, line)) continue;
      if (line.compare(prefix.size(), options.size(), options) != 0) {
        // Solved under other options: resuming would mix two sets of rows under one bar.
        throw input_error("sweep: --out " + one_line(file) + " line " + std::to_string(line_no) + " was solved with " +
                          options_named(sweep, format, line, prefix.size()) + ", this run asks " +
                          options_named(sweep, format, prefix + options, prefix.size()) +
                          ": rerun with those options, or remove the file or choose another name");
      }
      out.lines.emplace(row, line);  // a duplicate keeps the first
      continue;
    }
    // A line cut short inside its row's own prefix (or inside {"row": before the number) is torn
    // too; anything else is foreign.
    const std::string start = numbered ? prefix : std::string(format == row_format::csv ? "" : "{\"row\":");
    const std::size_t kept = line.size() - 1;  // without its '\n'
    if (kept < start.size() && start.compare(0, kept, line, 0, kept) == 0) continue;
    throw input_error("sweep: --out " + one_line(file) + " line " + std::to_string(line_no) +
                      " is not a row of this sweep (another sweep's file?): remove it or choose another name");
  }
  return out;
}

bool status_ok(const std::string& line, std::size_t prefix, row_format format) {
  const std::string want = format == row_format::csv ? "ok," : "\"status\":\"ok\",";
  return line.compare(prefix, want.size(), want) == 0;
}

// Rewrites FILE in row order (temporary in the same directory, then rename).
void rewrite_sorted(const std::string& file, const std::string& header, const std::map<std::size_t, std::string>& lines) {
  std::string tmp = file + ".XXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) write_failed(file, std::string("cannot create a temporary next to it: ") + std::strerror(errno));
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  try {
    std::string text = header;
    for (const auto& [row, line] : lines) text += line;
    write_all(fd, text, file);
    if (::fsync(fd) != 0 && errno != EINVAL) write_failed(file, std::strerror(errno));
    if (::close(fd) != 0) write_failed(file, std::strerror(errno));
    if (std::rename(tmp.c_str(), file.c_str()) != 0) write_failed(file, std::strerror(errno));
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
}

}  // namespace

sweep_output::sweep_output(const sweep_spec& sweep, row_format format, std::string file, const run_request& request)
    : sweep_(sweep),
      format_(format),
      file_(std::move(file)),
      header_(header_line(sweep, format)),
      options_(row_options(sweep, format, request)) {
  existing_rows existing = scan_existing(sweep, format, file_, options_);
  lines_ = std::move(existing.lines);
  fd_ = ::open(file_.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0666);
  if (fd_ < 0) write_failed(file_, std::strerror(errno));
  try {
    if (::ftruncate(fd_, static_cast<off_t>(existing.keep_bytes)) != 0) write_failed(file_, std::strerror(errno));
    if (::lseek(fd_, 0, SEEK_END) < 0) write_failed(file_, std::strerror(errno));
    if (!existing.has_header) write_all(fd_, header_, file_);
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

sweep_output::~sweep_output() {
  if (fd_ >= 0) ::close(fd_);
}

std::vector<std::size_t> sweep_output::missing() const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < sweep_.rows; ++i)
    if (!lines_.count(i)) out.push_back(i);
  return out;
}

void sweep_output::append(finished_row&& row) {
  write_all(fd_, row.line, file_);
  lines_.emplace(row.row, std::move(row.line));
}

void sweep_output::finish() {
  if (lines_.size() != sweep_.rows) throw std::runtime_error("sweep: internal error: rows missing after the run");
  rewrite_sorted(file_, header_, lines_);
  ::close(fd_);
  fd_ = -1;
}

bool sweep_output::all_ok() const {
  for (const auto& [row, line] : lines_)
    if (!status_ok(line, row_prefix(sweep_, row, format_).size() + options_.size(), format_)) return false;
  return true;
}

}  // namespace rhabel::scene
