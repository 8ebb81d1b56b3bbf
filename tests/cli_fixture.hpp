#pragma once
// The command-line test fixture: runs the wetroad binary in a scratch directory of its own and
// captures exit code, stdout and stderr (test_cli.cpp, test_cli_robustness.cpp).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "tests/scratch_dir.hpp"

namespace wr_test {

namespace fs = std::filesystem;

struct CliRun {
  int code;
  std::string out, err;
};

class Cli : public ScratchTest {
 protected:
  Cli() : ScratchTest("wetroad-cli-") {}

  CliRun run(const std::string& args) const {
    const std::string out = path("stdout.txt"), err = path("stderr.txt");
    // WETROAD_TEST_BIN runs the same checks against another build (e.g. an older one, to show
    // that a test fails without the fix it guards).
    const char* other = std::getenv("WETROAD_TEST_BIN");
    const std::string cmd = std::string(other ? other : WETROAD_BIN) + " " + args + " >" + out + " 2>" + err;
    const int status = std::system(cmd.c_str());
    CliRun r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
    fs::remove(out);
    fs::remove(err);
    return r;
  }

  static std::string slurp(const std::string& p) {
    std::ifstream f(p);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  }

  // Files in the scratch directory other than the inputs the test made.
  std::size_t count_files() const {
    std::size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir_)) n += e.is_regular_file();
    return n;
  }

  // Writes an HDF5 file with a float64 dataset of the given shape (chunked and never written
  // when `write` is false, so huge shapes cost nothing on disk) and optional dx.
  void make_h5(const std::string& name, const std::string& dataset, std::vector<hsize_t> dims,
               std::optional<double> dx, bool write = true, double fill = 1e-4) const {
    const hid_t f = H5Fcreate(path(name).c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    const hid_t space = H5Screate_simple(int(dims.size()), dims.data(), nullptr);
    const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
    if (!write) {
      std::vector<hsize_t> chunk(dims.size(), 16);
      H5Pset_chunk(dcpl, int(dims.size()), chunk.data());
    }
    const hid_t ds = H5Dcreate2(f, dataset.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    if (write) {
      hsize_t n = 1;
      for (auto d : dims) n *= d;
      std::vector<double> v(n);
      for (hsize_t i = 0; i < n; ++i) v[i] = std::isnan(fill) ? fill : fill * std::sin(0.37 * double(i));
      H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
    }
    if (dx) {
      const hid_t as = H5Screate(H5S_SCALAR);
      const hid_t a = H5Acreate2(ds, "dx", H5T_IEEE_F64LE, as, H5P_DEFAULT, H5P_DEFAULT);
      H5Awrite(a, H5T_NATIVE_DOUBLE, &*dx);
      H5Aclose(a);
      H5Sclose(as);
    }
    H5Dclose(ds);
    H5Pclose(dcpl);
    H5Sclose(space);
    H5Fclose(f);
  }

  // Bar 6: one line naming the file, exit code 2, no output file.
  void expect_bad_input(const std::string& file, const std::string& fragment) {
    const std::size_t before = count_files();
    const CliRun r = run("analyze " + file + " --json " + path("out.json") + " --out " + path("out.h5"));
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
    EXPECT_EQ(count_files(), before) << "an output file appeared";
  }

};

}  // namespace wr_test
