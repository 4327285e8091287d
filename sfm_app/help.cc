#include "sfm_app/help.h"

#include <glog/logging.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace sfm {
namespace {

// Flag and default are padded to this column, so the help lines start together.
constexpr std::size_t kHelpColumn = 40;

}  // namespace

std::string ReadableDefault(const gflags::CommandLineFlagInfo& info) {
  if (info.type == "double") {
    char text[32];
    std::snprintf(text, sizeof(text), "%.6g", std::strtod(info.default_value.c_str(), nullptr));
    return text;
  }
  if (info.type == "string" && info.default_value.empty()) return "''";
  return info.default_value;
}

std::string ProgramHelp(const std::string& usage, const std::vector<HelpFlag>& table,
                        const std::string& footer) {
  std::string text = usage + "\n";
  std::string group;
  for (const HelpFlag& row : table) {
    gflags::CommandLineFlagInfo info;
    CHECK(gflags::GetCommandLineFlagInfo(row.name, &info)) << "help table: no flag --" << row.name;
    if (row.group != group) {
      group = row.group;
      text += "\n" + group + ":\n";
    }
    std::string line = "  --" + info.name + "=" + ReadableDefault(info);
    line += line.size() + 2 <= kHelpColumn ? std::string(kHelpColumn - line.size(), ' ') : std::string("  ");
    text += line + row.help + "\n";
  }
  text +=
      "\n" + footer + "Every flag with its full description, the logging library's included: --helpfull.\n";
  return text;
}

void ParseFlagsWithProgramHelp(int* argc, char*** argv, const std::string& usage,
                               const std::vector<HelpFlag>& table, const std::string& footer) {
  gflags::SetUsageMessage(usage);
  gflags::ParseCommandLineNonHelpFlags(argc, argv, /*remove_flags=*/true);
  std::string help;
  if (gflags::GetCommandLineOption("help", &help) && help == "true") {
    std::fputs(ProgramHelp(usage, table, footer).c_str(), stdout);
    std::exit(0);
  }
  gflags::HandleCommandLineHelpFlags();
}

}  // namespace sfm
