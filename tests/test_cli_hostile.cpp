// End-to-end, issue 54 ("hostile inputs, round three"): one test per class of defect, each
// driven by the class rather than its single reproducer where a table can cover it.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/types.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "lib/core/content_hash.hpp"
#include "lib/io/hdf5_file.hpp"
#include "tests/cli_fixture.hpp"

namespace {

using namespace wr_test;
namespace fs = std::filesystem;

class Hostile : public Cli {
 protected:
  void SetUp() override {
    Cli::SetUp();
    ASSERT_EQ(run("synth --size 16 --dx 1.875e-3 --h0 1e-4 --seed 3 -q -o " + path("a.h5")).code, 0);
    ASSERT_EQ(run("synth --size 16 --dx 1.875e-3 --h0 1e-4 --seed 4 -q -o " + path("b.h5")).code, 0);
  }

  // Exit 2 with one line on stderr holding `needle`.
  void expect_one_line(const std::string& args, const std::string& needle, int code = 2) {
    const CliRun r = run(args);
    EXPECT_EQ(r.code, code) << args << "\n" << r.out << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(r.out.find("error"), std::string::npos) << args << ": an error on stdout\n" << r.out;
  }

  // Adds a float64 attribute to a dataset of a file made by make_h5.
  void set_attr(const std::string& file, const std::string& dataset, const std::string& name, double value) const {
    const hid_t f = H5Fopen(path(file).c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    const hid_t ds = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT);
    const hid_t sp = H5Screate(H5S_SCALAR);
    const hid_t at = H5Acreate2(ds, name.c_str(), H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(at, H5T_NATIVE_DOUBLE, &value);
    H5Aclose(at);
    H5Sclose(sp);
    H5Dclose(ds);
    H5Fclose(f);
  }

  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string n = e.path().filename().string();
      if (n != "stdout.txt" && n != "stderr.txt") names.push_back(n);
    }
    std::sort(names.begin(), names.end());
    return names;
  }
};

// ---- class 1: every input of every command is an input to the output check -------------------

struct FileOption {
  std::string name;  // "--compound", or a positional's name
  std::string type;  // FILE, OUTPUT or FOLDER
  bool required = false;
  bool positional() const { return name[0] != '-'; }
};

// The file options of a (sub)command as its --help lists them ("--json OUTPUT", "surface FILE
// REQUIRED"): the same marks the binary's own check reads, so a new option is covered unasked.
std::vector<FileOption> file_options(const std::string& help) {
  std::vector<FileOption> out;
  std::istringstream in(help);
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    std::vector<std::string> tok;
    for (std::string t; ls >> t && tok.size() < 5;) tok.push_back(t);
    if (tok.size() >= 2) tok[1] = tok[1].substr(0, tok[1].find(':'));  // "FILE:FILE": a validator's suffix
    if (tok.size() < 2 || (tok[1] != "FILE" && tok[1] != "OUTPUT" && tok[1] != "FOLDER")) continue;
    FileOption o;
    o.name = tok[0].substr(tok[0].rfind(',') == std::string::npos ? 0 : tok[0].rfind(',') + 1);
    o.type = tok[1];
    o.required = std::find(tok.begin() + 2, tok.end(), "REQUIRED") != tok.end();
    out.push_back(o);
  }
  return out;
}

TEST_F(Hostile, Class1_NoOutputOfAnyCommandMayBeAnyOfItsInputs) {
  // Each command with what it needs to parse beyond its file options (the check runs before any work).
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"synth", "-q"},
      {"analyze", ""},
      {"fill", "--limit"},
      {"friction", ""},
      {"flow", ""},
      {"compound", ""},
      {"contact", "--model spectral --uz 1e-5"},
      {"sweep-coverage", "--model hysteresis --coverages 0"},
      {"sweep-roughness", "--model hysteresis --dataset A"},
      {"report", ""},
      {"bench mesh-convergence", ""},
  };
  const std::string precious = "a user's file that must survive\n";
  int pairs = 0;
  for (const auto& [command, extra] : commands) {
    const std::vector<FileOption> opts = file_options(run(command + " --help").out);
    const auto count = [&](bool input) {
      return std::count_if(opts.begin(), opts.end(), [&](const FileOption& o) { return (o.type == "FILE") == input; });
    };
    ASSERT_GE(count(true), 1) << command << " lists no input file option";
    ASSERT_GE(count(false), 1) << command << " lists no output option";
    for (const FileOption& in : opts) {
      if (in.type != "FILE") continue;
      for (const FileOption& out : opts) {
        if (out.type == "FILE") continue;
        std::ofstream(path("victim")) << precious;
        std::string args = command + " " + extra;
        int other = 0;
        for (const FileOption& o : opts) {
          std::string value;
          if (&o == &in || &o == &out)
            value = path("victim");
          else if (o.required)
            value = o.type == "FILE" ? path("a.h5") : path("elsewhere-" + std::to_string(other++));
          if (value.empty()) continue;
          args += " " + (o.positional() ? value : o.name + " " + value);
        }
        const auto before = entries();
        const CliRun r = run(args);
        EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
        EXPECT_NE(r.err.find("is an input of this command (" + in.name), std::string::npos) << args << "\n" << r.err;
        EXPECT_EQ(slurp(path("victim")), precious) << args << ": the input was overwritten";
        EXPECT_EQ(entries(), before) << args << ": something was written";
        ++pairs;
      }
    }
  }
  EXPECT_GE(pairs, 30);  // the table is not vacuous: 11 commands, their inputs x outputs
}

TEST_F(Hostile, Class1_TheScenesSurfaceFileIsAnInputOfTheSweep) {
  std::ofstream(path("scene.json")) << "{\"surface\": {\"size\": 16, \"dx\": 1.875e-3, \"h0\": 1e-4}}";
  expect_one_line("sweep-coverage --scene " + path("scene.json") + " --model hysteresis --coverages 0 --out " +
                      path("r.h5") + " --csv " + path("scene.json"),
                  "is an input of this command (--scene");
}

// ---- class 2: special files --------------------------------------------------------------------

TEST_F(Hostile, Class2_SpecialFilesAreNeverReplacedNorReadAsFiles) {
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0644), 0);
  expect_one_line("fill " + path("a.h5") + " --limit -o " + path("fifo"), "FIFO");
  struct stat st {};
  ASSERT_EQ(::lstat(path("fifo").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
  // A character device (null's numbers) made in the scratch folder, so that a binary that does
  // replace it harms nothing: /dev/null itself was replaced by the former main's binary.
  if (::mknod(path("chardev").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) {
    expect_one_line("analyze " + path("a.h5") + " --json " + path("chardev"), "character device");
    ASSERT_EQ(::lstat(path("chardev").c_str(), &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode)) << "the device node was replaced";
  }
  // A FIFO or a process substitution as an input: refused in one line, never a hang (timeout).
  expect_one_line("analyze " + path("fifo"), "not a regular file");
  // A process substitution (std::system runs sh, which has none: through bash).
  const std::string bash = "bash -c 'timeout 20 " + std::string(WETROAD_BIN) + " friction " + path("a.h5") +
                           " --compound <(cat /dev/null)' 2>" + path("bash-err.txt");
  const int status = std::system(bash.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 2) << slurp(path("bash-err.txt"));
  EXPECT_NE(slurp(path("bash-err.txt")).find("not a regular file"), std::string::npos) << slurp(path("bash-err.txt"));
}

// ---- class 3: concurrent runs on one set of outputs ---------------------------------------------

TEST_F(Hostile, Class3_TwoRunsOnOneOutputSetNeverMixTheirFiles) {
  // Every rename delayed at random (tests/slow_rename.c), so that the two commits interleave.
  const char* other = std::getenv("WETROAD_TEST_BIN");
  const std::string fill = std::string("LD_PRELOAD=") + SLOW_RENAME_LIB + " ASAN_OPTIONS=verify_asan_link_order=0 " +
                           (other ? other : WETROAD_BIN) + " fill ";
  const std::string o = " --limit -q -o " + path("w.h5") + " --json " + path("w.json");
  int mixed = 0;
  for (int round = 0; round < 30; ++round) {
    std::thread t([&] { std::system((fill + path("a.h5") + o).c_str()); });
    const int status = std::system((fill + path("b.h5") + o).c_str());
    t.join();
    ASSERT_EQ(WEXITSTATUS(status), 0);
    // Which run wrote each file: the surface its provenance names.
    const auto surface_of = [](const nlohmann::json& provenance) { return provenance["inputs"]["surface"].get<std::string>(); };
    const std::string in_json = surface_of(nlohmann::json::parse(slurp(path("w.json")))["provenance"]);
    const std::string in_h5 = surface_of(nlohmann::json::parse(*wr::Hdf5Reader(path("w.h5")).attr_string("/", "provenance")));
    mixed += in_json != in_h5;
  }
  EXPECT_EQ(mixed, 0) << "rounds with the HDF5 of one run beside the JSON of the other";
}

// ---- class 5: a wet file belongs to its dry surface ----------------------------------------------

TEST_F(Hostile, Class5_AWetFileIsTiedToItsDrySurface) {
  ASSERT_EQ(run("fill " + path("a.h5") + " --limit -q -o " + path("wet.h5")).code, 0);
  ASSERT_EQ(run("friction " + path("a.h5") + " --wet " + path("wet.h5") + " -q").code, 0);
  expect_one_line("friction " + path("b.h5") + " --wet " + path("wet.h5"), "another surface");
  expect_one_line("contact --surface " + path("b.h5") + " --wet " + path("wet.h5") + " --model spectral --uz 1e-5 -q",
                  "another surface");
  expect_one_line("friction " + path("a.h5") + " --wet " + path("b.h5"), "no /water_depth");
  ASSERT_EQ(run("synth --size 12 --dx 1.875e-3 --h0 1e-4 -q -o " + path("small.h5")).code, 0);
  expect_one_line("friction " + path("small.h5") + " --wet " + path("wet.h5"), "another surface");
  // A hand-made file with the right tie but negative depths.
  {
    wr::Hdf5Writer w(path("neg.h5"));
    std::vector<double> h(16 * 16, 0.0), d(16 * 16, -1e-4);
    for (const char* name : {"/height", "/ground"}) w.write_matrix(name, h.data(), 16, 16);
    w.write_matrix("/water_depth", d.data(), 16, 16);
    w.write_attr("/", "dry_surface_sha256", wr::sha256_file_hex(path("a.h5")));
    w.commit();
  }
  expect_one_line("friction " + path("a.h5") + " --wet " + path("neg.h5"), "water depths are finite and >= 0");
}

// ---- class 6: nothing to report, nothing reported -------------------------------------------------

TEST_F(Hostile, Class6_NoFrictionWithoutContactAndNoNonFiniteNumbers) {
  const CliRun r = run("contact --surface " + path("a.h5") + " --problem shear --uz 1e-6 --ux 1e-3 --steps 1 --shear-steps 2");
  EXPECT_EQ(r.out.find("mu >="), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("mu ="), std::string::npos) << r.out;
  if (r.code == 0) EXPECT_NE(r.out.find("no friction without contact"), std::string::npos) << r.out;
  make_h5("flat.h5", "height", {16, 16}, 1e-3, true, 0.0);
  set_attr("flat.h5", "height", "periodic", 1.0);
  expect_one_line("contact --surface " + path("flat.h5") + " --model analytic --pressure 1e4", "is flat");
  expect_one_line("sweep-roughness --dataset A --values 1000 --model hysteresis --out " + path("r.h5"), "no road texture");
}

// ---- class 7: no option silently ignored ----------------------------------------------------------

TEST_F(Hostile, Class7_OptionsAreHonouredOrRefusedByName) {
  const std::string a = path("a.h5");
  for (const std::string opt : {"--unit um", "--dx 1e-3", "--periodic", "--points", "--dy 1e-3"})
    expect_one_line("analyze " + a + " " + opt, opt.substr(0, opt.find(' ')) + " applies to plain-text grids");
  const std::string sweep = "sweep-coverage --surface " + a + " --model hysteresis --out " + path("r.h5");
  expect_one_line(sweep + " --count 3 --coverages 0 0.1", "--count");
  expect_one_line(sweep + " --max-coverage 0.5", "--max-coverage");
  expect_one_line("fill " + a + " --limit -o " + path("w.h5") + " --dmax 1e-3", "--dmax");
  for (const std::string opt : {"--steps 3", "--refine 2", "--E 1e6", "--thickness inf"})
    expect_one_line(sweep + " --coverages 0 " + opt, opt.substr(0, opt.find(' ')));
  expect_one_line("sweep-coverage --surface " + a + " --uz 1e-3 --ux 1e-3 --coverages 0 --out " + path("r.h5") +
                      " --compound x.json",
                  "--compound");
  std::ofstream(path("typo.json")) << "{\"surface\": {\"size\": 16, \"hurts\": 0.5}}";
  expect_one_line("synth --scene " + path("typo.json") + " -o " + path("s.h5"), "\"hurts\"");
}

// ---- class 8: one range of seeds ------------------------------------------------------------------

TEST_F(Hostile, Class8_SeedsWetroadWritesItCanReadBack) {
  for (const std::string seed : {"-1", "9223372036854775808", "18446744073709551615", "9007199254740992"})
    expect_one_line("synth --size 16 --seed " + seed + " -o " + path("s.h5"), "--seed");
  ASSERT_EQ(run("synth --size 16 --dx 1e-3 --h0 1e-4 -q --seed 9007199254740991 -o " + path("s.h5")).code, 0);
  EXPECT_EQ(run("analyze " + path("s.h5") + " -q").code, 0);
  EXPECT_EQ(run("fill " + path("s.h5") + " --limit -q -o " + path("w.h5")).code, 0);
  expect_one_line("sweep-coverage --size 16 --seed 9007199254740991 --realizations 2 --model hysteresis --coverages 0 "
                  "--out " + path("r.h5"), "--seed");
}

// ---- class 9: bounded before work -----------------------------------------------------------------

TEST_F(Hostile, Class9_AbsurdSpacingsAndCountsAreRefusedBeforeWork) {
  for (double dx : {1e-300, 4.9e-324, 1e-12, 1e3}) {
    make_h5("tiny.h5", "height", {16, 16}, dx);
    expect_one_line("contact --surface " + path("tiny.h5") + " --uz 1e-6 -q", "outside 1e-09 ... 1 m");
  }
  expect_one_line("bench spectral --loads 0", "--loads");
  expect_one_line("bench hertz --meshes 0", "--meshes");
}

// ---- class 10 and 12: internal errors and unchecked values -----------------------------------------

TEST_F(Hostile, Class10And12_EveryBadValueIsOneLineAndExit2) {
  const std::string a = path("a.h5");
  fs::create_directories(path("dir"));
  std::ofstream(path("grid.txt")) << "1 2 3\n4 5 6\n7 8 9\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"friction " + a + " --compound " + path("dir"), "is a folder"},
      {"analyze " + path("grid.txt") + " --dx 1e308", "outside 1e-09 ... 1 m"},
      {"contact --surface " + a + " --E 1e308 --uz 1e-6", "--E"},
      {"bench water --size 1", "--size"},
      {"friction " + a + " --threads -1", "--threads"},
      {"synth --size 16 --threads -1 -o " + path("s.h5"), "--threads"},
      {"sweep-coverage --surface " + a + " --model hysteresis --coverages 0 --threads -1 --out " + path("r.h5"), "--threads"},
      {"report --sweep " + a + " --ifi-a nan --ifi-b 1 -o " + path("r.html"), "--ifi-a"},
      {"report --sweep " + a + " --ifi-a 1 --ifi-b inf -o " + path("r.html"), "--ifi-b"},
      {"report --sweep " + a + " --ifi-a 1 --ifi-b 1 --ifi-c 1 --ifi-tx -1 -o " + path("r.html"), "--ifi-tx"},
      {"friction " + a + " --temperature 1e308", "--temperature"},
      {"sweep-roughness --dataset A --values 1e-4 2e-4 1e-4 --model hysteresis --out " + path("r.h5"), "twice"},
      {"synth --size 16 --q1-fraction 1e-300 -o " + path("s.h5"), "--q1-fraction"},
      {"bench speed --repeat -1", "--repeat"},
      {"bench coverage --seeds -1", "--seeds"},
      {"bench speed --sizes 0", "--sizes"},
      {"sweep-coverage --surface " + a + " --model bogus --coverages 0 --out " + path("r.h5"), "--model"},
      {"fill " + a + " --limit -o \"\"", "--output"},
  };
  for (const auto& [args, needle] : cases) expect_one_line(args, needle);
  // A sweep record whose numbers were nulled after it was written: one line naming the file.
  ASSERT_EQ(run("sweep-coverage --surface " + a + " --model hysteresis --coverages 0 0.2 -q --out " + path("s.h5")).code, 0);
  {
    const wr::Hdf5Reader in(path("s.h5"));
    nlohmann::json sweep = nlohmann::json::parse(in.read_text("/sweep"));
    for (auto& row : sweep["table"]) row["failed"] = nullptr, row["mu_peak"]["n"] = nullptr;
    wr::Hdf5Writer out(path("nulls.h5"));
    out.write_attr("/", "kind", *in.attr_string("/", "kind"));
    out.write_text("/sweep", sweep.dump());
    out.commit();
  }
  expect_one_line("report --sweep " + path("nulls.h5") + " -o " + path("r.html"), "nulls.h5: a field is missing");
  for (double periodic : {0.5, 2.0}) {
    make_h5("p.h5", "height", {16, 16}, 1e-3);
    set_attr("p.h5", "height", "periodic", periodic);
    expect_one_line("analyze " + path("p.h5"), "periodic");
  }
}

// ---- class 11: staging files removed however a run ends --------------------------------------------

TEST_F(Hostile, Class11_InterruptedRunsLeaveNoStagingFiles) {
  for (const auto& [sig, code] : std::map<int, int>{{SIGINT, 130}, {SIGTERM, 143}}) {
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      const std::string out = path("big.h5");
      ::execl(WETROAD_BIN, WETROAD_BIN, "synth", "--size", "4096", "-q", "-o", out.c_str(), nullptr);
      ::_exit(127);
    }
    // Wait for the staging file, then interrupt.
    bool staged = false;
    for (int i = 0; i < 400 && !staged; ++i) {
      for (const auto& n : entries()) staged |= n.rfind(".big.h5.tmp-", 0) == 0;
      if (!staged) std::this_thread::sleep_for(std::chrono::milliseconds(25));
    }
    ASSERT_TRUE(staged);
    ::kill(pid, sig);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), code);
    for (const auto& n : entries()) EXPECT_EQ(n.find(".tmp-"), std::string::npos) << n << " left behind";
  }
  // A staging file of a process that no longer exists (killed outright) is removed by the next run.
  pid_t dead = 0;
  if (const pid_t p = ::fork(); p == 0) {
    ::_exit(0);
  } else {
    ::waitpid(p, nullptr, 0);
    dead = p;
  }
  const std::string stale = ".w.h5.tmp-" + std::to_string(dead) + "-0", live = ".w.h5.tmp-" + std::to_string(::getpid()) + "-0";
  std::ofstream(path(stale)) << "x";
  std::ofstream(path(live)) << "x";
  ASSERT_EQ(run("fill " + path("a.h5") + " --limit -q -o " + path("w.h5")).code, 0);
  EXPECT_FALSE(fs::exists(path(stale)));
  EXPECT_TRUE(fs::exists(path(live))) << "a live process's staging file was removed";
  // The same inside a sweep's checkpoint folder, whose run records are staged beside each other.
  const std::string sweep = "sweep-coverage --surface " + path("a.h5") + " --model hysteresis --coverages 0 -q --out " +
                            path("r.h5");
  ASSERT_EQ(run(sweep).code, 0);
  const std::string record = path("r.h5.runs/.run-0001.json.tmp-" + std::to_string(dead) + "-3");
  std::ofstream(record) << "{";
  ASSERT_EQ(run(sweep + " --resume").code, 0);
  EXPECT_FALSE(fs::exists(record));
}

// ---- class 13: messages that say what is wrong ----------------------------------------------------

TEST_F(Hostile, Class13_MessagesNameWhatIsWrong) {
  // An HDF5 file with a 512-byte user block is HDF5.
  const hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
  H5Pset_userblock(fcpl, 512);
  const hid_t f = H5Fcreate(path("ub.h5").c_str(), H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
  H5Pclose(fcpl);
  H5Fclose(f);
  const CliRun r = run("analyze " + path("ub.h5"));
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err.find("not an HDF5"), std::string::npos) << r.err;
  // A resumed sweep given one more coverage names the list, not "coverages.-".
  const std::string sweep = "sweep-coverage --surface " + path("a.h5") + " --model hysteresis -q --out " + path("r.h5");
  ASSERT_EQ(run(sweep + " --coverages 0 0.2").code, 0);
  const CliRun resumed = run(sweep + " --coverages 0 0.2 0.4 --resume");
  EXPECT_EQ(resumed.code, 2);
  EXPECT_NE(resumed.err.find("coverages is [0.0,0.2,0.4], was [0.0,0.2]"), std::string::npos) << resumed.err;
  EXPECT_EQ(resumed.err.find("absent"), std::string::npos) << resumed.err;
  // A chart folder whose name holds a quote: the charts land there (gnuplot is run through sh).
  const CliRun charts = run(sweep + "2 --coverages 0 0.2 --plots \"" + path("it's") + "\"");
  EXPECT_EQ(charts.code, 0) << charts.err;
  ASSERT_TRUE(fs::is_directory(path("it's"))) << charts.err;
  EXPECT_FALSE(fs::is_empty(path("it's"))) << charts.err;
}

}  // namespace
