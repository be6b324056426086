#include "output/output_directory.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace rf::output {

namespace fs = std::filesystem;

namespace {

std::string reason(int error) {
  return std::generic_category().message(error);
}

// write(2) until done; EINTR retried, a short write of a full disk reported as ENOSPC.
bool write_all(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    if (w == 0) {
      errno = ENOSPC;
      return false;
    }
    data += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

}  // namespace

void prepare_output_directory(const fs::path& directory) {
  std::error_code ec;
  const fs::file_status status = fs::status(directory, ec);
  if (fs::exists(status) && !fs::is_directory(status)) {
    throw std::runtime_error(fmt::format(
        "cannot use output directory '{}': a file of that name is in its place (remove it or "
        "choose another directory with -o)",
        directory.string()));
  }
  if (!fs::exists(status)) {
    fs::create_directories(directory, ec);
    if (ec) {
      throw std::runtime_error(fmt::format("cannot create output directory '{}': {}",
                                           directory.string(), ec.message()));
    }
  }
  // Root ignores permission bits, so try a real write: it also finds a read-only or full file
  // system before the run starts rather than at its first output.
  const fs::path probe = directory / fmt::format(".rigidflex-write-test-{}", ::getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int error = errno;
    throw std::runtime_error(fmt::format("cannot write in output directory '{}': {}",
                                         directory.string(), reason(error)));
  }
  const bool written = write_all(fd, "\n", 1);
  const int error = errno;
  ::close(fd);
  ::unlink(probe.c_str());
  if (!written) {
    throw std::runtime_error(fmt::format("cannot write in output directory '{}': {}",
                                         directory.string(), reason(error)));
  }
}

void sync_file(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int error = errno;
    if (fd >= 0) ::close(fd);
    throw std::runtime_error(
        fmt::format("cannot write output file '{}': {}", path.string(), reason(error)));
  }
  ::close(fd);
}

void sync_directory_of(const fs::path& path) {
  fs::path directory = path.parent_path();
  if (directory.empty()) directory = ".";
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // the rename is done; a directory that cannot be opened cannot be synced
  ::fsync(fd);         // best effort: some file systems refuse fsync on directories
  ::close(fd);
}

void write_file_atomically(const fs::path& path, std::string_view bytes) {
  fs::path temporary = path;
  temporary += ".tmp";
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int error = errno;
    throw std::runtime_error(fmt::format("cannot open output file '{}' for writing: {}",
                                         temporary.string(), reason(error)));
  }
  bool ok = write_all(fd, bytes.data(), bytes.size());
  int error = errno;
  if (ok && ::fsync(fd) != 0) {
    ok = false;
    error = errno;
  }
  if (::close(fd) != 0 && ok) {
    ok = false;
    error = errno;
  }
  if (ok && std::rename(temporary.c_str(), path.c_str()) != 0) {
    ok = false;
    error = errno;
  }
  if (!ok) {
    ::unlink(temporary.c_str());
    throw std::runtime_error(
        fmt::format("cannot write output file '{}': {}", path.string(), reason(error)));
  }
  sync_directory_of(path);
}

}  // namespace rf::output
