// OutputSet (lib/io/output_set.hpp): outputs staged and committed together, inputs protected.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "lib/core/errors.hpp"
#include "lib/io/atomic_output.hpp"
#include "lib/io/output_set.hpp"
#include "tests/scratch_dir.hpp"

namespace wr {
namespace {

namespace fs = std::filesystem;

class OutputSetTest : public wr_test::ScratchTest {
 protected:
  OutputSetTest() : ScratchTest("wetroad-outputs-") {}
  std::size_t entries() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++n;
    return n;
  }
  static std::string read(const std::string& p) {
    std::ifstream f(p);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  }
};

TEST_F(OutputSetTest, NothingAppearsUntilCommitAndEverythingAfter) {
  OutputSet set;
  const std::string a = set.add("--json", path("a.json")), b = set.add("--out", path("b.txt"));
  const std::string charts = set.add_directory("--plots", path("charts"));
  write_text_atomically(a, "{}\n");
  write_text_atomically(b, "b\n");
  write_text_atomically(charts + "/mu.svg", "<svg/>\n");
  EXPECT_FALSE(fs::exists(path("a.json")));
  EXPECT_FALSE(fs::exists(path("b.txt")));
  EXPECT_FALSE(fs::exists(path("charts")));
  set.commit();
  EXPECT_EQ(read(path("a.json")), "{}\n");
  EXPECT_EQ(read(path("b.txt")), "b\n");
  EXPECT_EQ(read(path("charts/mu.svg")), "<svg/>\n");
  EXPECT_EQ(entries(), 3u) << "staging left behind";
}

TEST_F(OutputSetTest, AnErrorBeforeCommitLeavesNothingAndKeepsOldFiles) {
  std::ofstream(path("old.json")) << "old\n";
  {
    OutputSet set;
    write_text_atomically(set.add("--json", path("old.json")), "new\n");
    write_text_atomically(set.add("--out", path("b.txt")), "b\n");
  }  // no commit: a later output failed, or the run did
  EXPECT_EQ(read(path("old.json")), "old\n");
  EXPECT_FALSE(fs::exists(path("b.txt")));
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputSetTest, InputsAndRepeatedOutputsAreRefusedWhateverTheSpelling) {
  std::ofstream(path("in.h5")) << "data\n";
  fs::create_directories(path("sub"));
  fs::create_symlink(path("in.h5"), path("link.h5"));
  OutputSet set;
  set.input(path("in.h5"));
  EXPECT_THROW(set.add("--out", path("in.h5")), InputError);
  EXPECT_THROW(set.add("--out", path("sub/../in.h5")), InputError);
  EXPECT_THROW(set.add("--out", path("link.h5")), InputError);
  set.add("--json", path("x.json"));
  EXPECT_THROW(set.add("--csv", path("./x.json")), InputError);
  EXPECT_THROW(set.add("--out", path("sub")), InputError);                 // a directory
  EXPECT_THROW(set.add("--out", path("missing/x.h5")), InputError);        // no such directory
  EXPECT_THROW(set.add_directory("--plots", path("in.h5/charts")), InputError);  // under a file
  EXPECT_EQ(read(path("in.h5")), "data\n");
  EXPECT_TRUE(same_file(path("in.h5"), path("sub/../link.h5")));
  EXPECT_FALSE(same_file(path("in.h5"), path("x.json")));
}

}  // namespace
}  // namespace wr
