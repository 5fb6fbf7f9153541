// materials/src/text_file.cpp: see rhabel/materials/text_file.hpp.
#include "rhabel/materials/text_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace rhabel::materials {
namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "it is a directory";
  if (S_ISFIFO(mode)) return "it is a FIFO (only regular files are read)";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "it is a device (only regular files are read)";
  if (S_ISSOCK(mode)) return "it is a socket (only regular files are read)";
  return "it is not a regular file";
}

// Reads fd to the end; more than max_bytes is refused as soon as it is read.
std::string read_bounded(int fd, std::size_t max_bytes, const std::string& fail_prefix) {
  std::string text;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::invalid_argument(fail_prefix + std::strerror(errno));
    }
    if (n == 0) return text;
    if (text.size() + static_cast<std::size_t>(n) > max_bytes) {
      throw std::invalid_argument(fail_prefix + "larger than the limit of " + std::to_string(max_bytes) + " bytes");
    }
    text.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace

std::string read_text_file(const std::string& path, const std::string& what, std::size_t max_bytes, bool allow_stdin) {
  const std::string prefix = "cannot read " + what + " '" + printable(path, 200) + "': ";
  if (path.find('\0') != std::string::npos) throw std::invalid_argument(prefix + "the name contains a NUL byte");
  if (allow_stdin && path == "-") return read_bounded(STDIN_FILENO, max_bytes, prefix);
  // O_NONBLOCK: opening a FIFO without a writer would block; it is refused below by fstat.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw std::invalid_argument(prefix + std::strerror(errno));
  struct fd_closer {
    int fd;
    ~fd_closer() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0) throw std::invalid_argument(prefix + std::strerror(errno));
  if (!S_ISREG(info.st_mode)) throw std::invalid_argument(prefix + kind_of(info.st_mode));
  if (static_cast<unsigned long long>(info.st_size) > max_bytes) {
    throw std::invalid_argument(prefix + "larger than the limit of " + std::to_string(max_bytes) + " bytes");
  }
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return read_bounded(fd, max_bytes, prefix);
}

std::string printable(std::string_view text, std::size_t max_bytes) {
  std::string out;
  for (const char c : text.substr(0, max_bytes)) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n' || c == '\r' || c == '\t') {
      out += c == '\n' ? "\\n" : c == '\r' ? "\\r" : "\\t";
    } else if (byte < 0x20 || byte == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", byte);
      out += buf;
    } else {
      out += c;
    }
  }
  if (text.size() > max_bytes) out += "...";
  return out;
}

std::string_view without_bom(std::string_view text) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  return text;
}

}  // namespace rhabel::materials
