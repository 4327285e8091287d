// --help for users: a program's own flags grouped by stage, each with a readable default and one
// line, instead of gflags' listing of every linked file's flags under its build path (which
// --helpfull keeps).
#pragma once

#include <gflags/gflags.h>

#include <string>
#include <vector>

namespace sfm {

// One row of a program's help table: the flag, the heading it is listed under (rows of one group
// are consecutive) and one line of help. The table is the order --help prints.
struct HelpFlag {
  const char* name;
  const char* group;
  const char* help;
};

// A flag's default as a user reads it: doubles with 6 significant digits ("0.844", not
// "0.84399999999999997"), an empty string as '', the rest as gflags stores them.
std::string ReadableDefault(const gflags::CommandLineFlagInfo& info);

// The text --help prints: `usage`, then each group's heading and its flags, one line each
// ("  --threads=8   Threads for the bundle adjustment."), then `footer` and a line naming --helpfull.
// A name in `table` that is no flag of the program is a programmer error (CHECK).
std::string ProgramHelp(const std::string& usage, const std::vector<HelpFlag>& table,
                        const std::string& footer);

// gflags::ParseCommandLineFlags with --help answered by ProgramHelp on stdout (exit 0); --helpfull,
// --helpxml, --helpmatch, --version and the others stay gflags'. Sets `usage` as the usage message.
void ParseFlagsWithProgramHelp(int* argc, char*** argv, const std::string& usage,
                               const std::vector<HelpFlag>& table, const std::string& footer);

}  // namespace sfm
