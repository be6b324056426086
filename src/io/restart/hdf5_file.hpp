// A small RAII layer over the HDF5 C API for restart dumps: groups, 1-D datasets of numbers and
// bytes, and scalar attributes. Only what the dump needs, with errors that name the file and the
// object so that a damaged dump gives a clear message instead of HDF5's error stack.
//
// Integrity: arrays are written chunked with the Fletcher-32 checksum filter and the file uses
// the HDF5 1.8+ object formats, whose metadata carry checksums too, so a flipped byte is caught
// when the dump is read (HDF5 User's Guide, "Datasets: Filters", H5Pset_fletcher32).
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace rf::io::h5 {

// Owns one HDF5 identifier and closes it with the matching H5*close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept;
  Handle& operator=(Handle&& other) noexcept;
  ~Handle();
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  void reset() noexcept;
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

// A group of an open file. Reading functions throw rf::InputError naming the file and the
// object's path when it is missing or of the wrong kind or size.
class Group {
 public:
  Group(Handle handle, std::string path, std::string file)
      : handle_(std::move(handle)), path_(std::move(path)), file_(std::move(file)) {}

  Group create_group(const std::string& name) const;
  Group group(const std::string& name) const;
  bool has(const std::string& name) const;
  const std::string& path() const { return path_; }

  // 1-D datasets.
  void write(const std::string& name, std::span<const double> values) const;
  void write(const std::string& name, std::span<const std::int32_t> values) const;
  void write(const std::string& name, std::span<const std::int64_t> values) const;
  void write(const std::string& name, std::span<const std::uint8_t> values) const;
  void write_text(const std::string& name, const std::string& text) const;  // as bytes
  std::vector<double> read_doubles(const std::string& name) const;
  std::vector<std::int32_t> read_int32(const std::string& name) const;
  std::vector<std::int64_t> read_int64(const std::string& name) const;
  std::vector<std::uint8_t> read_bytes(const std::string& name) const;
  std::string read_text(const std::string& name) const;
  // Number of elements of a dataset (throws when it is missing).
  std::size_t length(const std::string& name) const;

  // Scalar attributes of this group.
  void set(const std::string& name, double value) const;
  void set(const std::string& name, std::int64_t value) const;
  void set(const std::string& name, const std::string& value) const;
  double get_double(const std::string& name) const;
  std::int64_t get_int(const std::string& name) const;
  std::string get_string(const std::string& name) const;
  bool has_attribute(const std::string& name) const;

  // An rf::InputError about this group's object `name` (for checks made by the caller).
  [[noreturn]] void fail(const std::string& name, const std::string& message) const;

 private:
  std::string child_path(const std::string& name) const;
  void write_array(const std::string& name, hid_t type, const void* data, std::size_t n) const;
  template <class T>
  std::vector<T> read_array(const std::string& name, hid_t type) const;
  void check_storage(hid_t set, const std::string& name, std::size_t n,
                     std::size_t entry_bytes) const;
  Handle open_attribute(const std::string& name) const;

  Handle handle_;
  std::string path_;
  std::string file_;
};

class File {
 public:
  // Creates (truncates) `path` for writing. Throws std::runtime_error when it cannot.
  static File create(const std::filesystem::path& path);
  // Opens `path` read-only. Throws rf::InputError when it does not exist or is not a readable
  // HDF5 file.
  static File open(const std::filesystem::path& path);

  Group root() const;
  // Writes everything to disk and closes the file (errors surface here, not in a destructor).
  void close();

 private:
  File(Handle handle, std::string name) : handle_(std::move(handle)), name_(std::move(name)) {}
  Handle handle_;
  std::string name_;
};

}  // namespace rf::io::h5
