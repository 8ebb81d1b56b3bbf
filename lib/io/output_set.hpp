#pragma once
// The files one command writes, checked before the work and committed together after it.
//
// Contract:
//  - input(path) names a file the command reads; no output may be that file, whatever the
//    spelling ("./a.h5", "dir/../a.h5") or a symbolic link to it.
//  - add(option, path) declares an output before any work: it throws InputError naming the
//    option and the path when the path is an input, another output, a directory, or cannot be
//    created (its directory missing or not writable: an empty staging file is made next to it
//    to find out). It returns that staging path: the writer writes there.
//  - add_directory(option, dir) declares a folder of outputs (charts): the writer fills the
//    returned staging folder; commit moves its files into `dir` (created if missing).
//  - commit() renames every staged output onto its final name, in the order declared; only
//    then do outputs appear. Destroyed without commit() (an error, a numerical failure), the
//    set removes what it staged: a command leaves all of its outputs or none.
//  - A set made with `writes = false` (MPI ranks other than 0) checks the same, stages nothing,
//    and returns the final paths.
#include <string>
#include <vector>

namespace wr {

class OutputSet {
 public:
  explicit OutputSet(bool writes = true) : writes_(writes) {}
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // Records an input file (ignored when empty or absent: the reader reports that).
  void input(const std::string& path);
  // Declares an output file; returns the path to write. An empty path returns "" (no output).
  std::string add(const std::string& option, const std::string& path);
  // Declares an output folder; returns the folder to write into ("" when `dir` is empty).
  std::string add_directory(const std::string& option, const std::string& dir);
  // Withdraws the output declared under `option` (nothing to write after all): its staged file
  // is removed and commit() skips it.
  void discard(const std::string& option);
  // Makes every staged output appear under its final name; throws InputError on failure.
  void commit();

 private:
  struct Entry {
    std::string option, final_path, staged;
    bool directory = false;
  };
  void check_distinct(const std::string& option, const std::string& path) const;
  std::string keep(Entry e);  // records a staged output; returns the path to write

  bool writes_;
  bool committed_ = false;
  std::vector<std::string> inputs_;
  std::vector<Entry> outputs_;
};

// True when `a` and `b` name the same file (existing: same inode; otherwise the same
// normalised absolute path).
bool same_file(const std::string& a, const std::string& b);

}  // namespace wr
