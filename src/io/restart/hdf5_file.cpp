#include "io/restart/hdf5_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "model/error.hpp"

namespace rf::io::h5 {

namespace {

// Elements per chunk: 64 Ki doubles is 512 KiB, large enough that chunk bookkeeping costs
// nothing next to the data and small enough that a checksum failure names a useful region.
constexpr hsize_t kChunkElements = hsize_t{1} << 16;

// HDF5 prints its error stack to stderr by default; the dump code reports its own errors.
void silence_hdf5() {
  static const bool silenced = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)silenced;
}

[[noreturn]] void write_failed(const std::string& file, const std::string& what) {
  throw std::runtime_error(fmt::format("cannot write restart dump '{}': {}", file, what));
}

}  // namespace

Handle::Handle(Handle&& other) noexcept
    : id_(std::exchange(other.id_, -1)), closer_(other.closer_) {}

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    reset();
    id_ = std::exchange(other.id_, -1);
    closer_ = other.closer_;
  }
  return *this;
}

Handle::~Handle() {
  reset();
}

void Handle::reset() noexcept {
  if (id_ >= 0 && closer_ != nullptr) closer_(id_);
  id_ = -1;
}

std::string Group::child_path(const std::string& name) const {
  return path_ == "/" ? "/" + name : path_ + "/" + name;
}

void Group::fail(const std::string& name, const std::string& message) const {
  throw InputError({file_, 0, "", 0, ""},
                   fmt::format("restart dump object {}: {}", child_path(name), message));
}

Group Group::create_group(const std::string& name) const {
  // No modification times in object headers: equal states give byte-equal dumps.
  Handle properties(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
  H5Pset_obj_track_times(properties.get(), false);
  Handle g(H5Gcreate2(handle_.get(), name.c_str(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
           H5Gclose);
  if (!g.valid()) write_failed(file_, "cannot create group " + child_path(name));
  return Group(std::move(g), child_path(name), file_);
}

bool Group::has(const std::string& name) const {
  return H5Lexists(handle_.get(), name.c_str(), H5P_DEFAULT) > 0;
}

Group Group::group(const std::string& name) const {
  if (!has(name)) fail(name, "is missing (the dump is damaged or was not written by RigidFlex)");
  Handle g(H5Gopen2(handle_.get(), name.c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail(name, "is not a readable group (the dump is damaged)");
  return Group(std::move(g), child_path(name), file_);
}

void Group::write_array(const std::string& name, hid_t type, const void* data,
                        std::size_t n) const {
  const hsize_t dims[1] = {static_cast<hsize_t>(n)};
  Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
  Handle properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (!space.valid() || !properties.valid()) write_failed(file_, "out of HDF5 resources");
  H5Pset_obj_track_times(properties.get(), false);
  if (n > 0) {
    const hsize_t chunk[1] = {std::min<hsize_t>(dims[0], kChunkElements)};
    if (H5Pset_chunk(properties.get(), 1, chunk) < 0 || H5Pset_fletcher32(properties.get()) < 0) {
      write_failed(file_, "cannot set up checksummed storage for " + child_path(name));
    }
  }
  Handle set(H5Dcreate2(handle_.get(), name.c_str(), type, space.get(), H5P_DEFAULT,
                        properties.get(), H5P_DEFAULT),
             H5Dclose);
  if (!set.valid()) write_failed(file_, "cannot create dataset " + child_path(name));
  if (n > 0 && H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    write_failed(file_, "cannot write dataset " + child_path(name));
  }
}

void Group::write(const std::string& name, std::span<const double> values) const {
  write_array(name, H5T_NATIVE_DOUBLE, values.data(), values.size());
}
void Group::write(const std::string& name, std::span<const std::int32_t> values) const {
  write_array(name, H5T_NATIVE_INT32, values.data(), values.size());
}
void Group::write(const std::string& name, std::span<const std::int64_t> values) const {
  write_array(name, H5T_NATIVE_INT64, values.data(), values.size());
}
void Group::write(const std::string& name, std::span<const std::uint8_t> values) const {
  write_array(name, H5T_NATIVE_UINT8, values.data(), values.size());
}
void Group::write_text(const std::string& name, const std::string& text) const {
  write_array(name, H5T_NATIVE_UINT8, text.data(), text.size());
}

std::size_t Group::length(const std::string& name) const {
  if (!has(name)) fail(name, "is missing (the dump is damaged or was not written by RigidFlex)");
  Handle set(H5Dopen2(handle_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!set.valid()) fail(name, "is not a readable dataset (the dump is damaged)");
  Handle space(H5Dget_space(set.get()), H5Sclose);
  if (!space.valid() || H5Sget_simple_extent_ndims(space.get()) != 1) {
    fail(name, "is not a one-dimensional array (the dump is damaged)");
  }
  hsize_t dims[1] = {0};
  H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  return static_cast<std::size_t>(dims[0]);
}

// A damaged file can claim any extent, chunk shape or chunk size, and libhdf5 allocates what
// the file claims before a checksum is verified (a fuzzed dump made it ask for 4.28 GB inside
// H5Dread). So the claims are checked before anything is allocated: the data fits in the file;
// a contiguous dataset is stored in exactly its bytes; a chunked one has chunks of at most
// 2^24 entries, each stored in at most its bytes plus the filters' overhead (exactly its bytes
// plus 4 for what write_array() makes: Fletcher-32 alone). Files written by other HDF5 tools
// (h5py's contiguous or compressed datasets, e.g. a mode database made elsewhere) still pass.
void Group::check_storage(hid_t set, const std::string& name, std::size_t n,
                          std::size_t entry_bytes) const {
  Handle file(H5Iget_file_id(set), H5Fclose);
  hsize_t file_bytes = 0;
  if (!file.valid() || H5Fget_filesize(file.get(), &file_bytes) < 0 ||
      n > file_bytes / entry_bytes) {
    fail(name, fmt::format("claims {} entries, more than the file holds (the dump is damaged)", n));
  }
  const auto damaged = [&] { fail(name, "has a damaged storage layout (the file is damaged)"); };
  Handle properties(H5Dget_create_plist(set), H5Pclose);
  if (!properties.valid()) damaged();
  const H5D_layout_t layout = H5Pget_layout(properties.get());
  const int filters = H5Pget_nfilters(properties.get());
  if (layout == H5D_CONTIGUOUS) {
    if (filters != 0 || H5Dget_storage_size(set) != n * entry_bytes) damaged();
    return;
  }
  if (layout == H5D_COMPACT) {
    if (filters != 0 || n * entry_bytes > (hsize_t{1} << 16)) damaged();
    return;
  }
  constexpr hsize_t kMaxChunkEntries = hsize_t{1} << 24;
  hsize_t chunk[1] = {0};
  if (layout != H5D_CHUNKED || H5Pget_chunk(properties.get(), 1, chunk) != 1 || chunk[0] == 0 ||
      chunk[0] > kMaxChunkEntries || filters < 0) {
    damaged();
  }
  bool fletcher_only = filters == 1;
  for (int k = 0; k < filters && fletcher_only; ++k) {
    unsigned flags = 0;
    std::size_t values = 0;
    fletcher_only = H5Pget_filter2(properties.get(), static_cast<unsigned>(k), &flags, &values,
                                   nullptr, 0, nullptr, nullptr) == H5Z_FILTER_FLETCHER32;
  }
  const hsize_t chunk_bytes = chunk[0] * entry_bytes;
  // Compressors may expand incompressible data slightly (deflate: ~0.1 % plus a few bytes).
  const hsize_t largest = filters == 0 ? chunk_bytes : chunk_bytes + chunk_bytes / 64 + 1024;
  for (hsize_t start = 0; start < n; start += chunk[0]) {
    const hsize_t offset[1] = {start};
    hsize_t stored = 0;  // edge chunks are stored whole, like the others
    if (H5Dget_chunk_storage_size(set, offset, &stored) < 0 ||
        (fletcher_only ? stored != chunk_bytes + 4 : stored > largest)) {
      fail(name, fmt::format("chunk at entry {} has a damaged size (the file is damaged)", start));
    }
  }
}

template <class T>
std::vector<T> Group::read_array(const std::string& name, hid_t type) const {
  const std::size_t n = length(name);
  Handle set(H5Dopen2(handle_.get(), name.c_str(), H5P_DEFAULT), H5Dclose);
  Handle stored_type(H5Dget_type(set.get()), H5Tclose);
  if (!stored_type.valid() || H5Tget_class(stored_type.get()) != H5Tget_class(type) ||
      H5Tget_size(stored_type.get()) != H5Tget_size(type)) {
    fail(name, "holds numbers of another type than this version writes (the dump is damaged)");
  }
  if (n > 0) check_storage(set.get(), name, n, sizeof(T));
  std::vector<T> out(n);
  if (n > 0 && H5Dread(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    fail(name,
         "cannot be read: its checksum does not match or the file is truncated (the dump "
         "is damaged)");
  }
  return out;
}

std::vector<double> Group::read_doubles(const std::string& name) const {
  return read_array<double>(name, H5T_NATIVE_DOUBLE);
}
std::vector<std::int32_t> Group::read_int32(const std::string& name) const {
  return read_array<std::int32_t>(name, H5T_NATIVE_INT32);
}
std::vector<std::int64_t> Group::read_int64(const std::string& name) const {
  return read_array<std::int64_t>(name, H5T_NATIVE_INT64);
}
std::vector<std::uint8_t> Group::read_bytes(const std::string& name) const {
  return read_array<std::uint8_t>(name, H5T_NATIVE_UINT8);
}
std::string Group::read_text(const std::string& name) const {
  const std::vector<std::uint8_t> bytes = read_bytes(name);
  return std::string(bytes.begin(), bytes.end());
}

namespace {

void write_attribute(hid_t object, const std::string& name, hid_t type, const void* value,
                     const std::string& file, const std::string& path) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
  Handle attribute(H5Acreate2(object, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose);
  if (!attribute.valid() || H5Awrite(attribute.get(), type, value) < 0) {
    write_failed(file, fmt::format("cannot write attribute {} of {}", name, path));
  }
}

}  // namespace

void Group::set(const std::string& name, double value) const {
  write_attribute(handle_.get(), name, H5T_NATIVE_DOUBLE, &value, file_, path_);
}

void Group::set(const std::string& name, std::int64_t value) const {
  write_attribute(handle_.get(), name, H5T_NATIVE_INT64, &value, file_, path_);
}

void Group::set(const std::string& name, const std::string& value) const {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  // A fixed-length string of the exact size (at least 1: HDF5 refuses size 0).
  H5Tset_size(type.get(), std::max<std::size_t>(1, value.size()));
  H5Tset_strpad(type.get(), H5T_STR_NULLPAD);
  std::string padded = value;
  if (padded.empty()) padded.push_back('\0');
  write_attribute(handle_.get(), name, type.get(), padded.data(), file_, path_);
}

bool Group::has_attribute(const std::string& name) const {
  return H5Aexists(handle_.get(), name.c_str()) > 0;
}

Handle Group::open_attribute(const std::string& name) const {
  if (!has_attribute(name)) {
    throw InputError({file_, 0, "", 0, ""},
                     fmt::format("restart dump: attribute {} of {} is missing (the dump is "
                                 "damaged or was not written by RigidFlex)",
                                 name, path_));
  }
  Handle attribute(H5Aopen(handle_.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!attribute.valid()) {
    throw InputError({file_, 0, "", 0, ""},
                     fmt::format("restart dump: attribute {} of {} cannot be read (the dump is "
                                 "damaged)",
                                 name, path_));
  }
  return attribute;
}

double Group::get_double(const std::string& name) const {
  const Handle attribute = open_attribute(name);
  Handle type(H5Aget_type(attribute.get()), H5Tclose);
  double value = 0.0;
  if (H5Tget_class(type.get()) != H5T_FLOAT ||
      H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) < 0) {
    throw InputError({file_, 0, "", 0, ""},
                     fmt::format("restart dump: attribute {} of {} is not a number", name, path_));
  }
  return value;
}

std::int64_t Group::get_int(const std::string& name) const {
  const Handle attribute = open_attribute(name);
  Handle type(H5Aget_type(attribute.get()), H5Tclose);
  std::int64_t value = 0;
  if (H5Tget_class(type.get()) != H5T_INTEGER ||
      H5Aread(attribute.get(), H5T_NATIVE_INT64, &value) < 0) {
    throw InputError(
        {file_, 0, "", 0, ""},
        fmt::format("restart dump: attribute {} of {} is not an integer", name, path_));
  }
  return value;
}

std::string Group::get_string(const std::string& name) const {
  const Handle attribute = open_attribute(name);
  Handle type(H5Aget_type(attribute.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0) {
    throw InputError({file_, 0, "", 0, ""},
                     fmt::format("restart dump: attribute {} of {} is not a text", name, path_));
  }
  const std::size_t size = H5Tget_size(type.get());
  std::string value(size, '\0');
  if (H5Aread(attribute.get(), type.get(), value.data()) < 0) {
    throw InputError({file_, 0, "", 0, ""},
                     fmt::format("restart dump: attribute {} of {} cannot be read", name, path_));
  }
  const auto end = value.find('\0');
  if (end != std::string::npos) value.resize(end);
  return value;
}

File File::create(const std::filesystem::path& path) {
  silence_hdf5();
  Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  Handle creation(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
  H5Pset_obj_track_times(creation.get(), false);  // the root group
  // 1.8 object formats and later: checksummed object headers and superblock.
  H5Pset_libver_bounds(access.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST);
  Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, creation.get(), access.get()), H5Fclose);
  if (!file.valid()) write_failed(path.string(), "the file cannot be created");
  return File(std::move(file), path.string());
}

File File::open(const std::filesystem::path& path) {
  silence_hdf5();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError({path.string(), 0, "", 0, ""}, "the restart dump does not exist");
  }
#if H5_VERSION_GE(1, 12, 0)
  const htri_t is_hdf5 = H5Fis_accessible(path.c_str(), H5P_DEFAULT);
#else
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
#endif
  if (is_hdf5 <= 0) {
    throw InputError({path.string(), 0, "", 0, ""},
                     "not a restart dump: the file is not an HDF5 file, or it is truncated or "
                     "damaged");
  }
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!file.valid()) {
    throw InputError({path.string(), 0, "", 0, ""},
                     "the restart dump cannot be opened: it is truncated or damaged");
  }
  return File(std::move(file), path.string());
}

Group File::root() const {
  Handle g(H5Gopen2(handle_.get(), "/", H5P_DEFAULT), H5Gclose);
  if (!g.valid()) {
    throw InputError({name_, 0, "", 0, ""},
                     "the restart dump has no readable root group (the dump is damaged)");
  }
  return Group(std::move(g), "/", name_);
}

void File::close() {
  if (!handle_.valid()) return;
  if (H5Fflush(handle_.get(), H5F_SCOPE_GLOBAL) < 0) write_failed(name_, "flush failed");
  handle_ = Handle();
}

}  // namespace rf::io::h5
