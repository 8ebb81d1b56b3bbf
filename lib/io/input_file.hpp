#pragma once
// A whole input file read into memory, for the small text inputs parsed from memory (compound
// JSON, measured skid-number CSV): the parsers are fuzzed on bytes, the files only opened here.
#include <string>

namespace wr {

// The bytes of `path`. InputError(path, ...) naming `what` (e.g. "compound file") when it is a
// folder, a FIFO or device (refused before opening: a FIFO would block), or cannot be read.
std::string read_input_file(const std::string& path, const std::string& what);

}  // namespace wr
