#pragma once
// Which options name files, and the checks on them that every command shares, run after parsing
// and before any work. Options are marked where they are declared: type name FILE (an input),
// OUTPUT (a file written) or FOLDER (a folder of outputs); --help shows the marks.
//
// check_file_options(sub) throws InputError (one line, exit 2) when
//  - an output names the same file as any input of the command (any spelling, hard or symbolic
//    link): writing it would destroy the input;
//  - an input exists but is a folder, or a FIFO, device or socket (readers seek and read twice:
//    a pipe would hang or be half read);
// and recurses into the parsed subcommands (bench's). Outputs that are special files are refused by
// OutputSet::add, where every output passes.
#include <CLI/CLI.hpp>

namespace wr::app {

void check_file_options(const CLI::App& sub);

}  // namespace wr::app
