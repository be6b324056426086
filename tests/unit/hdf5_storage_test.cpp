// io::h5::Group::check_storage: the storage claims of a dataset are checked before libhdf5 reads
// it (a damaged chunk record once made H5Dread allocate 4.28 GB), without refusing the layouts
// other HDF5 tools write (h5py's default contiguous datasets, deflate-compressed chunks).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <string>
#include <vector>

#include "io/restart/hdf5_file.hpp"
#include "model/error.hpp"

namespace {

namespace h5 = rf::io::h5;

std::filesystem::path temporary(const char* name) {
  const auto dir = std::filesystem::temp_directory_path() / "rigidflex_hdf5_storage_test";
  std::filesystem::create_directories(dir);
  return dir / name;
}

// Writes `values` as dataset `name` with the layout set up by `configure` (on a dataset
// creation property list), the way a tool other than RigidFlex might.
template <class Configure>
void write_with_layout(hid_t file, const char* name, const std::vector<double>& values,
                       Configure configure) {
  const hsize_t dims[1] = {values.size()};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t properties = H5Pcreate(H5P_DATASET_CREATE);
  configure(properties);
  const hid_t set =
      H5Dcreate2(file, name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, properties, H5P_DEFAULT);
  ASSERT_GE(set, 0);
  ASSERT_GE(H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  H5Dclose(set);
  H5Pclose(properties);
  H5Sclose(space);
}

}  // namespace

TEST(Hdf5Storage, LayoutsOfOtherToolsAreReadBack) {
  const auto path = temporary("layouts.h5");
  std::vector<double> values(200000);  // more than one RigidFlex chunk (64 Ki entries)
  std::iota(values.begin(), values.end(), 0.5);
  {
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    write_with_layout(file, "contiguous", values, [](hid_t) {});
    write_with_layout(file, "deflate", values, [](hid_t p) {
      const hsize_t chunk[1] = {30000};
      H5Pset_chunk(p, 1, chunk);
      H5Pset_shuffle(p);
      H5Pset_deflate(p, 4);
    });
    write_with_layout(file, "chunked", values, [](hid_t p) {
      const hsize_t chunk[1] = {7000};
      H5Pset_chunk(p, 1, chunk);
    });
    H5Fclose(file);
  }
  const h5::File file = h5::File::open(path);
  for (const char* name : {"contiguous", "deflate", "chunked"}) {
    EXPECT_EQ(file.root().read_doubles(name), values) << name;
  }
}

TEST(Hdf5Storage, RigidFlexOwnDatasetsAreReadBack) {
  const auto path = temporary("own.h5");
  std::vector<double> values(150000);
  std::iota(values.begin(), values.end(), -3.0);
  {
    h5::File file = h5::File::create(path);
    file.root().write("x", std::span<const double>(values));
    file.close();
  }
  EXPECT_EQ(h5::File::open(path).root().read_doubles("x"), values);
}

// The fuzzing finding itself (tests/decks/fuzz/restart/hdf5_oom_chunk_read.h5) is replayed by
// FuzzRegression.RestartFindingsAreRefusedWithAnInputError; here a chunk record is damaged by
// hand: the stored size of the only chunk of a small dataset is overwritten in the file.
TEST(Hdf5Storage, DamagedChunkSizeIsRefusedBeforeReading) {
  const auto path = temporary("damaged.h5");
  const std::vector<double> values(1000, 1.25);
  {
    h5::File file = h5::File::create(path);
    file.root().write("x", std::span<const double>(values));
    file.close();
  }
  // The chunk is stored in 8004 bytes (entries + Fletcher-32). With the version-1.8 formats a
  // single-chunk dataset's chunk size sits in its layout message as a 32-bit value; find it and
  // make it claim 0xFEEDF00D bytes.
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::uint32_t stored = 8004;
  const std::string needle(reinterpret_cast<const char*>(&stored), 4);
  std::size_t at = bytes.find(needle);
  ASSERT_NE(at, std::string::npos);
  std::size_t hits = 0;
  for (std::size_t i = at; i != std::string::npos; i = bytes.find(needle, i + 1)) ++hits;
  if (hits != 1) GTEST_SKIP() << "the chunk size occurs " << hits << " times in the file";
  const std::uint32_t claimed = 0xFEEDF00Du;
  bytes.replace(at, 4, reinterpret_cast<const char*>(&claimed), 4);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
  }
  try {
    const h5::File file = h5::File::open(path);
    (void)file.root().read_doubles("x");
    FAIL() << "a damaged chunk size was read";
  } catch (const rf::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("chunk at entry 0 has a damaged size"), std::string::npos)
        << e.what();
  }
}
